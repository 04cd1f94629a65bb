#!/usr/bin/python3
"""Checks an `fsi-server --mbd-only` run of turek_hron_csm3.scene (DIR/sensors.csv) against Turek &
Hron's (2006) CSM3 values for point A over the settled swing (t >= 5 s): uy = -63.607 +- 65.160 mm,
ux = -14.305 +- 14.305 mm, 1.0995 Hz. Tolerance 1 % of each amplitude and of the frequency (the
scene's 8 elements at 0.005 s are within 0.3 %). Prints one line per check; exit status 1 if one
fails."""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from fsi_results import Checks, read_run, zero_crossings  # noqa: E402 (examples/fsi_results.py)


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: analyze_csm3.py RUN_DIR")
    run, s = read_run(sys.argv[1])
    length = float(run["parameters_flat"]["Geometry.L"])
    rows = [k for k, t in enumerate(s["time"]) if t >= 5.0]
    if len(rows) < 100:
        sys.exit("analyze_csm3.py: the run must reach t = 10 s (the benchmark's swing from 5 s on)")
    time = [s["time"][k] for k in rows]
    uy = [s["A_y"][k] for k in rows]
    ux = [s["A_x"][k] - length for k in rows]
    checks = Checks(digits=".4f", against="benchmark", tolerance_digits=".3g")
    check = checks.check

    for name, values, mean, amplitude in (("uy", uy, -63.607, 65.160), ("ux", ux, -14.305, 14.305)):
        high, low = 1e3 * max(values), 1e3 * min(values)
        check(f"point A {name} mean [mm]", 0.5 * (high + low), mean, 0.01 * amplitude)
        check(f"point A {name} amplitude [mm]", 0.5 * (high - low), amplitude, 0.01 * amplitude)
    centre = 0.5 * (max(uy) + min(uy))
    crossings = zero_crossings(time, [v - centre for v in uy])  # two per period
    frequency = (len(crossings) - 1) / (2.0 * (crossings[-1] - crossings[0]))
    check("frequency [Hz]", frequency, 1.0995, 0.01 * 1.0995)
    checks.exit()


if __name__ == "__main__":
    main()
