"""crankcheck.grade: a Python function graded by `crankcheck grade`'s own cases, rule and report, held against the CLI
grading the example programs that compute the same things (examples/grade/)."""
import csv
import inspect
import os
import re
import signal
import subprocess
import sys
import threading
import time

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
    # A result that is not numbers is named as the result, in its unit (it was blamed on "phi [rad]").
    with pytest.raises(TypeError, match=r'case .*: result\["Q"\]: real numbers \[N m\] \(got an array of dtype <U'):
        crankcheck.grade(lambda s, phi: {"Q": ["a"] * len(phi)}, [SCENE_FILES[0]], quick=True)
    with pytest.raises(ValueError, match='"torque" is not a quantity'):
        crankcheck.grade(lambda s, phi: {"torque": phi}, [SCENE_FILES[0]], quick=True)
    with pytest.raises(ValueError, match=r'"\\x1b\[31m\\x00" is not a quantity'):  # quoted with its control bytes escaped
        crankcheck.grade(lambda s, phi: {"\x1b[31m\x00": phi}, [SCENE_FILES[0]], quick=True)
    with pytest.raises(TypeError, match="callable"):
        crankcheck.grade(42)
    # An empty list is not "the built-in campaign" (None is), and jobs is None or 1..256 (0 ran with one per core).
    with pytest.raises(ValueError, match="grade: scenes is empty"):
        crankcheck.grade(lambda s, phi: {}, [], quick=True)
    for jobs in (0, -1, 257, 2.5, True):
        with pytest.raises(ValueError, match=r"grade: jobs: value not in range 1 to 256 \(None: one per core\)"):
            crankcheck.grade(lambda s, phi: {}, [SCENE_FILES[0]], quick=True, jobs=jobs)


def test_the_timeout_ends_the_grade():
    def slow(scene, phi):
        time.sleep(0.5)
        return {}
    with pytest.raises(RuntimeError, match=r"crankcheck.grade: python: .*slow: case \w+: no complete answer within "
                                           r"0.05 s \(interrupted; timeout= sets the seconds per request\)"):
        crankcheck.grade(slow, [SCENE_FILES[0]], quick=True, timeout=0.05, jobs=1)


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


def relays():
    """This process's children that are grade relays (crankcheck-grade-relay; its name cut to 15 bytes), zombies
    included: pgrep -f would see other processes' grades on the machine, and not a zombie."""
    found = []
    for pid in filter(str.isdigit, os.listdir("/proc")):
        try:
            with open("/proc/%s/stat" % pid) as f:
                stat = f.read()
        except OSError:
            continue  # ended meanwhile
        name, fields = stat[stat.index("(") + 1:stat.rindex(")")], stat[stat.rindex(")") + 2:].split()
        if name.startswith("crankcheck-grad") and int(fields[1]) == os.getpid():
            found.append(int(pid))
    return found


def test_a_sleeping_function_is_interrupted_at_its_timeout():
    """timeout= holds each call: a call sleeping 30 s ends at 1 s, as `crankcheck grade --timeout 1` would kill a
    program that does; nothing of the grade is left, and the next grade works."""
    started = []

    def sleeper(scene, phi):
        started.append(time.monotonic())
        time.sleep(30)
        return {}
    # The caller's SIGALRM handler and timer, restored after the grade.
    mine = signal.signal(signal.SIGALRM, lambda *_: None)
    signal.setitimer(signal.ITIMER_REAL, 100)
    try:
        with pytest.raises(RuntimeError, match=r"sleeper: case \w+: no complete answer within 1 s \(interrupted; "
                                               r"timeout= sets the seconds per request\)") as e:
            crankcheck.grade(sleeper, [SCENE_FILES[0]], quick=True, timeout=1)
        ended = time.monotonic()
        assert signal.getsignal(signal.SIGALRM) is not mine and signal.getitimer(signal.ITIMER_REAL)[0] > 90
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, signal.SIG_DFL)
    # One call, interrupted at 1 s, not at the end of its 30 s sleep: the bound is half the sleep, so that a loaded
    # machine (2 cores under ctest -j2, the grade's threads joined) cannot fail it, and a sleep run out always does.
    assert len(started) == 1 and 1 <= ended - started[0] < 15
    assert "interrupted here" in str(e.value.__cause__)  # the traceback shows where the function was
    assert relays() == []
    # The next grade works, with the default time per call: 1 s once ran out on a loaded machine (a flake, not a fault).
    assert crankcheck.grade(evaluate, [SCENE_FILES[0]], quick=True).passed


def test_the_timeout_from_another_thread():
    """Called from a thread other than the main one, a call is interrupted at its next Python bytecode."""
    outcome = []

    def busy(scene, phi):
        while True:
            pass

    def run():
        try:
            crankcheck.grade(busy, [SCENE_FILES[0]], quick=True, timeout=0.2)
        except RuntimeError as e:
            outcome.append(str(e))
    t = threading.Thread(target=run)
    t.start()
    t.join(10)  # a bound: it ends at 0.2 s
    assert not t.is_alive() and outcome and "no complete answer within 0.2 s" in outcome[0], outcome
    assert relays() == []
    assert crankcheck.grade(evaluate, [SCENE_FILES[0]], quick=True).passed


# A grade in a subprocess whose function runs `BODY` and prints "called" when it starts; it prints "KeyboardInterrupt"
# and the relays its process has left when Ctrl-C ends the grade.
INTERRUPTED = """
import os, sys, time
import crankcheck

%(relays)s

def function(scene, phi):
    print("called", flush=True)
    %(body)s
    return {}
try:
    crankcheck.grade(function, [%(scene)r], quick=True, timeout=60)
except KeyboardInterrupt:
    print("KeyboardInterrupt", relays(), flush=True)
"""


@pytest.mark.parametrize("body", ["time.sleep(30)", "while True: pass"], ids=["sleeping", "running_python"])
def test_ctrl_c_raises_keyboard_interrupt_at_once(body):
    code = INTERRUPTED % {"relays": inspect.getsource(relays), "body": body, "scene": SCENE_FILES[0]}
    p = subprocess.Popen([sys.executable, "-c", code], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        # The function is running once it says so (the interpreter's start and the import take about a second).
        assert p.stdout.readline() == "called\n", p.stderr.read()
        time.sleep(0.2)
        p.send_signal(signal.SIGINT)
        sent = time.monotonic()
        # At once: the handler raises in the function; the grade's threads are joined and its relays gone within a
        # fraction of a second. 2 s bounds that on a loaded machine (2 cores), far below the 30 s of the sleep.
        out, err = p.communicate(timeout=2)
        assert time.monotonic() - sent < 2
    finally:
        p.kill()
        p.wait(10)
    assert out.split("\n")[0] == "KeyboardInterrupt []", (out, err)


def test_grade_at_import_time_with_a_function_that_imports(tmp_path):
    """grade at a module's top level (its import lock held) with a function that imports what imports that module."""
    (tmp_path / "graded_at_import.py").write_text(
        "import crankcheck\n"
        "def function(scene, phi):\n"
        "    import imports_back  # waits for graded_at_import's import lock in any other thread than its importer's\n"
        "    return {}\n"
        "result = crankcheck.grade(function, [%r], quick=True)\n" % SCENE_FILES[0])
    (tmp_path / "imports_back.py").write_text("import graded_at_import\n")
    env = dict(os.environ, PYTHONPATH=os.pathsep.join([str(tmp_path), os.environ.get("PYTHONPATH", "")]))
    # The grade takes a fraction of a second; only a deadlock reaches 20 s.
    p = subprocess.run([sys.executable, "-c", "import graded_at_import as g; print(g.result.cases)"], env=env,
                       capture_output=True, text=True, timeout=20)
    assert p.returncode == 0 and int(p.stdout) > 0, p.stderr


def test_a_path_with_a_nul_byte_is_refused(tmp_path):
    """A NUL ends a C string: "a.toml\\0junk" would read a.toml. Refused as Scene.load refuses a missing file."""
    with pytest.raises(crankcheck.SceneError) as e:
        crankcheck.grade(evaluate, [SCENE_FILES[0] + "\0junk"], quick=True)
    assert str(e.value) == '"%s\\x00junk": file: cannot be read (a path with a NUL byte: no file has that name)' \
        % SCENE_FILES[0]
    with pytest.raises(ValueError, match=r'^out: ".*/report\\x00junk": a path with a NUL byte'):
        crankcheck.grade(evaluate, [SCENE_FILES[0]], quick=True, out=str(tmp_path / "report") + "\0junk")
    assert os.listdir(tmp_path) == []
    with pytest.raises(TypeError, match="scenes must be a list"):
        crankcheck.grade(evaluate, SCENE_FILES[0])
