#!/usr/bin/python3
"""What checkpoints cost (issue 16; docs/user-guide.md, "Checkpoints and resume"): the same
coupled run without checkpoints (the baseline, measured in the same invocation) and with one
every N steps, alternately, R times each. It prints

  * the seconds per checkpoint (both sides: the client's capture and restore, the server's
    hashing, syncing and renaming; run.json checkpoints.seconds_writing / written) and its size;
  * the coupled phase's wall time of both runs (median) and their ratio;
  * the share of the wall time a checkpoint takes at the measured interval and at the default
    interval (Output.checkpoint_every_seconds = 1800 s of wall time).

Not a pass/fail test: the numbers go to docs/performance.md.

  bench/checkpoint_cost.py [--scene SCENE] [--np 2] [--steps 2000] [--every 500] [--repeat 3]
                           [--set KEY=EXPR ...] [--keep DIR] [--build build]

Default: the static tank at the thesis' resolution (h = 0.614 mm, 14 250 particles), with a short
equilibration (what a checkpoint costs does not depend on how settled the water is).
"""
import argparse
import json
import os
import shutil
import statistics
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
ENV = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
           OMPI_MCA_rmaps_base_oversubscribe="1")
DEFAULT_INTERVAL = 1800.0  # Output.checkpoint_every_seconds' default [s]


def run(args, folder, every):
    command = [os.path.join(args.build, "bin", "fsi-run"), args.scene, "--np", str(args.np),
               "--output", folder, "--overwrite",
               "--set", f"Resolution.end_time={args.steps}*Resolution.time_step",
               "--set", "Resolution.equilibration_steps=200", "--set", "Resolution.snapshot_every_steps=0",
               "--set", f"Output.checkpoint_every_steps={every}", "--set", "Output.checkpoint_every_seconds=0"]
    for item in args.set:
        command += ["--set", item]
    result = subprocess.run(command, capture_output=True, text=True, env=ENV)
    if result.returncode != 0:
        sys.exit(f"checkpoint_cost: {' '.join(command)} failed:\n{result.stderr[-3000:]}")
    with open(os.path.join(folder, "run.json")) as handle:
        manifest = json.load(handle)
    size = 0
    checkpoints = os.path.join(folder, "checkpoints")
    if os.path.isdir(checkpoints):
        newest = sorted(os.listdir(checkpoints))[-1]
        for name in os.listdir(os.path.join(checkpoints, newest)):
            size += os.path.getsize(os.path.join(checkpoints, newest, name))
    return manifest["timings_seconds"]["coupled_phase"], manifest["checkpoints"], size


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--scene", default=os.path.join(ROOT, "examples", "static_tank", "static_tank.scene"))
    parser.add_argument("--np", type=int, default=2)
    parser.add_argument("--steps", type=int, default=2000)
    parser.add_argument("--every", type=int, default=500)
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--set", action="append", default=[])
    parser.add_argument("--keep", default="")
    parser.add_argument("--build", default=os.path.join(ROOT, "build"))
    args = parser.parse_args()
    work = args.keep or tempfile.mkdtemp(prefix="fsi_checkpoint_cost_")
    plain, with_checkpoints, per_checkpoint = [], [], []
    size = 0
    for r in range(args.repeat):
        seconds, _, _ = run(args, os.path.join(work, f"plain{r}"), 0)
        plain.append(seconds)
        seconds, record, size = run(args, os.path.join(work, f"checkpoints{r}"), args.every)
        with_checkpoints.append(seconds)
        per_checkpoint.append(record["seconds_writing"] / max(1, record["written"]))
    base, timed, each = statistics.median(plain), statistics.median(with_checkpoints), statistics.median(per_checkpoint)
    written = (args.steps - 1) // args.every
    print(f"scene {os.path.relpath(args.scene, ROOT)}, {args.np} rank(s), {args.steps} steps, "
          f"a checkpoint every {args.every} steps ({written} per run), {args.repeat} runs each (medians)")
    print(f"checkpoint: {each:.3f} s each (both sides), {size / 1e6:.2f} MB")
    print(f"coupled phase: {base:.2f} s without, {timed:.2f} s with checkpoints (ratio {timed / base:.3f})")
    step = base / args.steps
    print(f"share of the wall time: {100 * each * written / base:.2f} % at one per {args.every} steps "
          f"({args.every * step:.2f} s); {100 * each / DEFAULT_INTERVAL:.4f} % at the default one per "
          f"{DEFAULT_INTERVAL:.0f} s")
    if not args.keep:
        shutil.rmtree(work)


if __name__ == "__main__":
    main()
