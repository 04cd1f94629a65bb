#!/usr/bin/python3
"""The thesis' four fibre runs (Figs 7.9 and 7.10): low and high viscosity of the fluid times low
and high bending stiffness of the fibres, one after another, then analyze.py over all four.

  run_four.py [--scene fibres_coarse.scene] [--output out/fibres_four] [--np 2] [--end-time T]
              [--nu-low 5e-5] [--nu-high 5e-4] [--ei-low 2e-6] [--ei-high 2e-4] [--until T]

Each run goes to OUTPUT/nu_<nu>_ei_<EI> (fsi-run --set Fibres.viscosity=... --set
Fibres.bending_stiffness=...); a run whose folder already holds a completed run.json is not run
again. The figures: OUTPUT/fibres_speed.png and OUTPUT/fibres_tips.png; analyze.py prints each
run's numbers (a run stopped by a health check with its sensors up to the stop). Exit status 1
when a run failed (its fsi-server.log says why)."""
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(HERE))
from fsi_results import fsi_run_binary, run_variant, study_arguments  # noqa: E402


def main():
    parser = study_arguments(__doc__, os.path.join(HERE, "fibres_coarse.scene"), os.path.join("out", "fibres_four"))
    parser.add_argument("--nu-low", type=float, default=5e-5)
    parser.add_argument("--nu-high", type=float, default=5e-4)
    parser.add_argument("--ei-low", type=float, default=2e-6)
    parser.add_argument("--ei-high", type=float, default=2e-4)
    parser.add_argument("--until", type=float, help="analyse t <= this only (analyze.py --until)")
    args = parser.parse_args()
    fsi_run = fsi_run_binary(args, "run_four.py")
    run_dirs = []
    failed = []
    for nu in (args.nu_high, args.nu_low):
        for ei in (args.ei_high, args.ei_low):
            run_dir = os.path.join(args.output, f"nu_{nu:g}_ei_{ei:g}")
            run_dirs.append(run_dir)
            settings = [("Fibres.viscosity", nu), ("Fibres.bending_stiffness", ei)]
            if args.end_time is not None:
                settings.append(("Resolution.end_time", args.end_time))
            if not run_variant(fsi_run, args.scene, run_dir, args.np, settings):
                failed.append(run_dir)
                print("run_four.py: its sensors up to the stop are analysed with the others", flush=True)
    analysis = [sys.executable, os.path.join(HERE, "analyze.py"), *run_dirs,
                "--figure-prefix", os.path.join(args.output, "fibres")]
    if args.until is not None:
        analysis += ["--until", repr(args.until)]
    status = subprocess.run(analysis).returncode
    if failed:
        sys.exit(f"run_four.py: {len(failed)} run(s) failed: {', '.join(failed)}")
    sys.exit(status)


if __name__ == "__main__":
    main()
