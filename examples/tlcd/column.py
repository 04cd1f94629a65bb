#!/usr/bin/python3
"""The TLCD's column alone, for the linear model (linear_model.py, MEASURED_COLUMN): the free
oscillation of the same U-tube (examples/u_tube, the tube at rest) filled to each level, with the
fluid the TLCD's scene would have at that fill — c = 10 sqrt(2 g fill) (the Fluid block's rule) and
the step of tlcd_model.inc (Resolution.time_step of tlcd_coarse.scene, shortened as sqrt(0.14/fill)
above 0.14 m). examples/u_tube/analyze.py measures each: the natural period against linear theory
and the damping ratio of a damped sinusoid fitted to the swing (25 mm at the release).

  column.py [--scene examples/u_tube/u_tube_coarse.scene] [--output out/tlcd_column] [--np 2]
            [--fills 0.11,0.14,0.17,0.20]

Each run is skipped when its folder (OUTPUT/fill_<f>) already holds a completed run. Prints a row
per fill and the MEASURED_COLUMN line for linear_model.py (the column's frequency above linear
theory, 1 / (1 + period error) - 1, and its damping ratio). Exit status 1 when a run failed."""
import json
import math
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(HERE))
from fsi_results import fsi_run_binary, run_variant, study_arguments  # noqa: E402

import linear_model  # noqa: E402

G = 9.81
TIME_STEP, TUNED_FILL, END_TIME = 5e-5, 0.14, 2.1   # tlcd_coarse.scene's step; u_tube_coarse's end


def settings(fill):
    """The --set of the U-tube run at `fill`: the TLCD's c and step there."""
    steps = round(END_TIME / (TIME_STEP * min(1.0, math.sqrt(TUNED_FILL / fill))) + 0.4)
    return [("Geometry.fill", fill), ("LIGGGHTS_SPH_parameters.cAB", round(10 * math.sqrt(2 * G * fill), 3)),
            ("Resolution.end_time", END_TIME), ("Resolution.time_step", END_TIME / steps)]


def main():
    parser = study_arguments(__doc__, os.path.join(HERE, "..", "u_tube", "u_tube_coarse.scene"),
                             os.path.join("out", "tlcd_column"))
    parser.add_argument("--fills", default="0.11,0.14,0.17,0.20", help="fill levels [m], comma-separated")
    args = parser.parse_args()
    fills = linear_model.fill_levels(parser, args.fills)
    fsi_run = fsi_run_binary(args, "column.py")
    failed, measured = [], {}
    for fill in fills:
        run = os.path.join(args.output, f"fill_{fill:g}")
        if not run_variant(fsi_run, args.scene, run, args.np, settings(fill)):
            failed.append(run)
            continue
        analyze = os.path.join(HERE, "..", "u_tube", "analyze.py")
        if subprocess.run([sys.executable, analyze, run], stdout=subprocess.DEVNULL).returncode != 0:
            failed.append(run)
            continue
        with open(os.path.join(run, "analysis.json")) as handle:
            result = json.load(handle)
        measured[fill] = (1.0 / (1.0 + result["period_error"]) - 1.0, result["damping_ratio"])
        print(f"fill {fill:g} m: natural period {result['period']:.4f} s, {100 * result['period_error']:+.2f} % against "
              f"linear theory ({result['period_theory']:.4f} s); damping ratio {result['damping_ratio']:.4f}", flush=True)
    if measured:
        print("MEASURED_COLUMN = {" + ", ".join(f"{f:g}: ({s:.4f}, {z:.4f})" for f, (s, z) in measured.items()) + "}")
    if failed:
        sys.exit(f"column.py: {len(failed)} run(s) failed: {', '.join(failed)}")


if __name__ == "__main__":
    main()
