"""`cmake --install` puts the package into PREFIX/lib/pythonX.Y/dist-packages (Debian; site-packages elsewhere), where
it imports and runs without the build tree: evaluate, a grade and a grade of runs with their reports (the relay program and the
report's gnuplot scripts found from the package's own place)."""
import os
import subprocess
import sys
import sysconfig
import textwrap

import pytest

BUILD_DIR = os.environ.get("CRANKCHECK_BUILD_DIR", "")


@pytest.mark.skipif(not BUILD_DIR, reason="CRANKCHECK_BUILD_DIR is not set")
def test_the_installed_package_runs(tmp_path):
    prefix = tmp_path / "prefix"
    subprocess.run(["cmake", "--install", BUILD_DIR, "--prefix", str(prefix)], check=True, capture_output=True)
    site = "dist-packages" if "dist-packages" in sysconfig.get_path("platlib") else "site-packages"
    package = prefix / "lib" / ("python%d.%d" % sys.version_info[:2]) / site
    assert (package / "crankcheck" / "__init__.py").is_file()
    assert os.access(package / "crankcheck" / "crankcheck-grade-relay", os.X_OK)
    script = textwrap.dedent("""
        import numpy as np, crankcheck, sys
        assert crankcheck.__file__.startswith(sys.argv[1]), crankcheck.__file__
        scene = crankcheck.Scene.load(sys.argv[2] + "/share/crankcheck/scenes/single_cylinder.toml")
        assert scene.evaluate(np.linspace(0, 1, 10), engine="mujoco")["Q"].shape == (10,)
        result = crankcheck.grade(lambda s, phi: s.evaluate(phi), [scene], quick=True, out=sys.argv[3])
        assert result.passed, result
        print(result.report)
        # The time-stepped grade from the install: the installed RK4 example answering as a function.
        import json, subprocess
        rk4 = sys.argv[2] + "/share/crankcheck/examples/free_run/rk4_reduced.py"
        def run(request):
            out = subprocess.run([sys.executable, rk4], input=json.dumps(request) + "\\n", capture_output=True,
                                 text=True, check=True).stdout
            return json.loads(out)
        runs = crankcheck.grade_free_run(run, [scene], revolutions=2, quick=True, out=sys.argv[3] + "-free-run")
        assert runs.passed, runs.measures
    """)
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "CRANKCHECK_REPORTS_DIR")}
    env["PYTHONPATH"] = str(package)
    run = subprocess.run([sys.executable, "-c", script, str(package), str(prefix), str(tmp_path / "report")],
                         env=env, cwd=tmp_path, capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    assert (tmp_path / "report" / "index.html").is_file()
    assert (tmp_path / "report" / "grade_error_vs_lambda.svg").is_file()
    assert (tmp_path / "report-free-run" / "free_run_error_vs_time.svg").is_file()
