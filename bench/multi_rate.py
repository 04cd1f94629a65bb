#!/usr/bin/python3
"""Multi-rate coupling (SolverOptions.Timeint.substeps = k; docs/theory.md, "Multi-rate
coupling"): the same scene run with k = 1 (the baseline, measured in the same invocation) and
each other k, one after the other. For each k it prints

  * the error against the k = 1 run: for every sensor column in metres or radians (the bodies'
    coordinates), the largest difference over the common rows divided by that column's range of
    motion in the k = 1 run; the largest of these is the headline;
  * the cost: wall time of the coupled phase, multibody steps and exchanges (TCP round trips),
    each also as the ratio k = 1 / this run.

Not a pass/fail test: the numbers go to docs/performance.md and docs/validation.md.

  bench/multi_rate.py [--scene SCENE] [--ks 1,2,5,10,20] [--np 1] [--set KEY=EXPR ...]
                      [--keep DIR] [--build build]

Every k must divide Output.sensor_every_steps and the run's step count (the scene refuses
otherwise); the default sets sensor_every_steps to the least common multiple of the ks.
"""
import argparse
import csv
import json
import math
import os
import shutil
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
ENV = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
           OMPI_MCA_rmaps_base_oversubscribe="1")


def read_sensors(folder):
    """sensors.csv as {column: [values]} and {column: unit}."""
    units = {}
    with open(os.path.join(folder, "sensors.csv")) as handle:
        lines = handle.read().splitlines()
    for line in lines:
        if line.startswith("# units:"):
            for item in line[len("# units:"):].split(","):
                name, _, unit = item.strip().partition(" [")
                units[name] = unit.rstrip("]")
    rows = list(csv.DictReader(line for line in lines if not line.startswith("#")))
    columns = {name: [float(row[name]) for row in rows] for name in rows[0]} if rows else {}
    return columns, units


def run(scene, k, ranks, overrides, output, build):
    command = [os.path.join(build, "bin", "fsi-run"), scene, "--np", str(ranks), "--output", output,
               "--overwrite", "--set", f"SolverOptions.Timeint.substeps={k}"]
    for item in overrides:
        command += ["--set", item]
    result = subprocess.run(command, env=ENV, capture_output=True, text=True)
    if result.returncode != 0:
        sys.exit(f"multi_rate: the run with k = {k} failed (exit {result.returncode}):\n"
                 f"{result.stderr[-2000:]}")
    with open(os.path.join(output, "run.json")) as handle:
        manifest = json.load(handle)
    columns, units = read_sensors(output)
    return manifest, columns, units


def errors_against(baseline, columns, units):
    """Per coordinate column: max |x_k - x_1| over the common rows / range of x_1."""
    times = {round(t, 12): i for i, t in enumerate(baseline["time"])}
    result = {}
    for name, unit in units.items():
        if unit not in ("m", "rad") or name not in columns or name not in baseline:
            continue
        reference = baseline[name]
        motion = max(reference) - min(reference)
        worst = 0.0
        for t, value in zip(columns["time"], columns[name]):
            i = times.get(round(t, 12))
            if i is not None:
                worst = max(worst, abs(value - reference[i]))
        result[name] = (worst / motion if motion > 0 else math.inf, worst, motion)
    return result


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--scene", default=os.path.join(ROOT, "examples", "immersed_block",
                                                        "falling_block_coarse.scene"))
    parser.add_argument("--ks", default="1,2,5,10,20", help="substeps to run; 1 is added as the baseline")
    parser.add_argument("--np", type=int, default=1)
    parser.add_argument("--set", action="append", default=[], metavar="KEY=EXPR",
                        help="scene overrides for every run (e.g. Resolution.end_time=0.4)")
    parser.add_argument("--keep", help="keep the runs in this folder (default: a temporary one)")
    parser.add_argument("--build", default=os.path.join(ROOT, "build"))
    args = parser.parse_args()
    try:
        ks = sorted({1} | {int(k) for k in args.ks.split(",")})
    except ValueError:
        sys.exit(f"multi_rate: --ks takes whole numbers separated by commas, not '{args.ks}'")
    if ks[0] < 1:
        sys.exit("multi_rate: every k must be at least 1")
    every = math.lcm(*ks)
    overrides = [f"Output.sensor_every_steps={every}"] + args.set

    folder = args.keep or tempfile.mkdtemp(prefix="fsi_multi_rate_")
    os.makedirs(folder, exist_ok=True)
    results = {}
    try:
        for k in ks:
            results[k] = run(args.scene, k, args.np, overrides, os.path.join(folder, f"k{k}"), args.build)
            print(f"k = {k}: done", flush=True)
    finally:
        if not args.keep:
            shutil.rmtree(folder, ignore_errors=True)

    base_manifest, base_columns, units = results[1]
    base_wall = base_manifest["timings_seconds"]["coupled_phase"]
    base_mbd = base_manifest["newton"]["steps"]
    base_exchanges = base_manifest["energy_audit"]["exchanges"]
    print(f"\nscene {os.path.relpath(args.scene, ROOT)}, {base_manifest['steps']} fluid steps, "
          f"{args.np} rank(s), overrides {overrides}")
    print("error: largest |x_k - x_1| over the rows / range of x_1, per coordinate column (m, rad)")
    print(f"{'k':>3} {'error':>10} {'worst column':>16} {'coupled [s]':>12} {'speed-up':>9} "
          f"{'MBD steps':>10} {'exchanges':>10} {'fewer':>6}")
    table = []
    for k in ks:
        manifest, columns, _ = results[k]
        errors = errors_against(base_columns, columns, units)
        worst = max(errors.items(), key=lambda item: item[1][0]) if errors else ("-", (0.0, 0.0, 0.0))
        wall = manifest["timings_seconds"]["coupled_phase"]
        mbd = manifest["newton"]["steps"]
        exchanges = manifest["energy_audit"]["exchanges"]
        row = {"k": k, "error": worst[1][0], "worst_column": worst[0],
               "errors": {name: value[0] for name, value in errors.items()},
               "coupled_seconds": wall, "speed_up": base_wall / wall if wall > 0 else math.inf,
               "mbd_steps": mbd, "exchanges": exchanges,
               "fewer_exchanges": base_exchanges / exchanges if exchanges else math.inf,
               "fewer_mbd_steps": base_mbd / mbd if mbd else math.inf,
               "status": manifest["status"]}
        table.append(row)
        print(f"{k:>3} {100 * row['error']:>9.3f}% {row['worst_column']:>16} {wall:>12.1f} "
              f"{row['speed_up']:>8.2f}x {mbd:>10} {exchanges:>10} {row['fewer_exchanges']:>5.1f}x")
    print(json.dumps({"scene": os.path.relpath(args.scene, ROOT), "ranks": args.np, "overrides": overrides,
                      "rows": table}))


if __name__ == "__main__":
    main()
