#!/usr/bin/python3
"""Is the 13 cm water column at rest when it is released? Prints, from DIR/run.json and
DIR/sensors.csv, the check at release (settling drag, weight carried by the walls, kinetic over
potential energy) and the weight the walls carry over the coupled run, and exits 1 when the floor
carries less than --min-fraction of the weight at release.

Usage: analyze.py DIR [--min-fraction 0.99]"""
import argparse
import csv
import json
import os
import sys


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("run_dir")
    parser.add_argument("--min-fraction", type=float, default=0.99)
    args = parser.parse_args()
    with open(os.path.join(args.run_dir, "run.json")) as handle:
        run = json.load(handle)
    release = run.get("release")
    if release is None:
        print("analyze: run.json has no 'release' (an fsi-client of protocol 1.1?)")
        return 1
    weight = release["weight"]
    print(f"settling drag {release['settling_drag']:.4g} 1/s, H = {release['column_height']:.4g} m, "
          f"weight M g = {weight:.6g} N/m")
    print(f"at release: the walls carry {100 * release['weight_fraction']:.2f} % of the weight, "
          f"kinetic / potential energy {release['kinetic_over_potential']:.3e}, "
          f"at rest: {release['at_rest']}")
    with open(os.path.join(args.run_dir, "sensors.csv")) as handle:
        rows = list(csv.DictReader(line for line in handle if not line.startswith("#")))
    carried = [-float(row["total_fluid_force_y"]) / weight for row in rows]
    print(f"coupled run, {len(rows)} rows to t = {float(rows[-1]['time']):.4g} s: the walls carry "
          f"{100 * min(carried):.2f} .. {100 * max(carried):.2f} % of the weight")
    if release["weight_fraction"] < args.min_fraction:
        print(f"FAIL: {100 * release['weight_fraction']:.2f} % < {100 * args.min_fraction:.0f} % at release")
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
