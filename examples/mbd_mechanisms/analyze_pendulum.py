#!/usr/bin/python3
"""Checks an `fsi-server --mbd-only` run of damped_pendulum.scene (DIR/sensors.csv): the damper's
`work` sensor equals the change of kinetic + potential energy at every row (the damper is the only
force that is not conservative) to --tolerance J/m (default 1e-8: measured 2.4e-9 at the scene's
h = 1e-3 s, 2026-12-07; 5.4e-7 when the sensor summed the trapezoids of the rows), it never rises (a damper only takes energy), and the pendulum, let go from
the horizontal, has lost part of its energy but not all of it by the end. Prints one line per
check; exit status 1 if one fails."""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from fsi_results import Checks, closed_form_run  # noqa: E402 (examples/fsi_results.py)


def main():
    args, _, s, params = closed_form_run(__doc__, 1e-8, "largest |work - energy change| [J/m]")
    released = float(params["Geometry.m"]) * 9.81 * 0.5 * float(params["Geometry.L"])  # to the lowest point
    energy = [k + p for k, p in zip(s["kinetic"], s["potential"])]
    gaps = [abs(w - (e - energy[0])) for w, e in zip(s["damper_work"], energy)]
    worst = max(range(len(gaps)), key=gaps.__getitem__)
    work = s["damper_work"]
    checks = Checks(digits=".4g", against="expected")
    checks.check(f"largest |work - energy change| [J/m] (t = {s['time'][worst]:g} s)", gaps[worst], 0.0,
                 args.tolerance)
    rises = max((b - a for a, b in zip(work, work[1:])), default=0.0)
    checks.check("largest rise of the damper's work between rows [J/m]", max(rises, 0.0), 0.0, 0.0)
    print(f"     the damper's work at t = {s['time'][-1]:g} s: {work[-1]:.6f} J/m "
          f"(energy change {energy[-1] - energy[0]:.6f} J/m; m g L/2 = {released:.4f} J/m)")
    checks.check("share of m g L/2 the damper took by the end", -work[-1] / released, 0.5, 0.45)
    checks.exit()


if __name__ == "__main__":
    main()
