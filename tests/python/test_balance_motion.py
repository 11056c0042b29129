"""Scene.balance and Scene.motion against `crankcheck balance` and `crankcheck motion` (--format json)."""
import numpy as np
import pytest

import crankcheck
from conftest import SCENE_FILES, cli_json, cli_refusal, scene_id


@pytest.mark.parametrize("path", SCENE_FILES, ids=scene_id)
def test_balance_is_the_clis(path):
    scene = crankcheck.Scene.load(path)
    # The same calcBalance (closed form, every reference engine's DFT, the exact symmetry): the same numbers. The
    # CLI's words ("reason") are not repeated: vanishes_by_symmetry says what they say.
    for flags in ([], ["--order", "12"]):
        cli = cli_json("balance", path, *flags)
        for h in cli["harmonics"]:
            del h["reason"]
        assert scene.balance(**({"order": 12} if flags else {})) == cli


@pytest.mark.parametrize("settings,flags", [
    ({}, []),
    ({"integrator": "CPodes", "accuracy": 1e-8, "mujoco_integrator": "Euler", "mujoco_step": 2e-3},
     ["--integrator", "CPodes", "--accuracy", "1e-8", "--mujoco-integrator", "Euler", "--mujoco-step", "2e-3"]),
], ids=["defaults", "other_integrators"])
def test_motion_is_the_clis(settings, flags):
    path = [p for p in SCENE_FILES if p.endswith("single_cylinder.toml")][0]
    scene = crankcheck.Scene.load(path)
    # The same energy integral and the same integrators from the same state: the same numbers.
    assert scene.motion(**settings) == cli_json("motion", path, *flags)


def test_motion_series():
    path = [p for p in SCENE_FILES if p.endswith("single_cylinder.toml")][0]
    run = crankcheck.Scene.load(path).motion(series=True)
    assert "series" not in run["analytic"]  # the energy integral has no steps
    # ... and each engine that steps free (bullet's defaults cap its speed: not measured, no series).
    assert "series" not in run["bullet"] and "not_measured" in run["bullet"]
    for engine in ("simbody", "mujoco-soft", "mujoco-soft-stiff", "ode", "ode-quickstep", "box2d"):
        s = run[engine]["series"]
        n = len(s["time"])
        assert n > 10 and all(s[key].shape == (n,) for key in ("time", "phi", "phi_dot", "energy"))
        assert s["phi"][-1] >= 2 * 2 * np.pi  # two revolutions
        # The drift the summary reports is this run's max |E(t) - E(0)| / E(0) per revolution.
        drift = np.max(np.abs(s["energy"] - s["energy"][0])) / abs(s["energy"][0]) / 2
        assert drift == pytest.approx(run[engine]["energy_drift_per_revolution"], rel=1e-12, abs=1e-300)


def test_refusals_are_the_clis(tmp_path):
    single = [p for p in SCENE_FILES if p.endswith("single_cylinder.toml")][0]
    text = open(single).read()
    no_flywheel = tmp_path / "no_flywheel.toml"
    no_flywheel.write_text(text[:text.index("[flywheel]")])
    with pytest.raises(crankcheck.SceneError) as e:
        crankcheck.Scene.load(no_flywheel).motion()
    assert str(e.value) == cli_refusal("motion", str(no_flywheel))
    at_rest = tmp_path / "at_rest.toml"
    at_rest.write_text(text.replace("speed_rpm = 3000", "speed_rpm = 0"))
    with pytest.raises(crankcheck.SceneError) as e:
        crankcheck.Scene.load(at_rest).motion()
    assert str(e.value) == cli_refusal("motion", str(at_rest))
    scene = crankcheck.Scene.load(single)
    with pytest.raises(ValueError, match="integrator: Verlet not in"):
        scene.motion(integrator="Verlet")
    with pytest.raises(ValueError, match="accuracy"):
        scene.motion(accuracy=0.5)
    with pytest.raises(ValueError, match="order: 0 not in"):
        scene.balance(0)
    with pytest.raises(ValueError, match="order: 65 not in"):
        scene.balance(65)
