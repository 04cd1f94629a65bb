#!/usr/bin/python3
"""Checks an `fsi-server --mbd-only` run of elastica.scene (DIR/sensors.csv) against the
inextensible elastica: the tip's u/L = (L - x)/L, v/L, its angle and the clamp's moment P x_tip
once the damped beam has settled (the last two rows 1 s apart agree to 1e-8 L). The table is
/work/shared/reference-data/elastica_inextensible_tip_load_computed.dat (RK4 shooting; the lam = 10
row is Mattiasson's 1981 value). Tolerance 5e-4 in u/L and v/L, 2e-4 rad (the scene's 16 elements
are within 5e-5). Prints one line per check; exit status 1 if one fails."""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from fsi_results import Checks, read_run  # noqa: E402 (examples/fsi_results.py)

# lam: (u/L, v/L, tip angle [rad], kappa_0 L)
TABLE = {0.1: (0.00067, 0.03330, 0.049954, 0.099933), 0.5: (0.01592, 0.16214, 0.244534, 0.492041),
         1.0: (0.05643, 0.30172, 0.461352, 0.943567), 2.0: (0.16064, 0.49346, 0.781750, 1.678717),
         3.0: (0.25442, 0.60325, 0.986017, 2.236739), 4.0: (0.32894, 0.66996, 1.121239, 2.684235),
         5.0: (0.38763, 0.71379, 1.215368, 3.061858), 6.0: (0.43459, 0.74457, 1.283697, 3.392467),
         7.0: (0.47293, 0.76737, 1.334960, 3.689508), 8.0: (0.50483, 0.78498, 1.374432, 3.961378),
         9.0: (0.53182, 0.79906, 1.405465, 4.213615), 10.0: (0.55500, 0.81061, 1.430286, 4.450044)}


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: analyze_elastica.py RUN_DIR")
    run, s = read_run(sys.argv[1])
    params = run["parameters_flat"]
    lam, length, ei = float(params["Geometry.lam"]), float(params["Geometry.L"]), float(params["Geometry.EI"])
    if lam not in TABLE:
        sys.exit(f"analyze_elastica.py: lam = {lam} is not in the table; use one of {sorted(TABLE)}")
    u_ref, v_ref, angle_ref, moment_ref = TABLE[lam]
    checks = Checks(digits=".6f", against="elastica")
    check = checks.check

    time = s["time"]
    before = max(k for k, t in enumerate(time) if t <= time[-1] - 1.0 + 1e-9)
    moved = max(abs(s[name][-1] - s[name][before]) for name in ("tip_x", "tip_y"))
    check("settled: tip moved in the last second [m]", moved, 0.0, 1e-8 * length)
    check("u/L", (length - s["tip_x"][-1]) / length, u_ref, 5e-4)
    check("v/L", -s["tip_y"][-1] / length, v_ref, 5e-4)
    check("tip angle [rad]", -s["tip_angle"][-1], angle_ref, 2e-4)
    check("clamp moment M L / EI", s["root_moment"][-1] * length / ei, moment_ref, 5e-4 * moment_ref)
    checks.exit()


if __name__ == "__main__":
    main()
