#!/usr/bin/env python3
"""A program graded by `crankcheck grade --free-run` (protocol 2, a time-stepped run): classical RK4 on the reduced
one-degree-of-freedom equation of the crank angle phi,

    J(phi) phi'' + (1/2) J'(phi) phi'^2 + Q(phi) = T_drive - T_load + T_gas(phi),

with J, J' = dJ/dphi, Q = dU/dphi and the gas torque from this script's own closed forms of the exact slider-crank
(docs/CONVENTIONS.md: theta_j = phi + crank_angles[j], bank angles, pin offsets; no crankcheck code is used).

    build/bin/crankcheck grade --free-run ... -- python3 examples/free_run/rk4_reduced.py

Drives: "free" (T_drive = T_load = 0), "loaded" (T_load = the request's load_torque), "held" (phi = phi0 + omega0 t
exactly, so J phi'' = 0 and drive_torque = (1/2) J' omega0^2 + Q - T_gas). The gas torque acts when the request says
"gas": true. phi and omega are reported at the same instant t (no omega_t, no values_t); x_p, v_p, a_p, rod_angle,
rod_omega, rod_alpha and the reactions (crank_pin_force, wrist_pin_force, wall_force, bearing_force) come from
Newton's laws of each body at the integrated state, with phi'' from the equation above.

Step: the request's dt, or with "own" 1/720 of a revolution at omega0 (shortened so a whole number of steps ends at
t_end). A sample is written at t = 0 and every round(output_interval / dt) >= 1 steps, and at the last step.
The balance shafts of a scene are not in the request's "scene" object and are therefore not modelled.

Reads one JSON request per line on stdin, writes one JSON response per line on stdout (flushed). A request it cannot
read: one line on stderr, exit status 2.
"""
import json
import math
import sys


class Cylinder:
    """One slider-crank: bank axis e = (cos g, sin g), normal n = (-sin g, cos g), phase c, pin offset d."""

    def __init__(self, g, c, d):
        self.e = (math.cos(g), math.sin(g))
        self.n = (-math.sin(g), math.cos(g))
        self.g = g
        self.c = c
        self.d = d


class Engine:
    def __init__(self, scene):
        eng = scene["engine"]
        k = eng["cylinders"]
        banks = eng.get("bank_angles") or [eng["cylinder_angle"]] * k
        offsets = eng.get("pin_offsets") or [0.0] * k
        self.cyl = [Cylinder(banks[j], eng["crank_angles"][j], offsets[j]) for j in range(k)]
        self.grav = eng["gravity"]
        self.r = scene["crank"]["radius"]
        self.m_s = scene["crank"].get("mass", 0.0)
        self.r_s = scene["crank"].get("com_radius", 0.0)
        self.m_p = scene["crank"].get("counterweight_mass", 0.0)
        self.r_p = scene["crank"].get("counterweight_radius", 0.0)
        self.l = scene["rod"]["length"]
        self.m_k = scene["rod"]["mass"]
        self.z = scene["rod"]["com_from_wrist_pin"]
        self.I_G = scene["rod"]["inertia_about_wrist_pin"] - self.m_k * self.z ** 2
        self.m_o = scene["piston"]["mass"]
        self.I_w = (scene.get("flywheel") or {}).get("inertia", 0.0)
        gas = scene.get("gas")
        self.gas = None
        if gas:
            self.gas = (gas["cycle_angles"], gas["pressures"], gas["cycle"], math.pi * gas["bore"] ** 2 / 4,
                        eng["firing_angles"])
        self.U0 = 0.0
        self.U0 = self.potential(0.0)

    def kin(self, cy, phi):
        """Closed forms at crank angle phi, derivatives with respect to theta (= with respect to phi):
        x_p, x', x'', beta, beta', beta'', and the rod's centre of mass G in (e, n) coordinates with G', G''."""
        r, l, z = self.r, self.l, self.z
        th = phi + cy.c
        s, co = math.sin(th), math.cos(th)
        sb = (r * s - cy.d) / l
        cb = math.sqrt(1.0 - sb * sb)
        b1 = r * co / (l * cb)                          # beta'
        b2 = -r * s / (l * cb) + b1 * b1 * sb / cb       # beta''
        x = r * co + l * cb
        x1 = -r * s - l * sb * b1
        x2 = -r * co - l * cb * b1 * b1 - l * sb * b2
        G = (x - z * cb, cy.d + z * sb)
        G1 = (x1 + z * sb * b1, z * cb * b1)
        G2 = (x2 + z * cb * b1 * b1 + z * sb * b2, -z * sb * b1 * b1 + z * cb * b2)
        return th, x, x1, x2, math.asin(sb), b1, b2, G, G1, G2

    def inertia(self, phi):
        """J [kg m^2] and J' [kg m^2/rad]."""
        J = self.I_w
        dJ = 0.0
        for cy in self.cyl:
            _, _, x1, x2, _, b1, b2, _, G1, G2 = self.kin(cy, phi)
            J += (self.m_o * x1 * x1 + self.m_k * (G1[0] ** 2 + G1[1] ** 2) + self.I_G * b1 * b1
                  + self.m_s * self.r_s ** 2 + self.m_p * self.r_p ** 2)
            dJ += 2.0 * (self.m_o * x1 * x2 + self.m_k * (G1[0] * G2[0] + G1[1] * G2[1]) + self.I_G * b1 * b2)
        return J, dJ

    def potential(self, phi):
        """U [J]: the mechanism's gravitational energy relative to phi = 0 (gravity along -Y)."""
        V = 0.0
        for cy in self.cyl:
            th, x, _, _, _, _, _, G, _, _ = self.kin(cy, phi)
            ey, ny = cy.e[1], cy.n[1]
            V += self.m_o * (x * ey + cy.d * ny) + self.m_k * (G[0] * ey + G[1] * ny)
            V += (self.m_s * self.r_s - self.m_p * self.r_p) * math.sin(cy.g + th)
        return self.grav * V - self.U0

    def gravity_torque(self, phi):
        """Q = dU/dphi [N m]."""
        Q = 0.0
        for cy in self.cyl:
            th, _, x1, _, _, _, _, _, G1, _ = self.kin(cy, phi)
            ey, ny = cy.e[1], cy.n[1]
            Q += self.m_o * x1 * ey + self.m_k * (G1[0] * ey + G1[1] * ny)
            Q += (self.m_s * self.r_s - self.m_p * self.r_p) * math.cos(cy.g + th)
        return self.grav * Q

    def gas_force(self, j, phi):
        """p_j A [N], toward the crank; 0 without a [gas] table."""
        if self.gas is None:
            return 0.0
        angles, pressures, cycle, area, firing = self.gas
        a = math.fmod(phi - firing[j], cycle)
        if a < 0.0:
            a += cycle
        for i in range(len(angles)):
            a0 = angles[i]
            a1 = angles[i + 1] if i + 1 < len(angles) else cycle
            p1 = pressures[i + 1] if i + 1 < len(angles) else pressures[0]
            if a < a1 or i + 1 == len(angles):
                return area * (pressures[i] + (p1 - pressures[i]) * (a - a0) / (a1 - a0))
        return 0.0

    def gas_torque(self, phi):
        """The gas forces' torque on the crank about +Z: -sum p_j A dx_p/dphi (virtual work)."""
        if self.gas is None:
            return 0.0
        return -sum(self.gas_force(j, phi) * self.kin(cy, phi)[2] for j, cy in enumerate(self.cyl))

    def values(self, phi, w, acc, gas, grav_on):
        """Per-cylinder x_p, v_p, a_p, the rod's angle, speed and acceleration and the reactions, and the bearing force, at the state (phi, w) with phi'' = acc."""
        g = (0.0, -self.grav if grav_on else 0.0)

        def glob(cy, a_e, a_n):
            return (a_e * cy.e[0] + a_n * cy.n[0], a_e * cy.e[1] + a_n * cy.n[1])

        def cross(a, b):
            return a[0] * b[1] - a[1] * b[0]

        cylinders = []
        bearing = [0.0, 0.0]
        for j, cy in enumerate(self.cyl):
            th, x, x1, x2, beta, b1, b2, G, G1, G2 = self.kin(cy, phi)
            v_p = x1 * w
            a_p = x2 * w * w + x1 * acc
            pA = self.gas_force(j, phi) if gas else 0.0
            # Piston (a particle at A, on its line): m_o a_p e = F_w + N_w n - p A e + m_o g.
            Fe = self.m_o * a_p + pA - self.m_o * (g[0] * cy.e[0] + g[1] * cy.e[1])
            # Rod: m_k a_G = F_c - F_w + m_k g; about G: I_G psi'' = (B - G) x F_c - (A - G) x F_w, psi = -beta + const.
            aG = glob(cy, G2[0] * w * w + G1[0] * acc, G2[1] * w * w + G1[1] * acc)
            beta_dd = b2 * w * w + b1 * acc
            sb, cb = math.sin(beta), math.cos(beta)
            BG = glob(cy, -(self.l - self.z) * cb, (self.l - self.z) * sb)   # B - G
            mk_ag = (self.m_k * (aG[0] - g[0]), self.m_k * (aG[1] - g[1]))
            # (B - A) x F_w = -l sin(beta) Fe - l cos(beta) Fn with F_w = Fe e + Fn n.
            Fn = (-self.I_G * beta_dd - cross(BG, mk_ag) + self.l * sb * Fe) / (-self.l * cb)
            Fw = glob(cy, Fe, Fn)
            Nw = -Fn - self.m_o * (g[0] * cy.n[0] + g[1] * cy.n[1])
            Fc = (mk_ag[0] + Fw[0], mk_ag[1] + Fw[1])
            # Crank throw masses (points at radius r_s and -r_p on the crank line): their share of the bearing force.
            ang = cy.g + th
            u = (math.cos(ang), math.sin(ang))
            up = (-u[1], u[0])
            mr = self.m_s * self.r_s - self.m_p * self.r_p
            mass = self.m_s + self.m_p
            for i in range(2):
                bearing[i] += mr * (-w * w * u[i] + acc * up[i]) - mass * g[i] + Fc[i]
            cylinders.append({"x_p": x, "v_p": v_p, "a_p": a_p, "crank_pin_force": list(Fc),
                              "wrist_pin_force": list(Fw), "wall_force": Nw, "rod_angle": beta,
                              "rod_omega": b1 * w, "rod_alpha": beta_dd})
        return cylinders, bearing


def fail(message, status=2):
    print("rk4_reduced.py: " + message, file=sys.stderr, flush=True)
    sys.exit(status)


def answer(request):
    try:
        engine = Engine(request["scene"])
        drive = request["drive"]
        gas = bool(request.get("gas", False))
        grav_on = bool(request.get("gravity", True))
        load = float(request.get("load_torque", 0.0)) if drive == "loaded" else 0.0
        phi0 = float(request["phi0"])
        omega0 = float(request["omega0"])
        t_end = float(request["t_end"])
        interval = float(request["output_interval"])
        quantities = set(request.get("quantities", []))
        dt = request["dt"]
    except (KeyError, TypeError, ValueError, IndexError) as error:
        fail("a request without a usable %s" % error)
    if drive not in ("free", "held", "loaded"):
        fail("unknown drive %r (free, held or loaded)" % drive)
    if gas and engine.gas is None:
        fail("the request asks for gas but the scene has no gas table")
    if not t_end > 0.0 or not interval > 0.0:
        fail("t_end and output_interval must be > 0")
    if dt == "own":
        if omega0 == 0.0:
            fail('dt "own" needs omega0 != 0 (a step of 1/720 revolution)')
        steps = max(1, math.ceil(t_end / (2.0 * math.pi / (720.0 * abs(omega0))) - 1e-9))
        dt = t_end / steps
    else:
        dt = float(dt)
        if not dt > 0.0:
            fail("dt must be > 0 or \"own\"")
        steps = max(1, math.ceil(t_end / dt - 1e-9))
    every = max(1, round(interval / dt))

    def accel(phi, w):
        J, dJ = engine.inertia(phi)
        torque = -load - 0.5 * dJ * w * w
        if grav_on:
            torque -= engine.gravity_torque(phi)
        if gas:
            torque += engine.gas_torque(phi)
        return torque / J

    def sample(n, phi, w):
        s = {"t": n * dt, "phi": phi, "omega": w}
        if drive == "held":
            _, dJ = engine.inertia(phi)
            acc = 0.0
            torque = 0.5 * dJ * w * w
            if grav_on:
                torque += engine.gravity_torque(phi)
            if gas:
                torque -= engine.gas_torque(phi)
            if "drive_torque" in quantities:
                s["drive_torque"] = torque
        else:
            acc = accel(phi, w)
        per_cylinder = {"x_p", "v_p", "a_p", "crank_pin_force", "wrist_pin_force", "wall_force", "rod_angle",
                        "rod_omega", "rod_alpha"} & quantities
        if per_cylinder or "bearing_force" in quantities:
            cylinders, bearing = engine.values(phi, w, acc, gas, grav_on)
            if "bearing_force" in quantities:
                s["bearing_force"] = bearing
            if per_cylinder:
                s["cylinders"] = [{k: c[k] for k in per_cylinder} for c in cylinders]
        return s

    phi, w = phi0, omega0
    samples = [sample(0, phi, w)]
    for n in range(1, steps + 1):
        if drive == "held":
            phi, w = phi0 + omega0 * n * dt, omega0
        else:
            k1p, k1w = w, accel(phi, w)
            k2p, k2w = w + 0.5 * dt * k1w, accel(phi + 0.5 * dt * k1p, w + 0.5 * dt * k1w)
            k3p, k3w = w + 0.5 * dt * k2w, accel(phi + 0.5 * dt * k2p, w + 0.5 * dt * k2w)
            k4p, k4w = w + dt * k3w, accel(phi + dt * k3p, w + dt * k3w)
            phi += dt / 6.0 * (k1p + 2.0 * k2p + 2.0 * k3p + k4p)
            w += dt / 6.0 * (k1w + 2.0 * k2w + 2.0 * k3w + k4w)
            if not (math.isfinite(phi) and math.isfinite(w)):
                fail("the run diverged at t = %g s (step too large?)" % (n * dt), 1)
        if n % every == 0 or n == steps:
            samples.append(sample(n, phi, w))
    return {"samples": samples}


def main():
    for line in sys.stdin:
        if not line.strip():
            continue
        try:
            request = json.loads(line)
        except json.JSONDecodeError as error:
            fail("a request line that is not JSON: %s" % error)
        if not isinstance(request, dict):
            fail("a request line that is not a JSON object")
        print(json.dumps(answer(request), allow_nan=False), flush=True)


if __name__ == "__main__":
    main()
