"""Scene.evaluate against the CLI: every quantity, every example scene, every engine of the registry.

The independent side is `crankcheck eval SCENE --phi-deg LIST --engine E --format json` (17 significant digits,
round-trip exact), run as a separate process. The angles are the CLI's: crankcheck.radians_from_degrees converts as
--phi-deg does (exact quarter turns), and is itself checked against the formula below.
"""
import math

import numpy as np
import pytest

import crankcheck
from conftest import EPS, SCENE_FILES, cli_json, scene_id

# Both dead centres, quarter turns, odd angles, a negative one and one beyond a turn.
ANGLES_DEG = [0, 17, 37.5, 90, 133, 180, 222.5, 270, 300, 359, -60, 1000.5]
ENGINES = [e["name"] for e in crankcheck.engines()]

# The physical scale of each quantity (validation/scales.h), the one batch.h's accuracy statement uses.
SCALE_OF = {
    "U": "energy", "Q": "energy", "drive_torque": "torque", "bearing_force": "force", "shaking_force": "force",
    "shaking_moment": "moment", "x_p": "position", "v_p": "velocity", "a_p": "acceleration",
    "crank_pin_force": "force", "wrist_pin_force": "force", "wall_force": "force",
}
# Quantities the analytic engine of the module takes from the same scalar functions as the CLI (no batch kernel):
# the same double, bit for bit.
SCALAR_PATH = {"rod_angle", "rod_omega", "rod_alpha", "gas_force"}
PER_CYLINDER = {"x_p", "v_p", "a_p", "crank_pin_force", "wrist_pin_force", "wall_force", "gas_force", "rod_angle",
                "rod_omega", "rod_alpha"}


def test_radians_from_degrees_is_the_clis_conversion():
    deg = np.array(ANGLES_DEG + [-270, 450, 1e6, 0.1], dtype=float)
    # Beyond 720 degrees the angle is first reduced modulo 720 (fmod: exact; test_angles.py checks it with rationals).
    reduced = [math.fmod(d, 720.0) if abs(d) > 720.0 else d for d in deg]
    expected = [d / 90.0 * (math.pi / 2) if math.fmod(d, 90.0) == 0.0 else d * (math.pi / 180.0) for d in reduced]
    np.testing.assert_array_equal(crankcheck.radians_from_degrees(deg), expected)


def cli_value(result, key, j=None):
    """A quantity of one CLI result (one cylinder's when j is given) as an array, null as NaN."""
    value = result["cylinders"][j][key] if j is not None else result[key]
    if value is None:
        return np.nan
    return np.array([np.nan if v is None else v for v in value], float) if isinstance(value, list) else float(value)


def expected_keys(scene, doc):
    first = doc["results"][0]
    keys = {k for k in first if k not in ("engine", "phi_deg", "cylinders")}
    keys |= set(first["cylinders"][0])
    return keys


@pytest.mark.parametrize("engine", ENGINES)
@pytest.mark.parametrize("path", SCENE_FILES, ids=scene_id)
def test_every_quantity_agrees_with_the_cli(path, engine):
    doc = cli_json("eval", path, "--phi-deg", ",".join(str(a) for a in ANGLES_DEG), "--engine", engine)
    scene = crankcheck.Scene.load(path)
    phi = crankcheck.radians_from_degrees(ANGLES_DEG)
    got = scene.evaluate(phi, engine=engine)
    assert set(got) == expected_keys(scene, doc)
    assert [r["engine"] for r in doc["results"]] == [engine] * len(ANGLES_DEG)

    k = scene.engine.cylinders
    lam = scene.crank_ratio
    scales = scene.scales()
    flywheel = scene.flywheel
    unit = flywheel.inertia * scene.engine.speed ** 2 if flywheel is not None and scene.engine.speed > 0 else None

    def tolerance(key, i, expected):
        """|python - cli| allowed for quantity `key` at angle i."""
        if engine != "analytic" or key in SCALAR_PATH or not scene.batch_kernels:
            # The same engine model evaluating the same angles in the same order (models keep warm starts), or the
            # same scalar function (a scene the kernels do not cover is evaluated by calcEvaluation, as the CLI
            # does): the very same doubles.
            return 0.0
        base = key[:-len("_star")] if key.endswith("_star") else key
        scale = scales[SCALE_OF[base]]
        # batch.h: the kernels agree with the scalar closed forms (which the CLI prints) within 4 eps x scale, times
        # 1 / (1 - lambda^2) near lambda = 1 (the radical's growth); at exact quarter turns the scalar calcSinCos
        # snaps sin and cos to 0 and +-1, moving them by up to 2 eps |phi|, which moves the quantity by up to that
        # times its scale (the scales bound the derivatives with respect to sin and cos).
        quarter = math.fmod(ANGLES_DEG[i], 90.0) == 0.0
        allowance = EPS * scale * (4.0 / (1.0 - lam * lam) + (2.0 * abs(phi[i]) if quarter else 0.0))
        if key.endswith("_star"):
            # U / (I_w omega^2) and Q / (I_w omega^2): the same allowance divided by the unit, and one rounding of the
            # division on each side.
            return allowance / unit + 2.0 * EPS * np.max(np.abs(expected))
        return allowance

    worst = {}
    for i, result in enumerate(doc["results"]):
        for key in got:
            per_cylinder = key in PER_CYLINDER
            if got[key] is None:  # U_star, Q_star without a flywheel or at rest: the CLI's null
                assert result[key] is None, key
                continue
            for j in range(k) if per_cylinder else [None]:
                expected = cli_value(result, key, j)
                actual = got[key][i, j] if per_cylinder else got[key][i]
                # null in the CLI (shaking_moment X, Y without axial positions) is NaN here, and only there.
                np.testing.assert_array_equal(np.isnan(actual), np.isnan(expected), err_msg=key)
                diff = np.nanmax(np.abs(np.asarray(actual) - expected), initial=0.0)
                tol = tolerance(key, i, expected)
                assert diff <= tol, "%s (cylinder %s) at %s deg: python %r, cli %r, |diff| %.3g > %.3g" % (
                    key, j, ANGLES_DEG[i], actual, expected, diff, tol)
                if tol > 0:
                    worst[key] = max(worst.get(key, 0.0), diff / tol)
    # What share of the allowance was used (pytest -s shows it).
    print("%s %s: worst |python - cli| / tolerance: %s" % (scene.name, engine,
          ", ".join("%s %.2f" % kv for kv in sorted(worst.items())) or "all exact"))


def test_the_batch_kernels_run_where_they_cover_the_scene():
    scenes = {scene_id(p): crankcheck.Scene.load(p) for p in SCENE_FILES}
    for name in ("single_cylinder", "inline4_four_stroke", "v8_cross_plane", "boxer4_four_stroke"):
        assert scenes[name].batch_kernels, name
    if "inline4_pin_offset" in scenes:  # pin offsets: the scalar closed forms (batch.h)
        assert not scenes["inline4_pin_offset"].batch_kernels


def test_the_analytic_engine_is_never_copied_or_looped_in_python():
    """A C-contiguous float64 array is used as it is: the C++ sees its buffer (std::span over phi's data)."""
    phi = np.linspace(0.0, 1.0, 1000)
    assert crankcheck._crankcheck._input_buffer_address(phi) == phi.ctypes.data
    # Anything else is converted once by NumPy (a strided view, float32, a list) and gives the same results.
    scene = crankcheck.Scene.load(SCENE_FILES[0])
    wide = np.linspace(0.0, 2.0, 2000)
    strided = wide[::2]
    assert crankcheck._crankcheck._input_buffer_address(strided) != strided.ctypes.data
    a = scene.evaluate(np.ascontiguousarray(strided), quantities=["Q", "x_p"])
    b = scene.evaluate(strided, quantities=["Q", "x_p"])
    c = scene.evaluate(list(strided), quantities=["Q", "x_p"])
    for key in a:
        np.testing.assert_array_equal(a[key], b[key])
        np.testing.assert_array_equal(a[key], c[key])
    # The input is not written to.
    before = wide.copy()
    scene.evaluate(wide)
    np.testing.assert_array_equal(wide, before)


@pytest.mark.parametrize("engine", ["analytic", "simbody"])
def test_threads_evaluate_alike(engine):
    """Each call builds its own engine model and releases the GIL: calls from several threads at once give the
    same results as one after the other."""
    from concurrent.futures import ThreadPoolExecutor
    scenes = [crankcheck.Scene.load(p) for p in SCENE_FILES]
    phi = np.linspace(-3.0, 9.0, 2000 if engine == "analytic" else 12)
    serial = [s.evaluate(phi, engine=engine) for s in scenes]
    with ThreadPoolExecutor(max_workers=4) as pool:
        parallel = list(pool.map(lambda s: s.evaluate(phi, engine=engine), scenes * 2))
    for i, r in enumerate(parallel):
        for key, value in serial[i % len(scenes)].items():
            if value is None:
                assert r[key] is None
            else:
                np.testing.assert_array_equal(r[key], value, err_msg=key)
