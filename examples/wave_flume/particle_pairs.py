#!/usr/bin/python3
"""Particle pairs in the corners of a settled tank, and what makes them (docs/theory.md, "Particle
pairs along the walls").

  particle_pairs.py OUT_DIR [--bin DIR] [--only NAME ...]

Runs corner_tank.scene (the wave flume's water and LIGGGHTS scripts in a 0.5 m tank, 320
particles) once per variant below, each 4000 settling steps (unless the variant says otherwise)
and 0.3 s of coupled run, one rank, and prints per variant: how the run ended, the closest pair and
the pairs closer than d/2 right after the settling (t = 0, the first snapshot) and the closest over
the run (fsi-server's own count, run.json "checks") with the largest density deviation of the
snapshots. The variants change one thing each: the settling's length, the density filter of
script 1 (its `fix ... sph/density/corr shepard every N` line: another N, or none), the kernel
(every `spiky2d` of script 1) or the floor corners (corner_tank_rounded.scene, arcs of radius r
instead of right angles). Their scripts are written into OUT_DIR beside the runs; wave_flume.in1
itself is not changed. About half a minute in all.
--bin: the folder of fsi-run (default: the PATH's).
"""
import argparse
import json
import os
import re
import shutil
import subprocess
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
SPACING = 0.025  # corner_tank.scene's Fluid.spacing
FILTER = re.compile(r"^fix\s+density_filter\s+all\s+sph/density/corr\s+shepard\s+every\s+\d+\s*$",
                    re.MULTILINE)

# name: (what it changes, equilibration steps, the filter line's replacement or None, kernel,
# the --set values of corner_tank_rounded.scene (none: corner_tank.scene))
VARIANTS = {
    "as committed": ("Shepard filter every 20 steps, spiky kernel", 4000, None, None, ()),
    "settle 500": ("500 settling steps", 500, None, None, ()),
    "settle 1000": ("1000 settling steps", 1000, None, None, ()),
    "settle 2000": ("2000 settling steps", 2000, None, None, ()),
    "filter every 5": ("Shepard filter every 5 steps", 4000, "every 5", None, ()),
    "filter every 100": ("Shepard filter every 100 steps", 4000, "every 100", None, ()),
    "no filter": ("no density filter (continuity alone)", 4000, "none", None, ()),
    "wendland": ("Wendland kernel (zero gradient at r = 0)", 4000, None, "wendland2d", ()),
    "rounded r = 2 d": ("floor corners rounded, radius 0.05 m", 4000, None, None, ("Tank.r=0.05",)),
    "rounded r = 4 d": ("floor corners rounded, radius 0.1 m", 4000, None, None, ("Tank.r=0.1",)),
    "rounded r = 8 d": ("floor corners rounded, radius 0.2 m", 4000, None, None, ("Tank.r=0.2",)),
}


def script_variant(out_dir, name, filter_change, kernel):
    """wave_flume.in1 with the variant's one change, written into OUT_DIR; its path."""
    with open(os.path.join(HERE, "wave_flume.in1")) as handle:
        text = handle.read()
    if not FILTER.search(text):
        sys.exit("particle_pairs.py: wave_flume.in1 has no 'fix density_filter all sph/density/corr "
                 "shepard every N' line; update FILTER in this script")
    if filter_change == "none":
        text = FILTER.sub("# (no density filter: particle_pairs.py)", text)
    elif filter_change:
        text = FILTER.sub("fix         density_filter all sph/density/corr shepard " + filter_change,
                          text)
    if kernel:
        text = text.replace("spiky2d", kernel)
    path = os.path.join(out_dir, re.sub(r"\W+", "_", name) + ".in1")
    with open(path, "w") as handle:
        handle.write(text)
    return path


def pairs_at_start(run_dir):
    """(closest pair / d, pairs closer than d/2) of the run's first snapshot, or None."""
    path = os.path.join(run_dir, "snapshots", "particles_000000000.csv")
    if not os.path.exists(path):
        return None
    x = np.loadtxt(path, delimiter=",", skiprows=2, usecols=(1, 2))
    distance = np.sqrt(((x[:, None, :] - x[None, :, :]) ** 2).sum(axis=2))
    upper = distance[np.triu_indices(len(x), k=1)]
    return upper.min() / SPACING, int((upper < 0.5 * SPACING).sum())


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("out_dir")
    parser.add_argument("--bin", help="the folder of fsi-run (default: the PATH's)")
    parser.add_argument("--only", nargs="+", choices=sorted(VARIANTS), metavar="NAME")
    args = parser.parse_args()
    fsi_run = os.path.join(args.bin, "fsi-run") if args.bin else shutil.which("fsi-run")
    if not fsi_run or not os.access(fsi_run, os.X_OK):
        sys.exit("particle_pairs.py: no fsi-run (give --bin with the build's bin folder)")
    os.makedirs(args.out_dir, exist_ok=True)
    rows = []
    for name in args.only or VARIANTS:
        what, steps, filter_change, kernel, sets = VARIANTS[name]
        run_dir = os.path.join(args.out_dir, re.sub(r"\W+", "_", name))
        scene = "corner_tank_rounded.scene" if sets else "corner_tank.scene"
        command = [fsi_run, os.path.join(HERE, scene), "--np", "1", "--output", run_dir,
                   "--overwrite", "--no-live", "--set", f"LIGGGHTS.equilibration_steps={steps}"]
        for value in sets:
            command += ["--set", value]
        if filter_change or kernel:
            script = script_variant(args.out_dir, name, filter_change, kernel)
            command += ["--set", f'LIGGGHTS.script1="{os.path.abspath(script)}"']
        with open(run_dir + ".log", "w") as log:
            status = subprocess.run(command, stdout=log, stderr=subprocess.STDOUT).returncode
        with open(os.path.join(run_dir, "run.json")) as handle:
            manifest = json.load(handle)
        checks = manifest["checks"]
        ended = "completed" if status == 0 else (manifest["health"] or {}).get("failed_check") or \
            f"failed (exit {status})"
        start = pairs_at_start(run_dir)
        closest = checks["closest_particle_pair_over_spacing_at_snapshots"]
        rows.append((name, what, ended,
                     f"{start[0]:.2f} d ({start[1]})" if start else "-",
                     f"{closest:.2f} d" if closest is not None else "none < d/2",
                     str(checks["max_particle_pairs_at_snapshots"]),
                     f'{checks["max_density_deviation_at_snapshots"]:.4f}'))
        print(f"{name}: {ended}", file=sys.stderr)
    print("| variant | change | run | closest pair at t = 0 (pairs < d/2) | closest over 0.3 s "
          "| most pairs < d/2 | max abs(rho/rho0 - 1) |")
    print("|---|---|---|---|---|---|---|")
    for row in rows:
        print("| " + " | ".join(row) + " |")


if __name__ == "__main__":
    main()
