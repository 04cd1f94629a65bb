#!/usr/bin/python3
"""Checks an `fsi-server --mbd-only` run of door_closer_3d.scene (DIR/sensors.csv): the door's
angle phi (of its free edge about the hinge, from the shut position) against the closed form of
the damped oscillator J phi'' + c phi' + k phi = 0 let go at phi = open turning at spin, J the door's moment of
inertia about the hinge, to --tolerance rad (default 1e-8); the closer's torque against
-k phi - c phi' of the closed form; the closer's `work` sensor against the door's change of
kinetic energy (the closer is the only force that does work: the hinge is vertical, so gravity does
none). Prints one line per check; exit status 1 if one fails."""
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from fsi_results import Checks, closed_form_run  # noqa: E402 (examples/fsi_results.py)


def main():
    args, _, s, params = closed_form_run(__doc__, 1e-8, "largest |phi - closed form| [rad]")
    m, w, b = (float(params[f"Geometry.{key}"]) for key in ("m", "w", "b"))
    k, c, opened, spin = (float(params[f"Geometry.{key}"]) for key in ("k", "c", "open", "spin"))
    inertia = m * (w * w + b * b) / 12 + m * (w / 2) ** 2  # about the hinge
    natural = math.sqrt(k / inertia)
    zeta = c / (2 * math.sqrt(k * inertia))
    damped = natural * math.sqrt(1 - zeta * zeta)

    # phi = exp(-zeta wn t) (A cos wd t + B sin wd t), phi(0) = open, phi'(0) = spin.
    first, second = opened, (spin + zeta * natural * opened) / damped

    def closed_form(t):
        decay = math.exp(-zeta * natural * t)
        cos, sin = math.cos(damped * t), math.sin(damped * t)
        angle = decay * (first * cos + second * sin)
        rate = decay * ((second * damped - zeta * natural * first) * cos
                        - (first * damped + zeta * natural * second) * sin)
        return angle, rate

    exact = [closed_form(t) for t in s["time"]]
    angle = [math.atan2(y, x) for x, y in zip(s["edge_x"], s["edge_y"])]
    checks = Checks(digits=".4g", against="expected")
    print(f"     J about the hinge {inertia:.5f} kg m^2, natural frequency {natural:.5f} rad/s, "
          f"damping ratio {zeta:.4f}")
    gaps = [abs(a - e[0]) for a, e in zip(angle, exact)]
    worst = max(range(len(gaps)), key=gaps.__getitem__)
    checks.check(f"largest |phi - closed form| [rad] (t = {s['time'][worst]:g} s)", gaps[worst], 0.0,
                 args.tolerance)
    torque_gap = max(abs(q - (-k * e[0] - c * e[1])) for q, e in zip(s["closer_torque"], exact))
    checks.check("largest |closer torque - (-k phi - c phi')| [N m]", torque_gap, 0.0, 1e-7)
    energy_gap = max(abs(wk - (kin - s["kinetic"][0])) for wk, kin in zip(s["closer_work"], s["kinetic"]))
    checks.check("largest |closer work - change of kinetic energy| [J]", energy_gap, 0.0, 1e-9)
    dissipated = s["kinetic"][0] + s["potential"][0] - s["kinetic"][-1] - s["potential"][-1]
    print(f"     the door at t = {s['time'][-1]:g} s: {math.degrees(angle[-1]):.4f} degrees open "
          f"(let go at {math.degrees(opened):.1f}); the closer has dissipated {dissipated:.6f} J "
          f"(its spring held {0.5 * k * opened ** 2:.6f} J)")
    checks.check("the door shut by the end [degrees open]", math.degrees(angle[-1]), 0.0, 0.1)
    checks.exit()


if __name__ == "__main__":
    main()
