"""Angles of any size (docs/safety.md "Angles of any size", scene/mechanism.h reduceCrankAngle, crankAngleFromDegrees).

A crank angle past double's reach of a turn used to come back wrong with exit status 0: `eval --phi-deg 1e18` gave
Q = 0 and top dead centre from the analytic engine and another number from Simbody, and at 1e15 and 1e17 every engine
was off in the fourth digit. Now every finite angle names the angle it is:
- in degrees (the CLI's --phi-deg, radians_from_degrees), reduced exactly modulo 720 degrees: the results at 1e18
  degrees are those at its residue, bit for bit, for every engine; the residue is found here with exact rationals;
- in radians (Scene.evaluate), reduced to rounding: the results at 1e15 rad are those at its residue modulo 4 pi,
  found here with mpmath at 60 digits, within the gate's promise (64 eps x scale x conditioning).
"""
import math
from fractions import Fraction

import mpmath
import numpy as np
import pytest

import crankcheck
from conftest import EPS, SCENE_FILES, cli_json, scene_id

# Far past 2^53 degrees, fractional (exact in binary), negative, and a power of two.
HUGE_DEG = [1e15, 1e17, 1e18, -1e18, 2.0 ** 60, 123456789012.5, -7654321.25]
GATED = [e["name"] for e in crankcheck.engines() if e["gated"]]


def residue_deg(d):
    """d modulo 720 with d's sign (C's fmod), exactly: a rational, then the double it is (exact: |r| < 720 and
    r is d minus a multiple of 720, both on d's binary grid)."""
    x = Fraction(d)
    turns = math.trunc(x / 720)
    r = x - 720 * turns
    assert float(r) == r, "the residue is a double"
    return float(r)


def test_radians_from_degrees_reduces_exactly():
    deg = np.array(HUGE_DEG + [720.5, -721.0, 719.0, 1e6])
    expected = crankcheck.radians_from_degrees(np.array([residue_deg(d) for d in deg]))
    np.testing.assert_array_equal(crankcheck.radians_from_degrees(deg), expected)


def test_radians_from_degrees_refuses_what_is_not_an_angle():
    # --phi-deg nan is refused by the CLI; the function gave nan (a hostile round, issue 58).
    for bad in (float("nan"), [0.0, float("inf")]):
        with pytest.raises(ValueError, match=r"degrees\[\d\] = (nan|inf): must be a finite number of degrees"):
            crankcheck.radians_from_degrees(bad)
    with pytest.raises(TypeError, match=r"degrees: real numbers \[deg\] \(got an array of dtype <U"):
        crankcheck.radians_from_degrees("90")


@pytest.mark.parametrize("path", [p for p in SCENE_FILES if "four_stroke" in p or "single" in p], ids=scene_id)
def test_eval_at_a_huge_angle_is_eval_at_its_residue(path):
    """Every engine, every quantity: the same doubles as at the residue (a four-stroke scene with gas: 720 matters)."""
    for engine in ["all"]:
        huge = cli_json("eval", path, "--phi-deg", ",".join(repr(d) for d in HUGE_DEG), "--engine", engine)
        small = cli_json("eval", path, "--phi-deg", ",".join(repr(residue_deg(d)) for d in HUGE_DEG), "--engine", engine)
        assert len(huge["results"]) == len(small["results"]) > 0
        for h, s in zip(huge["results"], small["results"]):
            assert h["phi_deg"] != s["phi_deg"] or abs(h["phi_deg"]) <= 720  # the angle is printed as given
            h = {k: v for k, v in h.items() if k != "phi_deg"}
            s = {k: v for k, v in s.items() if k != "phi_deg"}
            assert h == s


# The scale and conditioning of each quantity (validation/scales.h: the gate's agreement rule).
SCALE = {"U": ("energy", "conditioning"), "Q": ("energy", "conditioning"), "drive_torque": ("torque", "acceleration_conditioning"),
         "bearing_force": ("force", "acceleration_conditioning"), "shaking_force": ("force", "acceleration_conditioning"),
         "x_p": ("position", "closure"), "v_p": ("velocity", "velocity_conditioning"),
         "a_p": ("acceleration", "acceleration_conditioning"), "wall_force": ("force", "acceleration_conditioning"),
         "crank_pin_force": ("force", "acceleration_conditioning"),
         "wrist_pin_force": ("force", "acceleration_conditioning")}
HUGE_RAD = [1e6, 1e10, 1e15, 1e18, -3e17, 2.0 ** 60, 12345.678]


def residue_rad(phi):
    """phi modulo 4 pi at 60 digits (mpmath), as the nearest double: the reference the module does not compute."""
    with mpmath.workdps(60):
        return float(mpmath.fmod(mpmath.mpf(phi), 4 * mpmath.pi))


@pytest.mark.parametrize("engine", GATED)
@pytest.mark.parametrize("path", SCENE_FILES, ids=scene_id)
def test_evaluate_at_a_huge_angle_is_evaluate_at_its_residue(path, engine):
    scene = crankcheck.Scene.load(path)
    scales = scene.scales()
    names = [q for q in SCALE if q in crankcheck.quantities()]
    huge = scene.evaluate(np.array(HUGE_RAD), engine=engine, quantities=names)
    small = scene.evaluate(np.array([residue_rad(p) for p in HUGE_RAD]), engine=engine, quantities=names)
    for q in names:
        scale, conditioning = SCALE[q]
        # The promise: 64 eps x scale x conditioning (scales.h kAgreementMultiple). The reduction's own error (about
        # 1e-15 rad, a few eps of a turn) moves a quantity by that times its derivative in phi, which its scale bounds.
        tolerance = 64 * EPS * scales[scale] * scales[conditioning]
        error = np.max(np.abs(np.asarray(huge[q]) - np.asarray(small[q])))
        assert error <= tolerance, f"{q}: {error:.3g} > {tolerance:.3g}"


def test_non_finite_angles_are_not_reduced_into_numbers():
    """NaN and infinities stay what they are: reduction never turns them into an angle."""
    path = SCENE_FILES[0]
    scene = crankcheck.Scene.load(path)
    phi = np.array([np.inf, -np.inf, np.nan])
    try:
        r = scene.evaluate(phi, quantities=["x_p"])
    except ValueError as e:  # refused: fine, as long as it says so
        assert "phi" in str(e)
        return
    assert not np.any(np.isfinite(r["x_p"]))
