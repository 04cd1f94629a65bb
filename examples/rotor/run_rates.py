#!/usr/bin/python3
"""The rotor at several rotation rates (thesis Figs 7.3-7.5): one run per rate, one after another,
then analyze.py over all of them (the flux against the rate, the centre's trajectories).

  run_rates.py [--scene rotor_coarse.scene] [--output out/rotor_rates] [--np 2]
               [--rates 10 20 40] [--end-time T]

Each run goes to OUTPUT/rate_<w> (fsi-run --set Rotor.rate=w); a run whose folder already holds a
completed run.json is not run again. The figures: OUTPUT/rotor_flux.png, OUTPUT/rotor_trajectory.png
and OUTPUT/rotor_hub.png. Exit status 1 when a run failed (its fsi-server.log says why) or when the
flux does not grow with the rate (analyze.py --require-growth)."""
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(HERE))
from fsi_results import fsi_run_binary, run_variant, study_arguments  # noqa: E402


def main():
    parser = study_arguments(__doc__, os.path.join(HERE, "rotor_coarse.scene"), os.path.join("out", "rotor_rates"))
    parser.add_argument("--rates", type=float, nargs="+", default=[10.0, 20.0, 40.0],
                        help="rotation rates [rad/s] (the scene runs healthy up to 40 rad/s; at 80 the density check stops the run: -3.1 %%)")
    args = parser.parse_args()
    fsi_run = fsi_run_binary(args, "run_rates.py")
    if len(args.rates) < 2:
        sys.exit("run_rates.py: --rates needs at least two rates to compare")
    run_dirs, failed = [], []
    for rate in sorted(args.rates):
        run_dir = os.path.join(args.output, f"rate_{rate:g}")
        settings = [("Rotor.rate", rate)]
        if args.end_time is not None:
            settings.append(("Resolution.end_time", args.end_time))
        if run_variant(fsi_run, args.scene, run_dir, args.np, settings):
            run_dirs.append(run_dir)
        else:
            failed.append(run_dir)
    if run_dirs:
        analysis = [sys.executable, os.path.join(HERE, "analyze.py"), *run_dirs,
                    "--figure-prefix", os.path.join(args.output, "rotor"), "--require-growth"]
        if subprocess.run(analysis).returncode != 0:
            failed.append("the analysis")
    if failed:
        sys.exit(f"run_rates.py: failed: {', '.join(failed)}")


if __name__ == "__main__":
    main()
