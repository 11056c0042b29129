"""crankcheck.grade: a Python function graded by `crankcheck grade`'s own cases, rule and report, held against the CLI
grading the example programs that compute the same things (examples/grade/)."""
import csv
import os
import re

import numpy as np
import pytest

import crankcheck
from conftest import EXAMPLES_DIR, SCENE_FILES, cli_refusal, run_cli

ANALYTIC_PROGRAM = os.environ.get("CRANKCHECK_GRADE_EXAMPLE_ANALYTIC", "")


def cli_grade(tmp_path, program, *scenes):
    """`crankcheck grade --quick --batch` of a program: (exit status, summary rows, failures) from its report."""
    out = tmp_path / "cli_report"
    status, _, err = run_cli("grade", *scenes, "--quick", "--batch", "--out", str(out), "--", *program, check=False)
    assert status in (0, 1), err

    def rows(name):
        with open(out / "data" / (name + ".csv")) as f:
            table = list(csv.reader(f))
        columns = [c.split(" [")[0] for c in table[0]]
        return [dict(zip(columns, row)) for row in table[1:]]
    return status, rows("grade_summary"), rows("grade_failures")


def by_quantity(rows):
    """The summary's rows by (quantity, regime): "all", and moving / at rest by lambda up to 0.4 and beyond."""
    return {(row["quantity"], row["regime"]): row for row in rows}


def evaluate(scene, phi):
    return scene.evaluate(phi)


def norton(scene, phi):
    """Norton's two-term piston motion, as examples/grade/norton_two_term.py computes it, for every cylinder."""
    theta = phi[:, None] + np.asarray(scene.engine.crank_angles)[None, :]
    n = crankcheck.norton_two_term(theta, scene.crank_ratio, r=scene.crank.radius, omega=scene.engine.speed)
    return {"x_p": n["x_p"], "v_p": n["v_p"], "a_p": n["a_p"]}


@pytest.mark.parametrize("scenes", ["built_in", "example_scenes"])
def test_the_analytic_engine_passes_as_the_clis_example_does(scenes, tmp_path):
    if not ANALYTIC_PROGRAM:
        pytest.skip("CRANKCHECK_GRADE_EXAMPLE_ANALYTIC is not set")
    files = SCENE_FILES if scenes == "example_scenes" else []
    result = crankcheck.grade(evaluate, files or None, quick=True)
    status, summary, failures = cli_grade(tmp_path, [ANALYTIC_PROGRAM], *files)
    assert result.exit_status == status == 0
    assert result.passed and result.failures == [] and failures == []
    cli = by_quantity(summary)
    assert [(row["quantity"], row["regime"]) for row in result.summary] == list(cli)
    for row in result.summary:
        # The same cases: the same number of values asked for; every one provided and passed by both.
        c = cli[row["quantity"], row["regime"]]
        assert row["asked"] == float(c["asked"]), row
        assert row["provided"] == row["asked"] and row["verdict"] == "pass" == c["verdict"], row
    assert result.cases > 0 and result.report is None


def test_norton_fails_where_the_clis_norton_example_fails(tmp_path):
    result = crankcheck.grade(norton, quick=True)
    status, summary, failures = cli_grade(tmp_path, ["/usr/bin/python3", os.path.join(EXAMPLES_DIR, "norton_two_term.py")])
    assert result.exit_status == status == 1 and not result.passed
    cli = by_quantity(summary)
    for row in result.summary:
        c = cli[row["quantity"], row["regime"]]
        assert (row["asked"], row["provided"], row["verdict"]) == (float(c["asked"]), float(c["provided"]), c["verdict"])
        if row["provided"] and row["regime"].startswith("moving"):
            # The same formula computed twice (NumPy here, math there; angles from the CLI's radians and from
            # math.radians): the errors at speed, of order 1e-3 of the scale, agree far beyond rounding of the values.
            for column in ("largest_rel_error_simbody", "rel_error_at_worst_ratio"):
                assert row[column] == pytest.approx(float(c[column]), rel=1e-9), column
            # Where: the same case, or one tied with it. Norton's error relative to r omega^2 depends on lambda and the
            # angle alone, so every scene at lambda = 0.9 has the same worst values to rounding (0.0890809627472250 of
            # the scale), and the last digits of the two computations pick among them. Each side's case must reach,
            # in the other side's failures, the worst ratio and the largest error it reports.
            for mine, theirs, their_failures in ((row, c, failures), (c, row, result.failures)):
                for case_key, value, of in (("where_case", "worst_ratio", lambda f: float(f["rel_error"]) / float(f["tolerance_rel"])),
                                            ("largest_where_case", "largest_rel_error", lambda f: float(f["rel_error"]))):
                    reached = [of(f) for f in their_failures if f["case"] == mine[case_key] and f["quantity"] == row["quantity"]]
                    assert reached and max(reached) == pytest.approx(float(theirs[value]), rel=1e-9), (case_key, mine[case_key])
    assert result.verdict("a_p") == "FAIL" and result.verdict("U") == "not provided"
    # The summary names what it shows: the largest error, and the error where error / tolerance is worst.
    a_p = {row["regime"]: row for row in result.summary if row["quantity"] == "a_p"}
    assert a_p["all"]["largest_rel_error"] >= a_p["all"]["rel_error_at_worst_ratio"] > 0
    assert a_p["moving_lambda_gt_0.4"]["verdict"] == "FAIL" and a_p["at_rest_lambda_le_0.4"]["verdict"] == "pass"
    text = str(result)
    for words in ("largest error / scale", "error at worst ratio", "at rest, lambda <= 0.4", "moving, lambda > 0.4"):
        assert words in text, text
    assert not re.search(r"\b(nan|inf)\b", text, re.IGNORECASE), text
    assert {(f["case"], f["quantity"], f["cylinder"]) for f in result.failures} == \
        {(f["case"], f["quantity"], float(f["cylinder"])) for f in failures}


def test_a_partial_answer_is_graded_as_provided():
    result = crankcheck.grade(lambda s, phi: {"Q": s.evaluate(phi, quantities=["Q"])["Q"], "U": None},
                              [SCENE_FILES[0]], quick=True)
    assert result.exit_status == 0
    assert result.verdict("Q") == "pass" and result.verdict("U") == "not provided"
    nothing = crankcheck.grade(lambda s, phi: {}, [SCENE_FILES[0]], quick=True)
    assert nothing.exit_status == 1  # nothing provided: as the CLI


def test_rounding_of_a_velocity_at_rest_passes():
    """At rest v_p is 0 exactly and r omega = 0: 1e-18 m/s is rounding, judged against a positive scale."""
    def tiny_at_rest(scene, phi):
        if scene.engine.speed != 0:
            return {}
        return {"v_p": np.full((len(phi), scene.engine.cylinders), 1e-18),
                "rod_omega": np.full((len(phi), scene.engine.cylinders), 1e-18)}
    result = crankcheck.grade(tiny_at_rest, quick=True)
    assert result.exit_status == 0, str(result)
    for row in result.summary:
        if row["provided"]:
            assert 0 < row["tolerance_rel"] < 1e-11 and row["largest_rel_error"] < row["tolerance_rel"], row


def test_the_report(tmp_path):
    out = tmp_path / "report"
    result = crankcheck.grade(norton, [SCENE_FILES[0]], quick=True, out=out)
    assert result.report == str(out / "index.md")
    for name in ("index.md", "index.html", "crankcheck-manifest.json", "data/grade_summary.csv",
                 "data/grade_failures.csv", "grade_error_vs_lambda.svg"):
        assert (out / name).is_file(), name
    assert "python: test_grade.norton" in (out / "index.md").read_text()
    # The folder rule of --out: a folder with someone's file in it is refused before any work.
    (tmp_path / "mine").mkdir()
    (tmp_path / "mine" / "notes.txt").write_text("mine")
    with pytest.raises(ValueError, match="notes.txt|not empty|refus"):
        crankcheck.grade(norton, [SCENE_FILES[0]], quick=True, out=tmp_path / "mine")
    assert (tmp_path / "mine" / "notes.txt").read_text() == "mine"


class Boom(Exception):
    pass


def test_the_function_is_called_once_at_a_time():
    import threading
    import time
    active, most = [0], [0]
    lock = threading.Lock()

    def counting(scene, phi):
        with lock:
            active[0] += 1
            most[0] = max(most[0], active[0])
        time.sleep(0.01)  # lets the interpreter switch threads, were two calls under way
        with lock:
            active[0] -= 1
        return scene.evaluate(phi, quantities=["Q"])
    result = crankcheck.grade(counting, SCENE_FILES[:3], quick=True, jobs=3)
    assert result.passed and most[0] == 1


def test_what_the_function_gets_and_its_errors():
    seen = []

    def record(scene, phi):
        assert isinstance(scene, crankcheck.Scene) and phi.dtype == np.float64 and phi.ndim == 1
        seen.append((scene.name, phi.copy()))
        return {}
    crankcheck.grade(record, [SCENE_FILES[0]], quick=True)
    assert seen and all(np.allclose(np.degrees(phi), np.arange(0, 360, 45)) for _, phi in seen)  # --quick: every 45

    def boom(scene, phi):
        raise Boom("no")
    with pytest.raises(Boom) as e:
        crankcheck.grade(boom, [SCENE_FILES[0]], quick=True)
    assert any("crankcheck.grade: raised on case" in note for note in getattr(e.value, "__notes__", []))

    with pytest.raises(TypeError, match="must return a dict"):
        crankcheck.grade(lambda s, phi: [1, 2], [SCENE_FILES[0]], quick=True)
    with pytest.raises(ValueError, match=r'result\["x_p"\] has shape \(8,\), expected \(8, 1\)'):
        crankcheck.grade(lambda s, phi: {"x_p": phi}, [SCENE_FILES[-1] if "single" in SCENE_FILES[-1] else
                                                        [p for p in SCENE_FILES if "single" in p][0]], quick=True)
    with pytest.raises(ValueError, match="not a finite number"):
        crankcheck.grade(lambda s, phi: {"Q": phi * np.nan}, [SCENE_FILES[0]], quick=True)
    with pytest.raises(ValueError, match='"torque" is not a quantity'):
        crankcheck.grade(lambda s, phi: {"torque": phi}, [SCENE_FILES[0]], quick=True)
    with pytest.raises(ValueError, match=r'"\\x1b\[31m\\x00" is not a quantity'):  # quoted with its control bytes escaped
        crankcheck.grade(lambda s, phi: {"\x1b[31m\x00": phi}, [SCENE_FILES[0]], quick=True)
    with pytest.raises(TypeError, match="callable"):
        crankcheck.grade(42)


def test_the_timeout_ends_the_grade():
    import time

    def slow(scene, phi):
        time.sleep(0.5)
        return {}
    start = time.monotonic()
    with pytest.raises(RuntimeError, match=r"crankcheck.grade: python: .*slow: case \w+: no complete answer within "
                                           r"0.05 s \(interrupted; timeout= sets the seconds per request\)"):
        crankcheck.grade(slow, [SCENE_FILES[0]], quick=True, timeout=0.05, jobs=1)
    # The first call is interrupted at 0.05 s: well under its own 0.5 s sleep.
    assert time.monotonic() - start < 0.5


def test_scene_refusals_are_the_clis(tmp_path):
    missing = str(tmp_path / "missing.toml")
    with pytest.raises(crankcheck.SceneError) as e:
        crankcheck.grade(evaluate, [missing])
    assert str(e.value) == cli_refusal("grade", missing, "--quick", "--", "/bin/true")
    with pytest.raises(crankcheck.SceneError) as e:
        crankcheck.grade(evaluate, [SCENE_FILES[0], SCENE_FILES[0]])
    assert str(e.value) == cli_refusal("grade", SCENE_FILES[0], SCENE_FILES[0], "--quick", "--", "/bin/true")
    # A Scene object is graded as its file is.
    result = crankcheck.grade(evaluate, [crankcheck.Scene.load(SCENE_FILES[0])], quick=True)
    assert result.passed
