#!/usr/bin/env python3
"""A pass-through for `crankcheck grade --free-run`: runs PROGRAM on the request it is given and keeps both sides of
the exchange, so that a test can measure the very run the grader measured.

    free_run_tee.py CAPTURE_DIR PROGRAM [ARG...]

Reads the request on stdin, hands it to PROGRAM unchanged, passes PROGRAM's stdout, stderr and exit status through,
and writes CAPTURE_DIR/<case>.request.json and CAPTURE_DIR/<case>.response.json (<case>: the request's "case").
"""
import json
import os
import subprocess
import sys


def main():
    if len(sys.argv) < 3:
        print("free_run_tee.py: usage: free_run_tee.py CAPTURE_DIR PROGRAM [ARG...]", file=sys.stderr)
        sys.exit(2)
    capture, program = sys.argv[1], sys.argv[2:]
    request = sys.stdin.buffer.read()
    done = subprocess.run(program, input=request, capture_output=True)
    case = json.loads(request)["case"]
    with open(os.path.join(capture, case + ".request.json"), "wb") as f:
        f.write(request)
    with open(os.path.join(capture, case + ".response.json"), "wb") as f:
        f.write(done.stdout)
    sys.stdout.buffer.write(done.stdout)
    sys.stdout.flush()
    sys.stderr.buffer.write(done.stderr)
    sys.exit(done.returncode)


if __name__ == "__main__":
    main()
