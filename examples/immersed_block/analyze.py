#!/usr/bin/python3
"""Immersed block: the mean vertical fluid force on a block held fully under water against
Archimedes' buoyancy rho0 g a^2 (per unit depth), over the settled interval of the run.

  analyze.py RUN_DIR [--settle-start T] [--tolerance F]

The block is drawn with its true outline; a wall law that keeps the fluid off by a stand-off s
inflates it to (a + 2s)^2 (docs/theory.md, "The true shape")."""
import argparse
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from fsi_results import read_run, write_analysis  # noqa: E402


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("run_dir")
    parser.add_argument("--settle-start", type=float,
                        help="the averaging interval starts here [s] (default: half the run's "
                             "end time; the switch from equilibration to the coupled run rings "
                             "for about 0.1 s, which an earlier start would average in)")
    parser.add_argument("--tolerance", type=float, help="fail if |F / (rho0 g V) - 1| exceeds this")
    args = parser.parse_args()

    run, sensors = read_run(args.run_dir)
    params = run["parameters_flat"]
    side = params["Geometry.side"]
    rho0 = run["fluid"]["density"]
    g = abs(run["model"]["gravity"][1])
    buoyancy = rho0 * g * side * side
    time = sensors["time"]
    if args.settle_start is None:
        args.settle_start = 0.5 * time[-1]
    window = [i for i, t in enumerate(time) if t >= args.settle_start]
    if len(window) < 10:
        print(f"analyze: only {len(window)} samples after {args.settle_start} s; run longer", file=sys.stderr)
        return 1
    force = sum(sensors["block_fluid_force_y"][i] for i in window) / len(window)
    sideways = sum(sensors["block_fluid_force_x"][i] for i in window) / len(window)
    ratio = force / buoyancy
    # The stand-off s that would explain the ratio on a square: (a + 2 s)^2 = ratio a^2.
    stand_off = 0.5 * side * (ratio ** 0.5 - 1.0) if ratio > 0 else float("nan")
    spacing = params["LIGGGHTS_SPH_parameters.particlespacing"]
    result = {"buoyancy_exact": buoyancy, "mean_fluid_force_y": force, "ratio": ratio,
              "mean_fluid_force_x": sideways, "equivalent_stand_off": stand_off,
              "equivalent_stand_off_over_spacing": stand_off / spacing,
              "interval": [args.settle_start, time[-1]], "samples": len(window)}
    print(f"block {side} m square, d = {spacing} m: mean fluid force {force:.5g} N/m over "
          f"{args.settle_start}..{time[-1]:.3f} s ({len(window)} samples), rho0 g V = {buoyancy:.5g} N/m, "
          f"ratio {ratio:.4f} (equivalent stand-off {stand_off / spacing:+.3f} d); sideways {sideways:.3g} N/m")
    write_analysis(args.run_dir, result)
    if args.tolerance is not None and abs(ratio - 1.0) > args.tolerance:
        print(f"FAIL: ratio {ratio:.4f} outside 1 +- {args.tolerance}")
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
