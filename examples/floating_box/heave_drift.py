#!/usr/bin/python3
"""The largest heave excursion of the box from where it started, max |box_y(t) - box_y(0)| [m],
and the largest heave speed [m/s], from DIR/sensors.csv; written to DIR/analysis.json as
heave_drift and heave_speed. A box started at its own equilibrium stays near it when the coupling
is stable; the added-mass instability makes the excursion grow (examples/floating_box/
stability_map.json, README "Made light"). Usage: heave_drift.py DIR"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from fsi_results import read_run, write_analysis  # noqa: E402 (examples/fsi_results.py)


def main():
    if len(sys.argv) != 2:
        print(__doc__, file=sys.stderr)
        return 2
    run_dir = sys.argv[1]
    _, sensors = read_run(run_dir)
    y, vy = sensors["box_y"], sensors["box_vy"]
    drift = max(abs(value - y[0]) for value in y)
    speed = max(abs(value) for value in vy)
    print(f"box heave: largest excursion from the start {drift:.4g} m, largest speed {speed:.4g} m/s "
          f"over {sensors['time'][-1]:.4g} s")
    write_analysis(run_dir, {"heave_drift": drift, "heave_speed": speed, "end_time": sensors["time"][-1]})
    return 0


if __name__ == "__main__":
    sys.exit(main())
