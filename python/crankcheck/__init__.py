"""crankcheck from Python: the same scenes, engines and grade as the `crankcheck` CLI, over NumPy arrays.

    import numpy as np, crankcheck
    scene = crankcheck.Scene.load("scenes/inline4_four_stroke.toml")
    phi = np.linspace(0.0, 4 * np.pi, 3600, endpoint=False)     # crank angles [rad]
    r = scene.evaluate(phi)                                      # the analytic engine, SIMD batch kernels
    r["Q"].shape, r["crank_pin_force"].shape                     # (3600,), (3600, 4, 2)
    s = scene.evaluate(phi[:36], engine="simbody")               # any engine of crankcheck.engines()

Names, units (SI: m, kg, s, N, N m, J; angles in radians) and signs are those of `crankcheck eval --format json`
(docs/eval.md, docs/CONVENTIONS.md). A scene the CLI refuses raises SceneError (a ValueError) with the
CLI's message: "FILE: KEY: rule".
"""

import numbers as _numbers
import os as _os
import signal as _signal
import textwrap as _textwrap
import threading as _threading
import time as _time
from dataclasses import dataclass as _dataclass, field as _field

from ._crankcheck import (  # noqa: F401  (the public API)
    Scene,
    SceneError,
    __version__,
    batch_target,
    engines,
    fourier_piston_kinematics,
    free_run_tolerances,
    inverse_radical_fourier_coefficients,
    lambda_coefficients,
    lambda_coefficients_as_printed,
    lambda_series_coefficient,
    norton_two_term,
    piston_kinematics,
    quantities,
    radians_from_degrees,
    radical_fourier_coefficients,
)
from . import _crankcheck

__all__ = [
    "Scene", "SceneError", "SceneTable", "GradeResult", "grade", "FreeRunGradeResult", "grade_free_run",
    "free_run_tolerances", "engines", "quantities", "batch_target",
    "radical_fourier_coefficients", "inverse_radical_fourier_coefficients", "lambda_coefficients",
    "lambda_coefficients_as_printed", "lambda_series_coefficient", "piston_kinematics", "norton_two_term",
    "fourier_piston_kinematics", "radians_from_degrees", "__version__",
]

_RELAY = _os.path.join(_os.path.dirname(_os.path.abspath(__file__)), "crankcheck-grade-relay")


class SceneTable:
    """One table of a scene (engine, crank, rod, piston, gas, flywheel) with its values as read-only attributes, named
    and in the units of `crankcheck eval --format json`'s "scene" (SI, radians)."""

    __slots__ = ("_name", "_values")

    def __init__(self, name, values):
        object.__setattr__(self, "_name", name)
        object.__setattr__(self, "_values", dict(values))

    def __getattr__(self, key):
        try:
            return self._values[key]
        except KeyError:
            raise AttributeError("scene table %s has no value %r (it has: %s)"
                                 % (self._name, key, ", ".join(self._values))) from None

    def __setattr__(self, key, value):
        raise AttributeError("a scene is read-only: make a new one (Scene.from_toml) to change it")

    def __dir__(self):
        return list(self._values)

    def to_dict(self):
        return dict(self._values)

    def __repr__(self):
        return "%s(%s)" % (self._name, ", ".join("%s=%r" % kv for kv in self._values.items()))


def _scene_table(name, doc):
    def get(self):
        values = self.to_dict()[name] if name in self.to_dict() else None
        return None if values is None else SceneTable(name, values)
    return property(get, doc=doc)


Scene.engine = _scene_table("engine", "cylinders, cycle, acting, crank_angles, explicit_crank_angles, cylinder_angle, "
                                      "bank_angles, axial_positions, speed [rad/s], gravity [m/s^2] (firing_angles "
                                      "with [gas])")
Scene.crank = _scene_table("crank", "radius, mass, com_radius, counterweight_mass, counterweight_radius")
Scene.rod = _scene_table("rod", "length, mass, com_from_wrist_pin, inertia_about_wrist_pin")
Scene.piston = _scene_table("piston", "mass")
Scene.gas = _scene_table("gas", "bore, cycle_angles, pressures [Pa], cycle [rad]; None without [gas]")
Scene.flywheel = _scene_table("flywheel", "inertia [kg m^2]; None without [flywheel]")


# The grade tables' columns that count (cases, values, a cylinder's index): ints, not floats.
_INTEGER_COLUMNS = {"asked", "provided", "cylinder"}


def _rows(table):
    """A grade table's rows as dicts: numbers as floats (ints for the counts), text as str, None where empty."""
    def value(column, cell):
        if cell is None or cell == "":
            return None
        return int(cell) if column in _INTEGER_COLUMNS else cell
    return [{c: value(c, v) for c, v in zip(table["columns"], row)} for row in table["rows"]]


# The summary's regimes as `crankcheck grade` prints them (validation/grade.h: getGradeRegimes).
_REGIMES = _crankcheck._grade_regimes()


@_dataclass
class GradeResult:
    """What `crankcheck grade` found for a function: the tables of its report (validation/grade.h) as lists of dicts.

    summary          one row per quantity and regime ("all", then "moving_lambda_le_0.4", "moving_lambda_gt_0.4",
                     "at_rest_lambda_le_0.4", "at_rest_lambda_gt_0.4"; a regime without a value asked left out):
                     quantity, regime, asked, provided, largest_rel_error (the largest error / scale over every value
                     and the three references), largest_rel_error_simbody, largest_rel_error_analytic,
                     largest_rel_error_mujoco, largest_where_case, largest_where_phi_deg, largest_where_speed_rpm,
                     rel_error_at_worst_ratio (the error / scale where error / tolerance is worst), worst_ratio,
                     tolerance_rel (there), where_case, where_phi_deg, where_speed_rpm, verdict ("pass", "FAIL" or
                     "not provided")
    error_vs_lambda  quantity, lambda, program_max_rel_error, analytic_max_rel_error
    failures         case, family, lambda, quantity, cylinder, phi_deg, speed_rpm, program_value, simbody_value,
                     analytic_value, rel_error, tolerance_rel, mujoco_value
    exit_status      the CLI's: 0 when every provided value agrees with every reference engine (and one was
                     provided), 1 otherwise
    """

    exit_status: int
    summary: list = _field(default_factory=list)
    error_vs_lambda: list = _field(default_factory=list)
    failures: list = _field(default_factory=list)
    cases: int = 0
    seconds: float = 0.0
    report: str = None

    @property
    def passed(self):
        return self.exit_status == 0

    def verdict(self, quantity):
        """The summary's verdict for `quantity` over all cases ("pass", "FAIL", "not provided"), None when it was not
        asked."""
        for row in self.summary:
            if row["quantity"] == quantity and row["regime"] == "all":
                return row["verdict"]
        return None

    def __str__(self):
        """The summary as `crankcheck grade` prints it."""
        def brief(x):
            return "-" if x is None else "%.2g" % x

        form = "%-15s %-22s %11s %9s %9s %9s  %s"
        lines = [form % ("quantity", "regime", "provided", "largest", "at worst", "tolerance", "verdict"),
                 (form % ("", "", "/ asked", "error", "ratio", "/ scale", "")).rstrip()]
        for row in self.summary:
            if row["regime"] != "all" and not row["provided"]:
                continue  # a regime of a quantity not provided
            lines.append(form % (
                row["quantity"] if row["regime"] == "all" else "", _REGIMES.get(row["regime"], row["regime"]),
                "%d / %d" % (row["provided"], row["asked"]), brief(row["largest_rel_error"]),
                brief(row["rel_error_at_worst_ratio"]), brief(row["tolerance_rel"]), row["verdict"]))
        names = ["the analytic engine"] + [e["name"] for e in engines() if e["gated"] and e["name"] != "analytic"]
        references = ", ".join(names[:-1]) + " and " + names[-1]
        lines += _textwrap.wrap("Errors relative to the quantity's scale, against %s: the largest error / scale over "
                                "every value, and the error at worst ratio, where error / tolerance is worst (beside "
                                "that tolerance)." % references, 100)
        where = "the report's failing cases" if self.report else "`failures`; out= writes the report"
        lines.append("Every provided value agrees with %s." % references if self.passed
                     else "SOME VALUES DISAGREE, or none was provided (see %s)." % where)
        return "\n".join(lines)


def _find_reports_dir():
    """share/crankcheck/reports (the report's gnuplot scripts) above this package: the build tree's
    build/share/crankcheck/reports, or PREFIX/share/crankcheck/reports of an install tree."""
    folder = _os.path.dirname(_os.path.abspath(__file__))
    for up in range(1, 6):
        candidate = _os.path.join(folder, *([_os.pardir] * up), "share", "crankcheck", "reports")
        if _os.path.isdir(candidate):
            return _os.path.normpath(candidate)
    return None


class _Interrupted(BaseException):
    """Raised in the graded function where its call reaches grade's timeout. A BaseException, so that the function's
    own `except Exception` does not catch it."""


# [s] How long grade waits for a request at a time before Python looks at its signals: Ctrl-C's latency between calls.
_WAIT = 0.05


class _CallClock:
    """Holds each call of the graded function to `timeout` seconds.

    In the main thread: ITIMER_REAL and a SIGALRM handler that raise _Interrupted where the function is (Python code,
    time.sleep, a lock or import lock it waits for); close() restores the previous handler and timer (the timer less the
    time gone, at once if it is gone). In any other thread, where no signal handler can be set: a timer thread raises
    _Interrupted in the calling thread (PyThreadState_SetAsyncExc), which takes effect at the function's next Python
    bytecode, not inside a C call (time.sleep, a blocking read): such a call is interrupted when it returns."""

    def __init__(self, timeout):
        self.timeout = timeout
        self.calling = False
        self.fired = False
        self.main = False
        if _threading.current_thread() is _threading.main_thread():
            try:
                self.previous_handler = _signal.signal(_signal.SIGALRM, self._alarm)
                self.main = True
            except ValueError:  # not the main interpreter: no signal handler here
                pass
        if self.main:
            self.started = _time.monotonic()
            self.previous_timer = _signal.setitimer(_signal.ITIMER_REAL, 0)
        else:
            self.lock = _threading.Lock()
            self.thread_id = _threading.get_ident()

    def _alarm(self, signum, frame):
        if self.calling:  # else a call that ended as the timer fired: nothing to interrupt
            self.calling = False
            self.fired = True
            raise _Interrupted("the graded function's call interrupted here, at grade's timeout of %r s" % self.timeout)

    def _fire(self):
        with self.lock:  # a call that has ended is not interrupted (see call)
            if self.calling:
                self.fired = True
                _crankcheck._raise_in_thread(self.thread_id, _Interrupted)

    def call(self, function, *args):
        """function(*args), or _Interrupted when it did not return within the timeout (even if it caught it)."""
        self.fired = False
        if self.main:
            self.calling = True
            _signal.setitimer(_signal.ITIMER_REAL, self.timeout)
            try:
                answer = function(*args)
            finally:
                self.calling = False
                _signal.setitimer(_signal.ITIMER_REAL, 0)
        else:
            timer = _threading.Timer(self.timeout, self._fire)
            timer.daemon = True
            self.calling = True
            timer.start()
            try:
                answer = function(*args)
            finally:
                try:
                    with self.lock:
                        self.calling = False
                        if self.fired:  # raised, or still pending: cleared, and raised below instead
                            _crankcheck._raise_in_thread(self.thread_id, None)
                finally:
                    timer.cancel()
        if self.fired:
            raise _Interrupted("the graded function caught the interruption at grade's timeout of %r s" % self.timeout)
        return answer

    def close(self):
        self.calling = False
        if self.main:
            _signal.setitimer(_signal.ITIMER_REAL, 0)
            # None: a handler set outside Python, which Python cannot set again; the default in its place.
            _signal.signal(_signal.SIGALRM, _signal.SIG_DFL if self.previous_handler is None else self.previous_handler)
            delay, interval = self.previous_timer
            if delay > 0:
                left = delay - (_time.monotonic() - self.started)
                _signal.setitimer(_signal.ITIMER_REAL, left if left > 0 else 1e-6, interval)


def grade(function, scenes=None, quick=True, *, jobs=None, timeout=60.0, out=None):
    """Grades `function` by the rule and with the cases of `crankcheck grade --batch` (docs/grade.md).

    function(scene, phi) -> dict: `scene` is a crankcheck.Scene (the case's mechanism), `phi` a NumPy array of crank
    angles [rad]; it returns what it computes as Scene.evaluate does, with eval's names and shapes ((n,), (n, 2),
    (n, 3), (n, k), (n, k, 2) for n angles and k cylinders). A quantity left out, or None, is "not provided": reported as
    such, never as wrong. Values must be finite, except shaking_moment's X and Y for a scene without axial positions
    (not defined, not graded: NaN as Scene.evaluate gives them). An exception of the function ends the grade and is
    raised here (with a note naming the case).

    scenes: scene files (str, bytes or os.PathLike; a path with a NUL byte is refused) or Scenes (default: the built-in
    campaign of `crankcheck validate`); quick: the CLI's --quick; jobs: references computed in parallel (default: one
    per core); out: a folder for the CLI's report (the same folder rule as --out; needs gnuplot).

    The function is called in the calling thread, one call at a time (the requests reach it through a relay program
    that `crankcheck grade`'s own code starts; the grade runs in background threads meanwhile). timeout: seconds per
    request, as --timeout: a call that takes longer is interrupted (in the main thread by SIGALRM: Python code,
    time.sleep, a lock or import it waits for; ITIMER_REAL and the SIGALRM handler are the grade's while it runs and
    restored after), and the grade raises RuntimeError "crankcheck.grade: python: NAME: case ID: no complete answer
    within T s (interrupted; timeout= sets the seconds per request)". Called from another thread, the call is
    interrupted at its next Python bytecode only: a C call (time.sleep, a blocking read) runs to its end first.
    Ctrl-C raises KeyboardInterrupt at once, in the function or between calls. On every ending (a result, a timeout,
    KeyboardInterrupt, the function's exception) the grade's relays have exited and its threads are joined before
    grade returns or raises; the next call starts afresh.
    """
    if not callable(function):
        raise TypeError("grade: function must be callable as function(scene, phi) -> dict")
    if isinstance(scenes, (str, bytes, _os.PathLike, Scene)):
        raise TypeError("grade: scenes must be a list of scene files or Scenes, not one (scenes=[...])")
    scene_list = None if scenes is None else list(scenes)
    if scene_list is not None and not scene_list:
        raise ValueError("grade: scenes is empty; give at least one scene (None: the built-in campaign)")
    if jobs is not None and (isinstance(jobs, bool) or not isinstance(jobs, _numbers.Integral) or not 1 <= jobs <= 256):
        raise ValueError("grade: jobs: value not in range 1 to 256 (None: one per core), got %r" % (jobs,))
    name = getattr(function, "__qualname__", None) or repr(function)
    module = getattr(function, "__module__", None)
    program = "python: %s.%s" % (module, name) if module else "python: %s" % name
    # The report's gnuplot scripts: the C++ looks beside the running program (python3 here) unless told where.
    reports = None
    if out is not None and "CRANKCHECK_REPORTS_DIR" not in _os.environ:
        reports = _find_reports_dir()
        if reports is not None:
            _os.environ["CRANKCHECK_REPORTS_DIR"] = reports
    try:
        run = _crankcheck._grade_start(scene_list, _bool_argument("grade", "quick", quick),
                                       0 if jobs is None else int(jobs), float(timeout),
                                       out, _RELAY, program)
        clock = None
        try:
            clock = _CallClock(float(timeout))
            while True:
                request = run.next(_WAIT)
                if request is None:
                    if run.finished():
                        break
                    continue
                ident, scene, phi, case, family = request
                try:
                    run.answer(ident, clock.call(function, scene, phi))
                except _Interrupted as e:
                    raise RuntimeError(run.timeout_message(case)) from e
                except Exception as e:
                    if hasattr(e, "add_note"):
                        e.add_note("crankcheck.grade: raised on case %s (%s)" % (case, family))
                    raise
            r = run.result()
        except BaseException:
            run.stop()  # the relays exit, the threads are joined, the socket's folder is removed
            raise
        finally:
            if clock is not None:
                clock.close()
    finally:
        if reports is not None:
            del _os.environ["CRANKCHECK_REPORTS_DIR"]
    tables = r["tables"]
    return GradeResult(
        exit_status=r["exit_status"],
        summary=_rows(tables["grade_summary"]),
        error_vs_lambda=_rows(tables["grade_error_vs_lambda"]),
        failures=_rows(tables["grade_failures"]),
        cases=r["cases"],
        seconds=r["seconds"],
        report=r["report"],
    )


@_dataclass
class FreeRunGradeResult:
    """What `crankcheck grade --free-run` found for a function's runs: the tables of its report
    (validation/free_run_grade.h) as lists of dicts.

    measures     one row per measure of each run: case, scene, drive, dt, measure (energy_trend, delta,
                 phi_at_omega_max, phi_at_omega_min, phase, or a quantity's name), unit, program, exact, error,
                 tolerance, resolution, horizon, where, verdict ("pass" or "FAIL")
    convergence  with dt_sweep > 1: scene, drive, measure, observed_order, largest_step, tolerance
    history      case, dt, time, phase_error, energy_error (at each turn of a free run)
    engines      the engines' own free runs of each scene: scene, engine, integrator, accuracy, accuracy_meaning,
                 energy_trend_per_revolution, delta, delta_exact, delta_error_rel, phi_max_error, phi_min_error,
                 phase_error_at_horizon, horizon, revolutions, steps, omega_reading, cpu_per_revolution
    exit_status  the CLI's: 0 when every measure of the asked step is within its tolerance, 1 otherwise
    """

    exit_status: int
    measures: list = _field(default_factory=list)
    convergence: list = _field(default_factory=list)
    history: list = _field(default_factory=list)
    engines: list = _field(default_factory=list)
    runs: int = 0
    seconds: float = 0.0
    report: str = None

    @property
    def passed(self):
        return self.exit_status == 0

    def verdict(self, measure, dt=None):
        """The verdict of `measure` ("pass", "FAIL"; None when not graded) at step `dt` (default: the asked step, the
        largest of each scene's sweep); "FAIL" when it fails in any scene."""
        rows = [r for r in self.measures if r["measure"] == measure]
        if dt is None:
            largest = {}
            for r in self.measures:
                largest[r["scene"]] = max(largest.get(r["scene"], 0.0), r["dt"] or 0.0)
            rows = [r for r in rows if (r["dt"] or 0.0) == largest[r["scene"]]]
        else:
            rows = [r for r in rows if r["dt"] is not None and abs(r["dt"] - dt) <= 1e-12 * dt]
        if not rows:
            return None
        return "FAIL" if any(r["verdict"] == "FAIL" for r in rows) else rows[0]["verdict"]


def _integer_argument(function, name, value):
    """value as an int, or TypeError naming function and name: a float (2.9), a bool or a string is not truncated or
    read into one (the CLI refuses --revolutions 2.9 too)."""
    if isinstance(value, bool) or not isinstance(value, _numbers.Integral):
        raise TypeError("%s: %s must be an integer, got %r" % (function, name, value))
    return int(value)


def _bool_argument(function, name, value):
    """value if it is True or False, else TypeError naming function and name ("no" is not False)."""
    if not isinstance(value, bool):
        raise TypeError("%s: %s must be True or False, got %r" % (function, name, value))
    return value


def _as_run_response(answer):
    """The function's answer as protocol 2's response: {"samples": [...]} as it is, or columns {"t": [...], "phi": [...],
    "omega": [...], ...} (sequences or NumPy arrays of one length n; per-cylinder quantities (n, k) or (n, k, 2))
    turned into samples."""
    if not isinstance(answer, dict):
        raise TypeError("grade_free_run: the function must return a dict: {\"samples\": [...]} or columns "
                        "{\"t\": [...], \"phi\": [...], \"omega\": [...], ...}, not %s" % type(answer).__name__)
    if "samples" in answer:
        return answer
    def listed(value):
        return value.tolist() if hasattr(value, "tolist") else list(value)
    columns = {key: listed(value) for key, value in answer.items() if value is not None}
    for key in ("t", "phi", "omega"):
        if key not in columns:
            raise ValueError("grade_free_run: the function's columns need %r (it gave: %s)" % (key, ", ".join(answer)))
    n = len(columns["t"])
    per_cylinder = set(_crankcheck._per_cylinder_quantities())
    samples = []
    for i in range(n):
        sample = {}
        cylinders = []
        for key, column in columns.items():
            if len(column) != n:
                raise ValueError("grade_free_run: column %r has %d values, t has %d" % (key, len(column), n))
            if key in per_cylinder:
                for j, value in enumerate(column[i]):
                    while len(cylinders) <= j:
                        cylinders.append({})
                    cylinders[j][key] = value
            else:
                sample[key] = column[i]
        if cylinders:
            sample["cylinders"] = cylinders
        samples.append(sample)
    return {"samples": samples}


def grade_free_run(function, scenes, *, drive="free", revolutions=10, dt=None, dt_sweep=1, output_interval=None,
                   energy_tolerance=None, delta_tolerance=None, extreme_phase_tolerance=None, phase_tolerance=None,
                   values_tolerance=None, quick=False, timeout=60.0, out=None, work_limit=600.0):
    """Grades `function`'s time-stepped runs by the measures, tolerances and rules of `crankcheck grade --free-run`
    (docs/grade.md, "Time-stepped runs").

    function(request) -> dict: `request` is protocol 2's request as a dict (the scene as eval's "scene", "drive",
    "phi0", "omega0", "dt" (a number, or "own"), "t_end", "output_interval", "quantities", ...); the function returns
    the run as protocol 2's response {"samples": [{"t": ..., "phi": ..., "omega": ..., "omega_t": ..., ...}, ...]} or
    as columns {"t": array, "phi": array, "omega": array, optional "omega_t", "values_t" and quantities: whole-engine
    ones (n,) or (n, 2), per-cylinder ones (n, k) or (n, k, 2)}. A non-finite number is refused (RuntimeError, as the
    CLI's exit status 3: a broken run), as are t or phi not increasing, fewer than 8 samples, or a run stopping before
    t_end. An exception of the function is raised here (with a note naming the run).

    scenes: scene files or Scenes (at least one; with [flywheel] for a free run). drive, revolutions, dt (None: 1/720
    of a revolution; "own": the function's own), dt_sweep, output_interval, the tolerances (None: the CLI's defaults,
    crankcheck.free_run_tolerances()) and quick: the CLI's flags.
    timeout: seconds per run, as --timeout (the call is interrupted as crankcheck.grade's are). out: a folder for the
    report (the same folder rule as --out; needs gnuplot). work_limit: the longest work [s] of crankcheck's own runs
    over the horizon, estimated before the function is first called and refused past it (ValueError), as --work-limit.
    """
    import json as _json
    if not callable(function):
        raise TypeError("grade_free_run: function must be callable as function(request) -> dict")
    if isinstance(scenes, (str, bytes, _os.PathLike, Scene)):
        raise TypeError("grade_free_run: scenes must be a list of scene files or Scenes, not one (scenes=[...])")
    revolutions = _integer_argument("grade_free_run", "revolutions", revolutions)
    dt_sweep = _integer_argument("grade_free_run", "dt_sweep", dt_sweep)
    quick = _bool_argument("grade_free_run", "quick", quick)
    own = isinstance(dt, str)
    if own and dt != "own":
        raise ValueError("grade_free_run: dt must be a step [s], None or \"own\", not %r" % dt)
    if own and dt_sweep != 1:
        raise ValueError("grade_free_run: dt_sweep needs a step to halve; give dt=S (the function's own step cannot be swept)")
    name = getattr(function, "__qualname__", None) or repr(function)
    module = getattr(function, "__module__", None)
    program = "python: %s.%s" % (module, name) if module else "python: %s" % name
    reports = None
    if out is not None and "CRANKCHECK_REPORTS_DIR" not in _os.environ:
        reports = _find_reports_dir()
        if reports is not None:
            _os.environ["CRANKCHECK_REPORTS_DIR"] = reports
    clock = _CallClock(float(timeout))

    def answer(line):
        request = _json.loads(line)
        try:
            response = clock.call(function, request)
        except _Interrupted as e:
            raise RuntimeError("crankcheck.grade_free_run: %s: case %s: no complete answer within %s s (interrupted; "
                               "timeout= sets the seconds per run)" % (program, request["case"], timeout)) from e
        except Exception as e:
            if hasattr(e, "add_note"):
                e.add_note("crankcheck.grade_free_run: raised on run %s" % request["case"])
            raise
        # NaN and Infinity are written as such: not JSON, refused by the grade as a broken run.
        return _json.dumps(_as_run_response(response), allow_nan=True)

    try:
        r = _crankcheck._grade_free_run(
            list(scenes), str(drive), revolutions, None if (dt is None or own) else float(dt), own, dt_sweep,
            None if output_interval is None else float(output_interval),
            [None if x is None else float(x) for x in
             (energy_tolerance, delta_tolerance, extreme_phase_tolerance, phase_tolerance, values_tolerance)],
            quick, float(timeout), out, answer, program, float(work_limit))
    finally:
        clock.close()
        if reports is not None:
            del _os.environ["CRANKCHECK_REPORTS_DIR"]
    tables = r["tables"]
    empty = {"columns": [], "rows": []}
    return FreeRunGradeResult(
        exit_status=r["exit_status"],
        measures=_rows(tables.get("free_run_measures", empty)),
        convergence=_rows(tables.get("free_run_convergence", empty)),
        history=_rows(tables.get("free_run_history", empty)),
        engines=_rows(tables.get("free_run_engines", empty)),
        runs=r["runs"],
        seconds=r["seconds"],
        report=r["report"],
    )
