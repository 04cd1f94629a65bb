#!/usr/bin/python3
"""Frames of a pump run like the thesis' Figs 6.12-6.13: fsi-plot renders the snapshots nearest to
the given times (the loop's window, coloured by speed), and this script sets them side by side.

  frames.py RUN_DIR [--times T1,T2,...] [--columns N] [--output PNG] [--build DIR]

Default: one piston period, from 0.6 s (the second) every 0.1 s, three columns, into
RUN_DIR/pump_frames.png. The frames themselves stay in RUN_DIR/frames/frames/."""
import argparse
import glob
import os
import subprocess
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from fsi_results import pyplot  # noqa: E402

WINDOW = "0,0.3,0,0.2"  # the loop without the dry space above the reservoir's walls


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("run_dir")
    parser.add_argument("--times", default="0.6,0.7,0.8,0.9,1.0,1.1")
    parser.add_argument("--columns", type=int, default=3)
    parser.add_argument("--output")
    parser.add_argument("--build", default=os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "build"))
    args = parser.parse_args()
    fsi_plot = os.path.join(args.build, "bin", "fsi-plot")
    if not os.access(fsi_plot, os.X_OK):
        raise SystemExit(f"frames.py: no fsi-plot at {fsi_plot}; build first (cmake --build build) or give --build")
    folder = os.path.join(args.run_dir, "frames")
    for old in glob.glob(os.path.join(folder, "frames", "frame_*.png")):
        os.remove(old)
    subprocess.run([fsi_plot, args.run_dir, "--frames", args.times, "--window", WINDOW, "--dpi", "70",
                    "--output", folder], check=True, stdout=subprocess.DEVNULL)
    frames = sorted(glob.glob(os.path.join(folder, "frames", "frame_*.png")))
    plt = pyplot("frames.py")
    if plt is None or not frames:
        raise SystemExit(f"frames.py: no frames in {folder}/frames (does {args.run_dir} hold snapshots?)")
    rows = (len(frames) + args.columns - 1) // args.columns
    figure, axes = plt.subplots(rows, args.columns, figsize=(4.4 * args.columns, 2.6 * rows), squeeze=False)
    for axis in axes.flat:
        axis.axis("off")
    for axis, path in zip(axes.flat, frames):
        axis.imshow(plt.imread(path))
    figure.tight_layout(pad=0.2)
    output = args.output or os.path.join(args.run_dir, "pump_frames.png")
    figure.savefig(output, dpi=75)
    print(f"figure: {output} ({len(frames)} frames)")


if __name__ == "__main__":
    main()
