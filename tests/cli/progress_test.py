#!/usr/bin/python3
"""`crankcheck validate`'s progress line, as a user at a terminal sees it: stderr is a pseudo-terminal here (the
line is shown only on a terminal). Each update gives the tasks done of all, the elapsed time and an estimate of the
time left; the last says every task is done with nothing left, and the line is cleared at the end.

Usage (ctest, label cli): progress_test.py CRANKCHECK. Runs `validate --quick SCENE --parts PARTS` (the example single
cylinder, one family's cross-check and three parts: 15 tasks on two threads, 0.3 s; every part took 4 s, issue 28: the
line's form, one update per task and its end do not depend on the campaign's size) in a fresh mkdtemp folder, removed
at the end; the program is started without a shell.
"""

import os
import pty
import re
import shutil
import subprocess
import sys
import tempfile
import unittest

CRANKCHECK = None
SCENE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scenes", "single_cylinder.toml")
UPDATE = re.compile(r"\r\x1b\[K\[ *(\d+)/(\d+)\] (\d+s|\d+m\d\ds|\d+h\d\dm) elapsed, about (\d+s|\d+m\d\ds|\d+h\d\dm) left: ")


class ProgressTest(unittest.TestCase):
    def test_progress_shows_elapsed_and_time_left(self):
        folder = tempfile.mkdtemp(prefix="crankcheck_test_")
        try:
            master, slave = pty.openpty()
            process = subprocess.Popen([CRANKCHECK, "validate", "--quick", SCENE, "--parts",
                                        "pin_load_polar,offset,error_vs_lambda", "--jobs", "2", "--out",
                                        os.path.join(folder, "report")],
                                       stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL, stderr=slave)
            os.close(slave)
            output = b""
            while True:
                try:
                    chunk = os.read(master, 65536)
                except OSError:  # EIO: the program closed the terminal
                    break
                if not chunk:
                    break
                output += chunk
            os.close(master)
            self.assertEqual(process.wait(timeout=600), 0, output.decode(errors="replace")[-2000:])
        finally:
            shutil.rmtree(folder)
        text = output.decode()
        updates = UPDATE.findall(text)
        self.assertGreater(len(updates), 10, text[-2000:])
        done = [int(d) for d, _, _, _ in updates]
        totals = {int(t) for _, t, _, _ in updates}
        self.assertEqual(len(totals), 1)
        total = totals.pop()
        self.assertEqual(sorted(done), list(range(1, total + 1)), "one update per task")
        self.assertEqual(updates[-1][0], str(total))
        self.assertEqual(updates[-1][3], "0s", "nothing left once every task is done")
        self.assertTrue(text.endswith("\r\x1b[K"), "the line is cleared at the end: " + repr(text[-200:]))


if __name__ == "__main__":
    CRANKCHECK = sys.argv.pop(1)
    unittest.main(verbosity=1)
