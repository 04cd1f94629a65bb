"""What the example scripts read from a run's output folder (imported by examples/*/analyze.py)."""
import argparse
import csv
import glob
import json
import math
import os
import re
import subprocess
import sys


class Checks:
    """The analyses' verdicts: check() prints one line per figure, `ok  ` or `FAIL`, the value
    against the reference within a tolerance (`digits`: the values' format, `against`: the
    reference's name, `tolerance_digits` its format); exit() leaves with status 1 if any failed."""

    def __init__(self, digits=".10g", against="expected", tolerance_digits="g"):
        self.digits, self.against, self.tolerance_digits = digits, against, tolerance_digits
        self.failures = 0

    def check(self, name, value, expected, tolerance):
        ok = abs(value - expected) <= tolerance
        self.failures += not ok
        print(f"{'ok  ' if ok else 'FAIL'} {name}: {value:{self.digits}} "
              f"({self.against} {expected:{self.digits}} +- {tolerance:{self.tolerance_digits}})")

    def exit(self, count=False):
        if count:
            print(f"{self.failures} failed")
        sys.exit(1 if self.failures else 0)


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


SHARED_REFERENCE_DATA = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "shared",
                                     "reference-data")


def read_reference_points(path, how_to_give):
    """The (x, y) pairs of a reference-data file: its first two numbers on each line, separated by
    commas or blanks; blank lines and # comments skipped. Exits saying which file and line is
    wrong, or that the file is missing and `how_to_give` it (e.g. "give --reference FILE")."""
    if not os.path.exists(path):
        raise SystemExit(f"analyze: the reference data {path} is missing; {how_to_give}")
    points = []
    with open(path) as handle:
        for number, line in enumerate(handle, 1):
            if not line.strip() or line.lstrip().startswith("#"):
                continue
            try:
                x, y = (float(v) for v in line.replace(",", " ").split()[:2])
            except ValueError:
                raise SystemExit(f"analyze: {path}:{number}: expected two numbers, got {line.strip()!r}")
            points.append((x, y))
    return points


def interpolate_clamped(xs, ys, x):
    """ys at x, linear between the samples of the increasing xs around it; the end values beyond
    them."""
    if x <= xs[0]:
        return ys[0]
    for i in range(1, len(xs)):
        if xs[i] >= x:
            return ys[i - 1] + (ys[i] - ys[i - 1]) * (x - xs[i - 1]) / (xs[i] - xs[i - 1])
    return ys[-1]


def read_run(run_dir):
    """A run's output folder as (run.json as a dict, sensors.csv as {name: [float, ...]})."""
    with open(os.path.join(run_dir, "run.json")) as handle:
        run = json.load(handle)
    return run, read_sensors(os.path.join(run_dir, "sensors.csv"))


def read_snapshots(run_dir, t0=float("-inf"), t1=float("inf")):
    """(time, {column: numpy array}) of each particle snapshot DIR/snapshots/particles_<step>.csv
    with t0 <= time <= t1, in step order; columns by the file's header (id, x, y, vx, ...)."""
    import numpy as np
    for path in sorted(glob.glob(os.path.join(run_dir, "snapshots", "particles_*.csv"))):
        with open(path) as handle:
            found = re.search(r"t = (\S+) s", handle.readline())  # "# SPH particles at step N, t = T s"
            columns = handle.readline().strip().split(",")
        if found and t0 <= float(found.group(1)) <= t1:
            data = np.loadtxt(path, delimiter=",", comments="#", skiprows=2, ndmin=2)
            yield float(found.group(1)), {name: data[:, k] for k, name in enumerate(columns)}


def zero_crossings(time, values):
    """Times where `values` changes sign, linearly interpolated between samples."""
    crossings = []
    for i in range(1, len(values)):
        a, b = values[i - 1], values[i]
        if (a < 0.0 <= b) or (a > 0.0 >= b):
            crossings.append(time[i - 1] + (time[i] - time[i - 1]) * a / (a - b))
    return crossings


def damped_fit(time, values, omega_guess):
    """Least-squares fit of c + exp(-s (t - t0)) (a cos(w t) + b sin(w t)) to the samples (t0 the
    first sample's time): a grid over w in [0.5, 1.5] omega_guess and s in [0, 0.3 omega_guess]
    (damping ratios up to about 0.29), linear least squares for (c, a, b) at each, then a grid 50
    times finer around the best. The constant c absorbs an offset of the signal's mean, which
    biases zero crossings counted over an odd number of half periods.
    Returns {"omega", "sigma", "damped_period", "natural_period", "damping_ratio", "rms_residual"};
    the natural period 2 pi / sqrt(w^2 + s^2) is the undamped oscillator's."""
    import numpy as np
    t = np.asarray(time, dtype=float)
    y = np.asarray(values, dtype=float)

    def residual(w, s):
        decay = np.exp(-s * (t - t[0]))
        basis = np.column_stack([np.ones_like(t), decay * np.cos(w * t), decay * np.sin(w * t)])
        coefficients = np.linalg.lstsq(basis, y, rcond=None)[0]
        r = y - basis @ coefficients
        return float(r @ r)

    omegas = np.linspace(0.5 * omega_guess, 1.5 * omega_guess, 401)
    sigmas = np.linspace(0.0, 0.3 * omega_guess, 61)
    _, w0, s0 = min((residual(w, s), w, s) for w in omegas for s in sigmas)
    if w0 in (omegas[0], omegas[-1]) or s0 == sigmas[-1]:
        raise SystemExit(f"damped_fit: the best fit (w = {w0:.4g} rad/s, s = {s0:.4g} 1/s) lies on the edge "
                         f"of the searched range (w {omegas[0]:.4g}-{omegas[-1]:.4g}, s 0-{sigmas[-1]:.4g}): "
                         "the signal is not a damped oscillation near the expected frequency; plot it")
    dw, ds = 1.2 * (omegas[1] - omegas[0]), 1.2 * (sigmas[1] - sigmas[0])
    best, w, s = min((residual(w, s), w, s) for w in np.linspace(w0 - dw, w0 + dw, 121)
                     for s in np.linspace(max(0.0, s0 - ds), s0 + ds, 61))
    return {"omega": float(w), "sigma": float(s), "damped_period": 2.0 * math.pi / w,
            "natural_period": 2.0 * math.pi / math.hypot(w, s), "damping_ratio": s / math.hypot(w, s),
            "rms_residual": math.sqrt(best / len(t))}


def pyplot(script):
    """matplotlib.pyplot with the file-only Agg backend, or None after saying (as `script`) that the
    figures are left out and how to get them."""
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print(f"{script}: no matplotlib (apt-get install python3-matplotlib); no figures", file=sys.stderr)
        return None
    return plt


def finish_figure(figure, axes, title, path, legend_size=8, legend_location="upper left"):
    """What every analysis figure ends with: grid, legend, title, saved to `path` (and said)."""
    axes.grid(True, alpha=0.3)
    axes.legend(loc=legend_location, fontsize=legend_size)
    axes.set_title(title)
    figure.tight_layout()
    figure.savefig(path, dpi=120)
    print(f"figure: {path}")


def write_analysis(run_dir, result):
    """Writes an analysis script's figures as DIR/analysis.json."""
    with open(os.path.join(run_dir, "analysis.json"), "w") as handle:
        json.dump(result, handle, indent=2)


def judge_runs(results, report, judge, curves=()):
    """What a script comparing runs with a reference ends with: for each result (a dict with its
    "run_dir") report(result) prints its figures, judge(result) returns the failures (messages),
    and analysis.json gets the result without the `curves` keys (the time series). Prints each
    failure as "FAIL: ..." and returns the exit status (1 if any)."""
    failures = []
    for result in results:
        report(result)
        failures += judge(result)
        write_analysis(result["run_dir"], {k: v for k, v in result.items() if k not in curves})
    for failure in failures:
        print(f"FAIL: {failure}")
    return 1 if failures else 0


def weight_check_arguments(description, settle_start_default, settle_start_help):
    """The command line every weight check shares: the run folder, where the averaging interval
    starts, and the tolerance on the measured weight; a script adds its own checks' options."""
    parser = argparse.ArgumentParser(description=description, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("run_dir")
    parser.add_argument("--settle-start", type=float, default=settle_start_default,
                        help=f"start of the averaging interval [s] ({settle_start_help})")
    parser.add_argument("--weight-tolerance", type=float, help="fail if |F/W - 1| exceeds this")
    return parser


def closed_form_run(description, tolerance_default, tolerance_help):
    """The command line of a check against a closed form (RUN_DIR and --tolerance of its main
    check), parsed, and the run: (args, run.json as a dict, sensors.csv as columns, the scene's
    parameters by their path)."""
    parser = argparse.ArgumentParser(description=description, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("run_dir")
    parser.add_argument("--tolerance", type=float, default=tolerance_default, help=tolerance_help)
    args = parser.parse_args()
    run, sensors = read_run(args.run_dir)
    return args, run, sensors, run["parameters_flat"]


def fluid_weight(run, particle_count):
    """The weight N m g of `particle_count` particles of the run's particle mass m under its
    gravity g, as (m, g, N m g)."""
    particle_mass = run["fluid"]["particle_mass"]
    gravity = math.hypot(*run["model"]["gravity"])
    return particle_mass, gravity, particle_count * particle_mass * gravity


def completed(run_dir):
    """Whether `run_dir` holds a run.json of a completed run (a study script does not run it again)."""
    try:
        with open(os.path.join(run_dir, "run.json")) as handle:
            return json.load(handle).get("status") == "completed"
    except (OSError, ValueError):
        return False


def run_variant(fsi_run, scene, run_dir, ranks, settings):
    """Runs `scene` with fsi-run into `run_dir`, each (name, value) of `settings` as a --set, unless
    the folder already holds a completed run. Returns True when the run completed (now or before).
    """
    if completed(run_dir):
        print(f"{run_dir}: completed before, not run again", flush=True)
        return True
    command = [fsi_run, scene, "--np", str(ranks), "--output", run_dir]
    for name, value in settings:
        command += ["--set", f"{name}={value!r}"]
    print(" ".join(command), flush=True)
    environment = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    if subprocess.run(command, env=environment).returncode == 0:
        return True
    print(f"the run in {run_dir} failed (its fsi-server.log says why)", flush=True)
    return False


def study_arguments(description, scene, output):
    """The command line every study script (several runs of one scene) shares: --scene (default
    `scene`), --output (default `output`), --np, --end-time, --build; the script adds its knobs.
    Returns the parser."""
    parser = argparse.ArgumentParser(description=description, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--scene", default=scene)
    parser.add_argument("--output", default=output)
    parser.add_argument("--np", type=int, default=2)
    parser.add_argument("--end-time", type=float, help="Resolution.end_time of every run (default: the scene's)")
    parser.add_argument("--build", default=os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "build"))
    return parser


def fsi_run_binary(args, script):
    """build/bin/fsi-run of a study script's --build, or exit saying how to get it."""
    fsi_run = os.path.join(args.build, "bin", "fsi-run")
    if not os.access(fsi_run, os.X_OK):
        raise SystemExit(f"{script}: no fsi-run at {fsi_run}; build first (cmake --build build) or give --build")
    return fsi_run


def require_run(run_dir, case):
    """Exits saying what to give when `run_dir` is no run's output folder (no sensors.csv)."""
    if not os.path.isfile(os.path.join(run_dir, "sensors.csv")):
        raise SystemExit(f"analyze: {run_dir} holds no sensors.csv; give the output folder of a "
                         f"finished {case} run (fsi-run ... --output DIR)")
