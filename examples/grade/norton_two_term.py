#!/usr/bin/env python3
"""A program graded by `crankcheck grade` (docs/grade.md): Norton's two-term piston motion.

    crankcheck grade --quick -- python3 examples/grade/norton_two_term.py

It answers x_p, v_p and a_p of every cylinder with Norton's approximation (Design of Machinery, eqs 13.3c-e):
    x = l - r^2 / (4 l) + r (cos(theta) + (r / (4 l)) cos(2 theta))
    v = -r omega (sin(theta) + (r / (2 l)) sin(2 theta))
    a = -r omega^2 (cos(theta) + (r / l) cos(2 theta))
with theta = phi + alpha_j, and leaves every other quantity out ("not provided"). It is an approximation: it
fails the grade (exit status 1), and the report shows its error growing with lambda = r / l.

Reads one JSON request per line on stdin (one line without --batch, many with it), writes one JSON response per
line on stdout.
"""
import json
import math
import sys


def answer(request):
    scene = request["scene"]
    r = scene["crank"]["radius"]
    l = scene["rod"]["length"]
    omega = scene["engine"]["speed"]
    alphas = scene["engine"]["crank_angles"]
    results = []
    for phi_deg in request["phi_deg"]:
        phi = math.radians(phi_deg)
        cylinders = []
        for alpha in alphas:
            t = phi + alpha
            cylinders.append({
                "x_p": l - r * r / (4 * l) + r * (math.cos(t) + r / (4 * l) * math.cos(2 * t)),
                "v_p": -r * omega * (math.sin(t) + r / (2 * l) * math.sin(2 * t)),
                "a_p": -r * omega * omega * (math.cos(t) + r / l * math.cos(2 * t)),
            })
        results.append({"phi_deg": phi_deg, "cylinders": cylinders})
    return {"results": results}


for line in sys.stdin:
    if line.strip():
        print(json.dumps(answer(json.loads(line))), flush=True)
