"""Scene: its values against the CLI's JSON "scene", its TOML, its scales."""
import math

import numpy as np
import pytest

import crankcheck
from conftest import SCENE_FILES, cli_json, scene_id


@pytest.mark.parametrize("path", SCENE_FILES, ids=scene_id)
def test_values_are_the_clis(path):
    cli = cli_json("eval", path, "--phi-deg", "0")["scene"]
    scene = crankcheck.Scene.load(path)
    assert scene.to_dict() == cli
    assert scene.name == cli["name"] == scene_id(path)
    assert scene.source == path
    assert scene.crank_ratio == cli["lambda"]
    for table in ("engine", "crank", "rod", "piston", "gas", "flywheel"):
        values = cli.get(table)
        attribute = getattr(scene, table)
        if values is None:
            assert attribute is None, table
            continue
        assert attribute.to_dict() == values
        for key, value in values.items():
            assert getattr(attribute, key) == value, (table, key)
    with pytest.raises(AttributeError, match="read-only"):
        scene.rod.length = 1.0
    with pytest.raises(AttributeError, match="has no value"):
        scene.rod.lenght


@pytest.mark.parametrize("path", SCENE_FILES, ids=scene_id)
def test_to_toml_reads_back_to_the_same_mechanism(path):
    """to_toml is the CLI's scene writer (scene_writer.h): lengths, masses and speeds read back exactly; angles pass
    through degrees, so an angle may come back one rounding away (and crank angles equal to eqs 8-11's are not
    written as explicit). The text is a fixed point, and the mechanism evaluates the same to rounding."""
    scene = crankcheck.Scene.load(path)
    again = crankcheck.Scene.from_toml(scene.to_toml(), path)
    assert again.to_toml() == scene.to_toml()
    for table in ("crank", "rod", "piston", "gas", "flywheel"):
        assert again.to_dict().get(table) == scene.to_dict().get(table)
    phi = np.linspace(0.0, 7.0, 20)
    a, b, scales = scene.evaluate(phi), again.evaluate(phi), scene.scales()
    # An angle one rounding (eps of 2 pi) away moves each quantity by at most eps x 2 pi x its scale; 64 eps x scale
    # (the gate's multiple) bounds that with room for the evaluation's own rounding.
    for key, scale in (("U", "energy"), ("Q", "energy"), ("x_p", "position"), ("a_p", "acceleration"),
                       ("crank_pin_force", "force"), ("drive_torque", "torque")):
        np.testing.assert_allclose(b[key], a[key], rtol=0, atol=64 * np.finfo(float).eps * scales[scale], err_msg=key)


def test_from_toml_names_the_scene_by_the_sources_stem():
    text = open(SCENE_FILES[0]).read()
    assert crankcheck.Scene.from_toml(text, "somewhere/my_engine.toml").name == "my_engine"
    assert crankcheck.Scene.from_toml(text).source == "<string>"


@pytest.mark.parametrize("path", SCENE_FILES, ids=scene_id)
def test_scales_are_the_clis(path):
    """scales() is validation/scales.h's calcScales, the scales the CLI uses: `eval --split` prints its tolerance,
    64 eps x torque scale x acceleration conditioning, computed from them in that order."""
    scene = crankcheck.Scene.load(path)
    s = scene.scales()
    split = cli_json("eval", path, "--phi-deg", "30", "--split")["results"][0]["split"]
    assert split["tolerance"] == 64 * np.finfo(float).eps * s["torque"] * s["acceleration_conditioning"]
    assert set(s) == {"energy", "absolute_height_energy", "position", "velocity", "acceleration", "force", "torque", "moment",
                      "conditioning", "velocity_conditioning", "acceleration_conditioning", "closure"}
    assert all(v > 0 or (v == 0 and scene.engine.speed == 0) for v in s.values())
    # The energy scale as scales.h defines it, for a plain inline scene (offsets and shafts add terms of their own).
    e, c, rod, p = scene.engine, scene.crank, scene.rod, scene.piston
    if not any(scene.to_dict()["engine"].get("pin_offsets", [])) and "balance_shafts" not in scene.to_dict():
        energy = e.cylinders * e.gravity * (c.radius * (p.mass + rod.mass) + c.mass * c.com_radius +
                                            c.counterweight_mass * c.counterweight_radius)
        assert s["energy"] == pytest.approx(energy, rel=4 * np.finfo(float).eps)


def test_engines_are_the_registry():
    names = [e["name"] for e in crankcheck.engines()]
    assert names[:5] == ["analytic", "simbody", "mujoco", "mujoco-soft", "mujoco-soft-stiff"]
    for e in crankcheck.engines():
        assert set(e) == {"name", "library", "method", "gated", "integrators", "settings", "routes"}
        assert "evaluate" in e["routes"]
    # One registry, filtered by route: the engines that step are not among those that evaluate.
    stepped = [e["name"] for e in crankcheck.engines("step_free")]
    assert stepped == ["ode", "ode-quickstep", "bullet", "box2d"]
    assert not set(stepped) & set(names)
    everything = [e["name"] for e in crankcheck.engines("all")]
    assert everything == names + stepped
    assert all(not e["gated"] and e["settings"][0] == "defaults" for e in crankcheck.engines("step_at_speed"))
    assert "simbody" in [e["name"] for e in crankcheck.engines("crank_train")]
    with pytest.raises(ValueError, match="route: walk not in"):
        crankcheck.engines("walk")
    assert crankcheck.batch_target() in ("AVX3", "AVX2", "SSE4", "SSSE3", "SCALAR", "AVX3_ZEN4", "AVX3_SPR")
    assert crankcheck.__version__ == cli_version()


def cli_version():
    from conftest import run_cli
    return run_cli("--version")[1].split()[-1]


def test_a_path_with_a_nul_byte_is_refused():
    """A NUL ends a C string: "a.toml\\0junk" would read a.toml. Refused as a missing file is, the NUL escaped."""
    with pytest.raises(crankcheck.SceneError) as e:
        crankcheck.Scene.load(SCENE_FILES[0] + "\0junk")
    assert str(e.value) == '"%s\\x00junk": file: cannot be read (a path with a NUL byte: no file has that name)' \
        % SCENE_FILES[0]
    assert isinstance(e.value, ValueError)  # as open()'s "embedded null byte"
    with pytest.raises(ValueError, match=r'^source: "a\\x00b.toml": a name with a NUL byte$'):
        crankcheck.Scene.from_toml(open(SCENE_FILES[0]).read(), "a\0b.toml")
    # Names echoed in messages keep what follows a NUL, escaped.
    scene = crankcheck.Scene.load(SCENE_FILES[0].encode())  # a bytes path, as open() takes
    assert scene.source == SCENE_FILES[0]
    with pytest.raises(ValueError, match=r'^engine: no engine "analytic\\x00x"; the engines are analytic, '):
        scene.evaluate(0.0, engine="analytic\0x")
    with pytest.raises(ValueError, match=r'^quantities: "Q\\x00x" is not a quantity'):
        scene.evaluate(0.0, quantities=["Q\0x"])
