"""crankcheck.grade_free_run: a Python function's time-stepped runs graded by `crankcheck grade --free-run`'s own
measures, tolerances and refusals, held against the CLI grading the example program that computes the same run."""
import csv
import json
import os
import subprocess
import sys
import time

import numpy as np
import pytest

import crankcheck
from conftest import EXAMPLES_DIR, SCENES_DIR, run_cli

SINGLE = os.path.join(SCENES_DIR, "single_cylinder.toml")
RK4 = os.path.join(os.path.dirname(EXAMPLES_DIR), "free_run", "rk4_reduced.py")


def constant_speed(request):
    """A run that keeps the protocol but not the physics: the crank at exactly omega0, as columns."""
    t = np.arange(0.0, request["t_end"] + 0.5 * request["output_interval"], request["output_interval"])
    t[-1] = request["t_end"]
    return {"t": t, "phi": request["omega0"] * t, "omega": np.full_like(t, request["omega0"])}


def rk4_example(request):
    """The shipped RK4 program (examples/free_run/rk4_reduced.py) answering the request, as a function."""
    done = subprocess.run([sys.executable, RK4], input=json.dumps(request) + "\n", capture_output=True, text=True,
                          check=True, timeout=120)
    return json.loads(done.stdout)


def test_a_constant_speed_run_is_graded_and_fails_on_delta():
    r = crankcheck.grade_free_run(constant_speed, [SINGLE], revolutions=3, quick=True)
    assert r.exit_status == 1 and not r.passed
    assert r.verdict("delta") == "FAIL"
    assert r.verdict("energy_trend") == "pass"  # E at phi = 2 pi k is the same state every turn
    assert {row["engine"] for row in r.engines} >= {"simbody"}  # the engines' own runs beside it


def test_the_example_passes_as_a_function_as_the_cli_grades_it(tmp_path):
    r = crankcheck.grade_free_run(rk4_example, [SINGLE], revolutions=3, quick=True, out=str(tmp_path / "py"))
    assert r.exit_status == 0, [m for m in r.measures if m["verdict"] != "pass"]
    assert os.path.exists(r.report)
    # The CLI grading the same program: the same measures to the last digit (the same code grades both).
    out = tmp_path / "cli"
    status, _, err = run_cli("grade", "--free-run", SINGLE, "--revolutions", "3", "--quick", "--out", str(out), "--",
                             sys.executable, RK4, check=False)
    assert status == 0, err
    with open(out / "data" / "free_run_measures.csv") as f:
        table = list(csv.reader(f))
    columns = [c.split(" [")[0] for c in table[0]]
    cli = {row[columns.index("measure")]: float(row[columns.index("error")]) for row in table[1:]}
    assert {m["measure"]: m["error"] for m in r.measures} == cli


def test_a_broken_run_is_refused():
    def with_nan(request):
        run = constant_speed(request)
        run["omega"][5] = float("nan")
        return run
    with pytest.raises(RuntimeError, match="is not JSON"):
        crankcheck.grade_free_run(with_nan, [SINGLE], revolutions=2, quick=True)

    def backwards(request):
        run = constant_speed(request)
        run["t"][7] = run["t"][3]
        return run
    with pytest.raises(RuntimeError, match="time must increase"):
        crankcheck.grade_free_run(backwards, [SINGLE], revolutions=2, quick=True)

    def too_few(request):
        return {"samples": [{"t": 0.0, "phi": 0.0, "omega": request["omega0"]}]}
    with pytest.raises(RuntimeError, match="too few samples"):
        crankcheck.grade_free_run(too_few, [SINGLE], revolutions=2, quick=True)


def test_omega_t_far_outside_the_run_is_refused_like_values_t():
    # Issue 58: an omega_t 1e6 s past its sample was graded (an "exact" phase of 1.1e41 rad); the same fault in
    # values_t was refused. Both are a broken run now.
    def far(key):
        def run(request):
            r = constant_speed(request)
            r[key] = [t + 1e6 for t in r["t"]]
            return r
        return run
    with pytest.raises(RuntimeError, match=r"omega_t is 1e\+06 s, outside the samples either side"):
        crankcheck.grade_free_run(far("omega_t"), [SINGLE], revolutions=2, quick=True)
    with pytest.raises(RuntimeError, match=r"values_t is 1e\+06 s, outside the run"):
        crankcheck.grade_free_run(far("values_t"), [SINGLE], revolutions=2, quick=True)


def test_crankcheck_s_own_work_past_the_limit_is_refused_before_the_function_runs():
    # Issue 58: revolutions=100000 kept crankcheck measuring for hours after the function answered.
    calls = []

    def counted(request):
        calls.append(request["case"])
        return constant_speed(request)
    start = time.monotonic()
    with pytest.raises(ValueError, match=r"revolutions: .* over 100000 revolutions.*fewer revolutions"):
        crankcheck.grade_free_run(counted, [SINGLE], revolutions=100000, quick=True)
    assert calls == []
    assert time.monotonic() - start < 60  # the probe is one revolution of the engines' runs: seconds
    with pytest.raises(ValueError, match="work_limit"):
        crankcheck.grade_free_run(counted, [SINGLE], work_limit=float("nan"))


def test_a_function_that_never_answers_is_interrupted():
    def stuck(request):
        time.sleep(30)
    start = time.monotonic()
    with pytest.raises(RuntimeError, match="no complete answer within 0.5 s"):
        crankcheck.grade_free_run(stuck, [SINGLE], revolutions=2, quick=True, timeout=0.5)
    assert time.monotonic() - start < 10


def test_the_function_s_own_exception_is_raised_with_the_run_named():
    def fails(request):
        raise ZeroDivisionError("my model")
    with pytest.raises(ZeroDivisionError, match="my model") as raised:
        crankcheck.grade_free_run(fails, [SINGLE], revolutions=2, quick=True)
    if hasattr(raised.value, "__notes__"):
        assert "single_cylinder_free" in raised.value.__notes__[0]


def test_bad_arguments_are_refused(tmp_path):
    with pytest.raises(TypeError):
        crankcheck.grade_free_run(constant_speed, SINGLE)
    with pytest.raises(ValueError, match="dt must be"):
        crankcheck.grade_free_run(constant_speed, [SINGLE], dt="fast")
    with pytest.raises(ValueError, match="dt_sweep needs a step"):
        crankcheck.grade_free_run(constant_speed, [SINGLE], dt="own", dt_sweep=3)
    with pytest.raises(ValueError, match="drive"):
        crankcheck.grade_free_run(constant_speed, [SINGLE], drive="pedal")
    bare = tmp_path / "bare.toml"
    text = open(SINGLE).read()
    start = text.index("[flywheel]")
    end = text.find("\n[", start + 1)
    bare.write_text(text[:start] + ("" if end < 0 else text[end + 1:]))
    with pytest.raises(crankcheck.SceneError, match=r"\[flywheel\]\.inertia"):
        crankcheck.grade_free_run(constant_speed, [str(bare)])


def test_the_default_tolerances_are_the_cli_s():
    defaults = crankcheck.free_run_tolerances()
    r = crankcheck.grade_free_run(constant_speed, [SINGLE], revolutions=2, quick=True, delta_tolerance=2.0)
    tolerance = {m["measure"]: m["tolerance"] for m in r.measures}
    assert tolerance["delta"] == 2.0  # given
    assert tolerance["energy_trend"] == defaults["energy_tolerance"]  # left at None: the CLI's default
    assert tolerance["phase"] == defaults["phase_tolerance"]


def test_a_count_or_a_switch_of_another_type_is_refused_not_read_into_one():
    # The CLI refuses --revolutions 2.9; the function must not run 2 revolutions in its place, nor read "no" as quick.
    calls = []

    def never(request):
        calls.append(request)
        return constant_speed(request)
    for kwargs, name in (({"revolutions": 2.9}, "revolutions"), ({"revolutions": True}, "revolutions"),
                         ({"revolutions": "3"}, "revolutions"), ({"dt": 1e-3, "dt_sweep": 2.0}, "dt_sweep"),
                         ({"quick": "no"}, "quick"), ({"quick": 1}, "quick")):
        args = {"revolutions": 2, "quick": True}
        args.update(kwargs)
        with pytest.raises(TypeError, match="grade_free_run: %s must be" % name):
            crankcheck.grade_free_run(never, [SINGLE], **args)
    with pytest.raises(TypeError, match="grade: quick must be True or False"):
        crankcheck.grade(lambda scene, phi: {}, [SINGLE], quick="no")
    assert calls == []
