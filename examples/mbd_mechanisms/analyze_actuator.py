#!/usr/bin/python3
"""Checks an `fsi-server --mbd-only` run of actuator.scene (DIR/sensors.csv): the cart's offset
e = x - 1 against the closed form of m e'' = -k (e - a sin w t) from rest,
e = A (sin w t - w/w0 sin w0 t), A = a w0^2 / (w0^2 - w^2), w0 = sqrt(k/m), at every row to
--tolerance m (default 1e-8: measured 1.1e-14 at h = 1e-3 s, 2026-12-07); the actuator's tension
k (e - a sin w t) at every row; and its work sensor against the cart's kinetic energy (the only
force doing work on the cart; to 1e-12 J/m, measured 9.8e-15 at h = 1e-3 s, 2026-12-07; 4.9e-7
when the sensor summed the trapezoids of the rows). Prints one line per check; exit status 1 if one fails."""
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from fsi_results import Checks, closed_form_run  # noqa: E402 (examples/fsi_results.py)


def main():
    args, _, s, params = closed_form_run(__doc__, 1e-8, "largest |e - closed form| [m]")
    k, a, w, m = (float(params["Geometry." + name]) for name in ("k", "a", "w", "m"))
    w0 = math.sqrt(k / m)
    amplitude = a * w0 * w0 / (w0 * w0 - w * w)
    checks = Checks(digits=".4g", against="expected")
    offsets = [x - 1.0 for x in s["cart_x"]]
    exact = [amplitude * (math.sin(w * t) - w / w0 * math.sin(w0 * t)) for t in s["time"]]
    checks.check("largest |offset - closed form| [m]", max(abs(e - f) for e, f in zip(offsets, exact)), 0.0,
                 args.tolerance)
    tension = [k * (e - a * math.sin(w * t)) for e, t in zip(offsets, s["time"])]
    checks.check("largest |tension - k (e - a sin w t)| [N/m]",
                 max(abs(f - g) for f, g in zip(s["actuator_tension"], tension)), 0.0, 1e-9)
    checks.check("largest |work - kinetic energy| [J/m]",
                 max(abs(wk - ke) for wk, ke in zip(s["actuator_work"], s["kinetic"])), 0.0, 1e-12)
    print(f"     largest offset {max(abs(e) for e in offsets):.6f} m, largest kinetic energy "
          f"{max(s['kinetic']):.6f} J/m")
    checks.exit()


if __name__ == "__main__":
    main()
