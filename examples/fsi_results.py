"""What the example scripts read from a run's output folder (imported by examples/*/analyze.py)."""
import argparse
import csv
import json
import math
import os


def read_sensors(path):
    """The columns of a sensors.csv (comment lines skipped) as {name: [float, ...]}."""
    with open(path) as handle:
        rows = [line for line in handle if not line.startswith("#")]
    reader = csv.reader(rows)
    header = next(reader)
    columns = {name: [] for name in header}
    for row in reader:
        for name, value in zip(header, row):
            columns[name].append(float(value))
    return columns


def read_run(run_dir):
    """A run's output folder as (run.json as a dict, sensors.csv as {name: [float, ...]})."""
    with open(os.path.join(run_dir, "run.json")) as handle:
        run = json.load(handle)
    return run, read_sensors(os.path.join(run_dir, "sensors.csv"))


def zero_crossings(time, values):
    """Times where `values` changes sign, linearly interpolated between samples."""
    crossings = []
    for i in range(1, len(values)):
        a, b = values[i - 1], values[i]
        if (a < 0.0 <= b) or (a > 0.0 >= b):
            crossings.append(time[i - 1] + (time[i] - time[i - 1]) * a / (a - b))
    return crossings


def write_analysis(run_dir, result):
    """Writes an analysis script's figures as DIR/analysis.json."""
    with open(os.path.join(run_dir, "analysis.json"), "w") as handle:
        json.dump(result, handle, indent=2)


def weight_check_arguments(description, settle_start_default, settle_start_help):
    """The command line every weight check shares: the run folder, where the averaging interval
    starts, and the tolerance on the measured weight; a script adds its own checks' options."""
    parser = argparse.ArgumentParser(description=description, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("run_dir")
    parser.add_argument("--settle-start", type=float, default=settle_start_default,
                        help=f"start of the averaging interval [s] ({settle_start_help})")
    parser.add_argument("--weight-tolerance", type=float, help="fail if |F/W - 1| exceeds this")
    return parser


def fluid_weight(run, particle_count):
    """The weight N m g of `particle_count` particles of the run's particle mass m under its
    gravity g, as (m, g, N m g)."""
    particle_mass = run["fluid"]["particle_mass"]
    gravity = math.hypot(*run["model"]["gravity"])
    return particle_mass, gravity, particle_count * particle_mass * gravity
