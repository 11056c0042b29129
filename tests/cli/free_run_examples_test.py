#!/usr/bin/python3
"""The two example programs of `crankcheck grade --free-run` (examples/free_run/), checked without the grader:
their answers have the protocol's form, and their numbers agree with something they did not produce.

- Form (docs of protocol 2): one JSON line per request, t strictly increasing from 0 to t_end, finite numbers, at least
  8 samples, the instants omega_t and values_t not after t; a request line that is not JSON: one line, exit status 2.
- rk4_reduced.py held at the scene's speed: its drive torque, x_p, v_p, a_p and reactions equal `crankcheck eval`'s
  at the samples' crank angles to the gate's agreement rule (64 eps x scale x conditioning, docs/CONVENTIONS.md):
  both evaluate closed forms of the same quantities at the same state, only arranged differently.
- free_run_example_euler held: first order in the step, its drive torque's largest error against eval falls tenfold
  (between 5 and 20 times) when the step does.
- Free runs (five revolutions, scenes/single_cylinder.toml): RK4 at T/720 and T/1440 agree to 1e-9 rad (fourth order:
  measured 4e-12 rad); the Euler program's phase against that reference falls tenfold (5 to 20) from T/720 to T/7200.

Usage (ctest free_run.examples, label cli):
    free_run_examples_test.py CRANKCHECK EULER_PROGRAM EXAMPLES_FREE_RUN_DIR
The programs are started without a shell; nothing is written to disk.
"""

import json
import math
import os
import subprocess
import sys
import unittest

CRANKCHECK = EULER = FOLDER = None
EPS = sys.float_info.epsilon


def rk4():
    return [sys.executable, os.path.join(FOLDER, "rk4_reduced.py")]


def euler():
    return [EULER]


def shipped_request():
    with open(os.path.join(FOLDER, "request_single.json")) as f:
        return json.loads(f.readline())


def run(program, *requests):
    """The responses to the requests, one line each, sent in one session."""
    text = "".join(json.dumps(r) + "\n" for r in requests)
    done = subprocess.run(program, input=text, capture_output=True, text=True, timeout=300)
    if done.returncode != 0:
        raise AssertionError("%s: exit status %d: %s" % (program, done.returncode, done.stderr.strip()))
    lines = done.stdout.splitlines()
    if len(lines) != len(requests):
        raise AssertionError("%s: %d lines for %d requests" % (program, len(lines), len(requests)))
    return [json.loads(line) for line in lines]


def evaluate(scene_toml_path, phis):
    """eval's results at the crank angles phis [rad]."""
    degrees = ",".join("%.17g" % math.degrees(p) for p in phis)
    out = subprocess.run([CRANKCHECK, "eval", scene_toml_path, "--phi-deg", degrees, "--format", "json"],
                         capture_output=True, text=True, check=True).stdout
    return json.loads(out)["results"]


SCENE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scenes", "single_cylinder.toml")


def scales(scene):
    """The agreement rule's scales (docs/CONVENTIONS.md, "Tolerances"): lengths, speeds, accelerations, forces,
    torques, and the conditioning 1 / (1 - lambda^2) of the loop."""
    k = scene["engine"]["cylinders"]
    r, l = scene["crank"]["radius"], scene["rod"]["length"]
    w, g = scene["engine"]["speed"], scene["engine"]["gravity"]
    lam = r / l
    accel = g + r * w * w * (1 + (1 - lam * lam) ** -1.5)
    c = scene["crank"]
    force = k * (scene["piston"]["mass"] + scene["rod"]["mass"] + scene["rod"]["inertia_about_wrist_pin"] / l ** 2
                 + c.get("mass", 0.0) + c.get("counterweight_mass", 0.0)) * accel
    return {"x_p": l + r, "v_p": r * w * (1 + (1 - lam * lam) ** -0.5), "a_p": accel, "force": force,
            "torque": force * max(r, c.get("com_radius", 0.0), c.get("counterweight_radius", 0.0)),
            "conditioning": 1 / (1 - lam * lam)}


class FreeRunExamplesTest(unittest.TestCase):
    def check_form(self, request, response):
        samples = response["samples"]
        self.assertGreaterEqual(len(samples), 8)
        self.assertEqual(samples[0]["t"], 0.0)
        for a, b in zip(samples, samples[1:]):
            self.assertLess(a["t"], b["t"])
        self.assertAlmostEqual(samples[-1]["t"], request["t_end"], delta=1e-9 * request["t_end"])
        k = request["scene"]["engine"]["cylinders"]

        def finite(value):
            if isinstance(value, list):
                return all(finite(v) for v in value)
            if isinstance(value, dict):
                return all(finite(v) for v in value.values())
            return isinstance(value, (int, float)) and math.isfinite(value)

        for s in samples:
            self.assertIn("phi", s)
            self.assertIn("omega", s)
            self.assertTrue(finite(s), s)
            self.assertLessEqual(s.get("omega_t", s["t"]), s["t"])
            self.assertLessEqual(s.get("values_t", s["t"]), s["t"])
            if "cylinders" in s:
                self.assertEqual(len(s["cylinders"]), k)

    def test_both_programs_answer_every_request_in_the_protocols_form(self):
        held = shipped_request()
        free = dict(held, drive="free", case="single_cylinder_free", output_interval=held["dt"], quantities=[])
        own = dict(free, dt="own", case="single_cylinder_own")
        for program in (rk4(), euler()):
            responses = run(program, held, free, own)
            for request, response in zip((held, free, own), responses):
                with self.subTest(program=program[-1], case=request["case"]):
                    self.check_form(request, response)
            self.assertIn("drive_torque", responses[0]["samples"][-1])
            self.assertNotIn("drive_torque", responses[1]["samples"][-1])

    def test_a_request_that_is_not_json_is_refused_with_status_2(self):
        for program in (rk4(), euler()):
            done = subprocess.run(program, input="{not json\n", capture_output=True, text=True, timeout=60)
            self.assertEqual(done.returncode, 2, program)
            self.assertEqual(len(done.stderr.strip().splitlines()), 1, done.stderr)
            self.assertEqual(done.stdout, "")

    def test_rk4_held_values_equal_evals(self):
        request = shipped_request()
        samples = run(rk4(), request)[0]["samples"]
        results = evaluate(SCENE, [s["phi"] for s in samples])
        sc = scales(request["scene"])
        bound = 64 * EPS * sc["conditioning"]
        for s, e in zip(samples, results):
            self.assertLessEqual(abs(s["drive_torque"] - e["drive_torque"]), bound * sc["torque"], e["phi_deg"])
            for i in range(2):
                self.assertLessEqual(abs(s["bearing_force"][i] - e["bearing_force"][i]), bound * sc["force"])
            c, ce = s["cylinders"][0], e["cylinders"][0]
            for name in ("x_p", "v_p", "a_p"):
                self.assertLessEqual(abs(c[name] - ce[name]), bound * sc[name], (name, e["phi_deg"]))
            self.assertLessEqual(abs(c["wall_force"] - ce["wall_force"]), bound * sc["force"])
            for name in ("crank_pin_force", "wrist_pin_force"):
                for i in range(2):
                    self.assertLessEqual(abs(c[name][i] - ce[name][i]), bound * sc["force"], (name, e["phi_deg"]))

    def euler_held_torque_error(self, dt):
        request = dict(shipped_request(), dt=dt)
        samples = [s for s in run(euler(), request)[0]["samples"] if "drive_torque" in s]
        # The crank's angle at values_t: held, phi = phi0 + omega0 values_t.
        phis = [request["phi0"] + request["omega0"] * s["values_t"] for s in samples]
        results = evaluate(SCENE, phis)
        return max(abs(s["drive_torque"] - e["drive_torque"]) for s, e in zip(samples, results))

    def test_euler_held_torque_is_first_order_against_eval(self):
        coarse, fine = self.euler_held_torque_error(1e-4), self.euler_held_torque_error(1e-5)
        self.assertTrue(5 < coarse / fine < 20, (coarse, fine))

    def test_free_runs_agree_and_euler_converges_to_rk4(self):
        request = shipped_request()
        period = 2 * math.pi / request["omega0"]
        free = dict(request, drive="free", t_end=5 * period, quantities=[])

        def phis(program, dt, every):
            samples = run(program, dict(free, dt=dt, output_interval=every * dt))[0]["samples"]
            return [s["phi"] for s in samples]

        reference = phis(rk4(), period / 720, 1)
        finer = phis(rk4(), period / 1440, 2)
        self.assertEqual(len(reference), len(finer))
        self.assertLess(max(abs(a - b) for a, b in zip(reference, finer)), 1e-9)
        errors = []
        for divisions in (720, 7200):
            run_phis = phis(euler(), period / divisions, divisions // 720)
            self.assertEqual(len(run_phis), len(reference))
            errors.append(max(abs(a - b) for a, b in zip(run_phis, reference)))
        self.assertTrue(5 < errors[0] / errors[1] < 20, errors)


if __name__ == "__main__":
    CRANKCHECK, EULER, FOLDER = sys.argv[1:4]
    unittest.main(argv=sys.argv[:1], verbosity=2)
