#!/usr/bin/python3
"""The Python module's batch speed beside the C++ batch kernels' (docs/python.md): a measurement, not a test.

    PYTHONPATH=build/python /usr/bin/python3 tests/python/measure_batch.py build/bin/crankcheck_python_batch_bench

Runs bench/python_batch_bench.cc (Google Benchmark, median of --repetitions runs) and times the same work from Python
on the same scenes and the same 1e6 angles (phi_i = i x 1e-5 rad), median of as many runs:
  kernels   Scene.evaluate(phi, quantities=<what the kernels compute>) beside BM_PythonBatchKernels with outputs
            allocated per call as NumPy allocates them (fresh:1)
  kernels, out=   the same writing into the arrays of an earlier call (evaluate(..., out=r)) beside the kernels writing
            into outputs allocated once (fresh:0): the kernels alone, no fresh memory to fault in and zero
  all       Scene.evaluate(phi), every quantity of eval, beside BM_PythonBatchEvaluate (the same C++ function the
            module calls, without Python)
and prints each Python time over the C++ time, both as wall time and as CPU time of the process (Google Benchmark's
cpu_time; Python's time.process_time): on a busy machine the CPU times are the steadier comparison.
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import time

import numpy as np

import crankcheck

KERNEL_QUANTITIES = ["U", "Q", "drive_torque", "bearing_force", "shaking_force", "shaking_moment", "x_p", "v_p", "a_p",
                     "crank_pin_force", "wrist_pin_force", "wall_force"]
SCENES = ["single_cylinder", "inline4_four_stroke"]  # scene:0, scene:1 in the benchmark's rows
ANGLES = 1_000_000


def median_seconds(f, repetitions):
    """(wall, cpu) medians [s]."""
    f()  # warm: first-touch of the allocator's memory, Highway's dispatch
    wall, cpu = [], []
    for _ in range(repetitions):
        t, c = time.perf_counter(), time.process_time()
        f()
        wall.append(time.perf_counter() - t)
        cpu.append(time.process_time() - c)
    return statistics.median(wall), statistics.median(cpu)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("bench", help="build/bin/crankcheck_python_batch_bench")
    parser.add_argument("--scenes", default=os.path.join(os.path.dirname(__file__), "..", "..", "scenes"))
    parser.add_argument("--repetitions", type=int, default=7)
    args = parser.parse_args()

    run = subprocess.run([args.bench, "--benchmark_format=json", "--benchmark_repetitions=%d" % args.repetitions,
                          "--benchmark_report_aggregates_only=true"], capture_output=True, text=True, check=True)
    cpp = {b["run_name"]: (b["real_time"] / 1e3, b["cpu_time"] / 1e3) for b in json.loads(run.stdout)["benchmarks"]
           if b.get("aggregate_name") == "median"}  # [s]; the rows are in milliseconds

    phi = np.arange(ANGLES, dtype=float) * 1e-5  # as the benchmark's angles
    print("batch target %s, %d angles, median of %d runs each; wall and CPU time [ms]" % (
        crankcheck.batch_target(), ANGLES, args.repetitions))
    print("%-20s %-14s %10s %10s %6s %10s %10s %6s   %s" % ("scene", "work", "Python", "C++", "ratio", "Python cpu",
                                                          "C++ cpu", "ratio", "C++ row"))
    for index, name in enumerate(SCENES):
        scene = crankcheck.Scene.load(os.path.join(args.scenes, name + ".toml"))
        assert scene.batch_kernels
        py_kernels = median_seconds(lambda: scene.evaluate(phi, quantities=KERNEL_QUANTITIES), args.repetitions)
        reused = scene.evaluate(phi, quantities=KERNEL_QUANTITIES)
        py_reused = median_seconds(lambda: scene.evaluate(phi, quantities=KERNEL_QUANTITIES, out=reused),
                                   args.repetitions)
        py_all = median_seconds(lambda: scene.evaluate(phi), args.repetitions)
        rows = [("kernels", py_kernels, "BM_PythonBatchKernels/scene:%d/fresh:1/real_time" % index),
                ("kernels, out=", py_reused, "BM_PythonBatchKernels/scene:%d/fresh:0/real_time" % index),
                ("all", py_all, "BM_PythonBatchEvaluate/scene:%d/fresh:1/real_time" % index)]
        for work, (wall, cpu), row in rows:
            cw, cc = cpp[row]
            print("%-20s %-14s %10.1f %10.1f %6.2f %10.1f %10.1f %6.2f   %s" % (
                name, work, wall * 1e3, cw * 1e3, wall / cw, cpu * 1e3, cc * 1e3, cpu / cc, row.replace("/real_time", "")))
    return 0


if __name__ == "__main__":
    sys.exit(main())
