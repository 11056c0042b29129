"""Array shapes of Scene.evaluate, and its refusals: the CLI's messages for bad scenes (SceneError), ValueError for bad
arguments."""
import os

import numpy as np
import pytest

import crankcheck
from conftest import SCENE_FILES, cli_refusal

SCENES = {os.path.splitext(os.path.basename(p))[0]: p for p in SCENE_FILES}
# The component shape of each quantity after phi's shape, for k cylinders.
SUFFIX = {
    "U": (), "Q": (), "U_star": (), "Q_star": (), "drive_torque": (), "bearing_force": (2,), "shaking_force": (2,),
    "shaking_moment": (3,), "x_p": ("k",), "v_p": ("k",), "a_p": ("k",), "crank_pin_force": ("k", 2),
    "wrist_pin_force": ("k", 2), "wall_force": ("k",), "gas_force": ("k",), "rod_angle": ("k",), "rod_omega": ("k",),
    "rod_alpha": ("k",),
}


def suffix(key, k):
    return tuple(k if d == "k" else d for d in SUFFIX[key])


def test_quantities_are_evals_names_in_order():
    assert crankcheck.quantities() == list(SUFFIX)


@pytest.mark.parametrize("engine", ["analytic", "mujoco"])
@pytest.mark.parametrize("name", ["single_cylinder", "inline4_four_stroke", "v8_cross_plane"])
@pytest.mark.parametrize("shape", [(7,), (2, 3), (0,)], ids=["1d", "2d", "empty"])
def test_shapes_follow_phi(name, shape, engine):
    scene = crankcheck.Scene.load(SCENES[name])
    k = scene.engine.cylinders
    phi = np.linspace(-1.0, 5.0, int(np.prod(shape))).reshape(shape)
    r = scene.evaluate(phi, engine=engine)
    flat = scene.evaluate(phi.ravel(), engine=engine)
    assert list(r) == [q for q in SUFFIX if q in r]  # eval's order
    for key, value in r.items():
        if value is None:
            assert key in ("U_star", "Q_star")
            continue
        assert value.shape == shape + suffix(key, k), key
        assert value.dtype == np.float64
        # The same numbers as for the flattened angles.
        np.testing.assert_array_equal(value.reshape((-1,) + suffix(key, k)), flat[key])


def test_a_float_angle_gives_numpy_scalars_and_vectors():
    scene = crankcheck.Scene.load(SCENES["inline4_four_stroke"])
    one = scene.evaluate(0.7)
    many = scene.evaluate(np.array([0.7]))
    for key, value in one.items():
        assert np.shape(value) == suffix(key, 4), key
        np.testing.assert_array_equal(value, many[key][0])
    assert isinstance(one["Q"], np.float64)


def test_defined_only_where_eval_defines_them():
    single = crankcheck.Scene.load(SCENES["single_cylinder"])  # no [gas], no axial positions, a flywheel
    r = single.evaluate([0.1, 0.2])
    assert "gas_force" not in r  # eval leaves it out without [gas]
    assert np.isnan(r["shaking_moment"][:, :2]).all()  # eval: null, never 0
    assert np.isfinite(r["shaking_moment"][:, 2]).all()
    v8 = crankcheck.Scene.load(SCENES["v8_cross_plane"])  # axial positions
    assert np.isfinite(v8.evaluate([0.1])["shaking_moment"]).all()
    at_rest = crankcheck.Scene.from_toml(single.to_toml().replace("speed_rpm = 3000", "speed_rpm = 0"), "at_rest.toml")
    r = at_rest.evaluate([0.1])
    assert r["U_star"] is None and r["Q_star"] is None  # eval: null at rest
    gas = crankcheck.Scene.load(SCENES["inline4_four_stroke"])
    assert gas.evaluate([0.1])["gas_force"].shape == (1, 4)


def test_a_subset_of_quantities():
    scene = crankcheck.Scene.load(SCENES["inline4_four_stroke"])
    phi = np.linspace(0, 6, 50)
    everything = scene.evaluate(phi)
    for subset in (["Q"], ["wall_force"], ["rod_alpha", "U_star"], ["crank_pin_force", "x_p", "shaking_moment"]):
        r = scene.evaluate(phi, quantities=subset)
        assert set(r) == set(subset)
        for key in subset:
            np.testing.assert_array_equal(r[key], everything[key])


def test_bad_arguments_are_value_errors():
    scene = crankcheck.Scene.load(SCENES["single_cylinder"])
    with pytest.raises(ValueError, match=r"phi\[2\] = nan: must be a finite number of radians"):
        scene.evaluate(np.array([0.0, 1.0, np.nan]))
    with pytest.raises(ValueError, match=r"phi\[0\] = inf"):
        scene.evaluate(np.inf, engine="simbody")
    with pytest.raises(ValueError, match=r"engine: .*no engine.*analytic, simbody, mujoco"):
        scene.evaluate(0.0, engine="bullet")
    with pytest.raises(ValueError, match=r'quantities: "torque" is not a quantity of eval'):
        scene.evaluate(0.0, quantities=["torque"])
    with pytest.raises(ValueError, match=r"gas_force is not defined for .*single_cylinder.toml \(it has no \[gas\] table\)"):
        scene.evaluate(0.0, quantities=["gas_force"])
    with pytest.raises(ValueError, match="given twice"):
        scene.evaluate(0.0, quantities=["Q", "Q"])


def test_angles_that_are_not_real_numbers_are_type_errors():
    # NumPy alone read None as NaN, "30" as 30 rad and 1+2j as 1 rad (with a warning): none is an angle.
    scene = crankcheck.Scene.load(SCENES["single_cylinder"])
    with pytest.raises(TypeError, match=r"phi: a crank angle \[rad\] or an array of them, not None"):
        scene.evaluate(None)
    with pytest.raises(TypeError, match=r"phi: real numbers \[rad\] \(got an array of dtype complex128: a complex angle"):
        scene.evaluate(np.array([1 + 2j, 0.5]))
    for text in ("ninety", "30", ["0", "90"]):
        with pytest.raises(TypeError, match=r"phi: real numbers \[rad\] \(got an array of dtype <U"):
            scene.evaluate(text)
    # Integers are numbers of radians as they are.
    np.testing.assert_array_equal(scene.evaluate(np.array([0, 1]))["U"], scene.evaluate(np.array([0.0, 1.0]))["U"])


SINGLE = open(SCENES["single_cylinder"]).read()
BAD_SCENES = {
    "unknown_key": SINGLE.replace("length = 0.145", "lenght = 0.145"),
    "not_toml": "[engine\ncylinders = 1\n",
    "empty": "",
    "no_mechanism": SINGLE.replace("radius = 0.043", "radius = 0.2"),  # lambda >= 1
    "negative_mass": SINGLE.replace("mass = 0.35", "mass = -0.35"),
    "inertia_too_small": SINGLE.replace("inertia_about_wrist_pin = 0.0072", "inertia_about_wrist_pin = 0.001"),
    "nan": SINGLE.replace("gravity = 9.80665", "gravity = nan"),
    "too_many_cylinders": SINGLE.replace("cylinders = 1", "cylinders = 65"),
}


@pytest.mark.parametrize("case", sorted(BAD_SCENES))
def test_scene_refusals_are_the_clis(case, tmp_path):
    path = tmp_path / (case + ".toml")
    path.write_text(BAD_SCENES[case])
    message = cli_refusal("eval", str(path))
    with pytest.raises(crankcheck.SceneError) as loaded:
        crankcheck.Scene.load(path)
    assert str(loaded.value) == message
    with pytest.raises(crankcheck.SceneError) as parsed:
        crankcheck.Scene.from_toml(BAD_SCENES[case], str(path))
    if case != "empty":  # an empty file is refused as such only by the file reader
        assert str(parsed.value) == message
    assert isinstance(loaded.value, ValueError)


def test_a_missing_file_is_refused_as_the_cli_does(tmp_path):
    path = str(tmp_path / "nowhere.toml")
    with pytest.raises(crankcheck.SceneError) as e:
        crankcheck.Scene.load(path)
    assert str(e.value) == cli_refusal("eval", path)


@pytest.mark.parametrize("engine,change", [
    ("mujoco", ("[piston]\nmass = 0.35", "[piston]\nmass = 0")),            # MuJoCo: no massless body on a joint
    ("mujoco-soft", ("[piston]\nmass = 0.35", "[piston]\nmass = 0")),
    ("simbody", ("[rod]\nlength = 0.145\nmass = 0.55", "[rod]\nlength = 0.145\nmass = 0")),  # singular mass matrix
])
def test_an_engine_that_cannot_build_the_scene_is_refused_as_the_cli_does(engine, change, tmp_path):
    text = SINGLE.replace(" " * 18 + "# m_o [kg], piston with pin and rings", "")
    text = "\n".join(line.split("#")[0].rstrip() if not line.startswith("#") else line for line in text.splitlines())
    assert change[0] in text
    text = text.replace(change[0], change[1])
    if engine == "simbody":
        text = text.replace("com_from_wrist_pin = 0.105", "com_from_wrist_pin = 0").replace(
            "inertia_about_wrist_pin = 0.0072", "inertia_about_wrist_pin = 0")
    path = tmp_path / "massless.toml"
    path.write_text(text)
    message = cli_refusal("eval", str(path), "--engine", engine)
    scene = crankcheck.Scene.load(path)  # the scene itself is fine: the analytic engine evaluates it
    scene.evaluate([0.0, 1.0])
    with pytest.raises(crankcheck.SceneError) as e:
        scene.evaluate([0.0, 1.0], engine=engine)
    assert str(e.value) == message


@pytest.mark.parametrize("name", ["single_cylinder", "inline4_four_stroke", "inline4_pin_offset"])
def test_out_writes_into_the_arrays_of_an_earlier_call(name):
    if name not in SCENES:
        pytest.skip("no such example scene")
    scene = crankcheck.Scene.load(SCENES[name])
    first = scene.evaluate(np.linspace(0.0, 1.0, 6).reshape(2, 3))
    arrays = {k: v for k, v in first.items()}
    phi = np.linspace(2.0, 5.0, 6).reshape(2, 3)
    again = scene.evaluate(phi, out=first)
    assert again is first
    fresh = scene.evaluate(phi)
    for key, value in fresh.items():
        if value is None:
            assert again[key] is None
            continue
        assert again[key] is arrays[key]  # the same arrays, written again
        np.testing.assert_array_equal(again[key], value)
    subset = scene.evaluate(phi, quantities=["Q", "crank_pin_force"])
    assert scene.evaluate(phi + 1, quantities=["Q", "crank_pin_force"], out=subset) is subset
    np.testing.assert_array_equal(subset["Q"], scene.evaluate(phi + 1)["Q"])


def test_out_must_be_an_earlier_result():
    scene = crankcheck.Scene.load(SCENES["inline4_four_stroke"])
    phi = np.linspace(0.0, 1.0, 5)
    r = scene.evaluate(phi)
    with pytest.raises(ValueError, match=r'out\["U"\]: not the float64 array of this shape'):
        scene.evaluate(np.linspace(0.0, 1.0, 6), out=r)  # another shape
    with pytest.raises(ValueError, match=r'out\["Q"\]: missing'):
        scene.evaluate(phi, out={"U": r["U"]}, quantities=["U", "Q"])
    with pytest.raises(ValueError, match=r'out\["U"\]: not the float64 array'):
        scene.evaluate(phi, out={"U": np.zeros(5, dtype=np.float32)}, quantities=["U"])
    with pytest.raises(ValueError, match="at least one dimension"):
        scene.evaluate(0.5, out=r)
    # phi of another rank than the arrays of out: the same message, not NumPy's "axes don't match array".
    layout = r'out\["(U|x_p)"\]: not the float64 array of this shape and layout evaluate returns \(out must be'
    with pytest.raises(ValueError, match=layout):
        scene.evaluate(phi.reshape(1, 5), out=r)
    with pytest.raises(ValueError, match=layout):
        scene.evaluate(phi.reshape(5, 1, 1), quantities=["x_p"], out=r)
    grid = scene.evaluate(phi.reshape(1, 5), quantities=["U", "crank_pin_force"])
    for quantities in (["U"], ["crank_pin_force"]):
        with pytest.raises(ValueError, match=layout.replace("U|x_p", quantities[0])):
            scene.evaluate(phi, quantities=quantities, out=grid)
