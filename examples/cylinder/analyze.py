#!/usr/bin/python3
"""Laminar flow around a cylinder (thesis §6.4): the time-averaged velocity profile across the
channel on the cylinder's centre line against the OpenFOAM reference (reference.csv, written by
openfoam_reference.py).

  analyze.py RUN_DIR [--window T0,T1] [--tolerance F] [--reference FILE] [--figure-prefix P]

The 13 probes p0..p12 stand at x = k W / 12, k = -6..6, on y = 0. For each, u_y is averaged over
the window (default 2,6 s, the thesis'; shortened to the run's end) with its standard deviation
over the window (the fluctuations, the error bar of the thesis' Fig. 6.9). The reference is the
finest OpenFOAM level, interpolated to the probe. Judged are the probes away from the walls: at
least 2h (the kernel's support) from the channel walls and from the cylinder's surface, wet over
the whole window; their relative error (mean - reference) / reference must stay within
--tolerance. Also printed: the flux through the centre line (FluxProbe "section") against the
piston's v0 W (continuity), and the piston's drive force.

Figures: PREFIX_profile.png (thesis Fig. 6.9: the profile with error bars against OpenFOAM's
curve) and PREFIX_probe.png (Fig. 6.7: u_y at the probe at x = -W/4 against time), PREFIX
defaulting to RUN_DIR/cylinder. RUN_DIR/analysis.json holds the numbers (max_relative_error over
the judged probes)."""
import argparse
import csv
import os
import statistics
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(HERE))
from fsi_results import finish_figure, pyplot, read_run, require_run, write_analysis  # noqa: E402

PROBES = 13


def read_reference(path):
    """(x, u_y of the finest level, its column name, the levels' columns) of reference.csv."""
    with open(path) as handle:
        rows = [line for line in handle if not line.startswith("#")]
    reader = csv.DictReader(rows)
    columns = [name for name in reader.fieldnames if name.startswith("uy_level_")]
    data = list(reader)
    finest = max(columns, key=lambda name: int(name.rsplit("_", 1)[1]))
    return ([float(row["x"]) for row in data], [float(row[finest]) for row in data], finest,
            {name: [float(row[name]) for row in data] for name in columns})


def interpolate(xs, values, x):
    """values at x, linear between the samples around it; None outside the sampled fluid."""
    for i in range(1, len(xs)):
        if xs[i - 1] <= x <= xs[i] and xs[i] - xs[i - 1] < 0.01:
            w = (x - xs[i - 1]) / (xs[i] - xs[i - 1])
            return (1 - w) * values[i - 1] + w * values[i]
    return None


def draw(prefix, rows, reference, sensors, window, probe_index):
    plt = pyplot("analyze")
    if plt is None:
        return
    xs, uys = reference
    figure, axes = plt.subplots(figsize=(7.5, 4.5))
    left = [(x, u) for x, u in zip(xs, uys) if x < 0]
    right = [(x, u) for x, u in zip(xs, uys) if x > 0]
    for part, label in ((left, "OpenFOAM (simpleFoam)"), (right, None)):
        axes.plot([x for x, _ in part], [u for _, u in part], "r-", label=label)
    wet = [row for row in rows if row["mean"] is not None]
    judged = [row for row in wet if row["judged"]]
    other = [row for row in wet if not row["judged"]]
    axes.errorbar([r["x"] for r in judged], [r["mean"] for r in judged], yerr=[r["std"] for r in judged],
                  fmt="bo", capsize=3, label=f"SPH, mean and std over {window[0]:g}-{window[1]:g} s (judged)")
    axes.errorbar([r["x"] for r in other], [r["mean"] for r in other], yerr=[r["std"] for r in other],
                  fmt="o", color="gray", mfc="none", capsize=3, label="SPH, within 2h of a wall (not judged)")
    axes.set_xlabel("x [m]")
    axes.set_ylabel("u_y on y = 0 [m/s]")
    finish_figure(figure, axes, "Flow around a cylinder: velocity across the centre line", f"{prefix}_profile.png",
                  legend_location="lower center")
    plt.close(figure)
    figure, axes = plt.subplots(figsize=(7.5, 3.5))
    name = f"p{probe_index}_vy"
    axes.plot(sensors["time"], sensors[name], "k-", linewidth=0.8, label=f"probe p{probe_index}, x = {rows[probe_index]['x']:+.3f} m")
    if rows[probe_index]["reference"] is not None:
        axes.axhline(rows[probe_index]["reference"], color="r", label="OpenFOAM, steady")
    axes.axvspan(window[0], window[1], color="b", alpha=0.08, label="averaging window")
    axes.set_xlabel("time [s]")
    axes.set_ylabel("u_y [m/s]")
    finish_figure(figure, axes, "Velocity at one probe (thesis Fig. 6.7)", f"{prefix}_probe.png", legend_location="lower right")
    plt.close(figure)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("run_dir")
    parser.add_argument("--window", default="2,6", help="averaging window T0,T1 [s] (default 2,6)")
    parser.add_argument("--tolerance", type=float, help="fail if a judged probe's |relative error| exceeds this")
    parser.add_argument("--reference", default=os.path.join(HERE, "reference.csv"))
    parser.add_argument("--figure-prefix")
    args = parser.parse_args()
    try:
        window = [float(v) for v in args.window.split(",")]
        if len(window) != 2 or not window[0] < window[1]:
            raise ValueError
    except ValueError:
        parser.error(f"--window {args.window!r}: give two times T0,T1 with T0 < T1, e.g. 2,6")
    require_run(args.run_dir, "cylinder")
    run, sensors = read_run(args.run_dir)
    params = run["parameters_flat"]
    width, radius, v0 = params["Geometry.W"], params["Geometry.r"], params["Geometry.v0"]
    h = params["Fluid.smoothing_length"]
    time = sensors["time"]
    window[1] = min(window[1], time[-1])
    rows_in = [i for i, t in enumerate(time) if window[0] <= t <= window[1]]
    if len(rows_in) < 10:
        raise SystemExit(f"analyze: {len(rows_in)} sensor rows in the window {window[0]:g}-{window[1]:g} s; the run "
                         f"ends at {time[-1]:.3f} s: run longer (Resolution.end_time) or give --window")
    ref_x, ref_u, finest, levels = read_reference(args.reference)
    rows = []
    for k in range(PROBES):
        x = (k - 6) * width / 12
        wet = all(sensors[f"p{k}_wet"][i] > 0 for i in rows_in)
        values = [sensors[f"p{k}_vy"][i] for i in rows_in]
        clearance = min(width / 2 - abs(x), abs(x) - radius)
        reference = interpolate(ref_x, ref_u, x)
        mean = statistics.fmean(values) if wet else None
        row = {"probe": f"p{k}", "x": x, "mean": mean, "std": statistics.pstdev(values) if wet else None,
               "reference": reference, "clearance": clearance,
               "judged": wet and reference is not None and clearance >= 2 * h}
        row["relative_error"] = (mean - reference) / reference if row["judged"] else None
        rows.append(row)
    print(f"u_y on y = 0, mean and std over {window[0]:g}-{window[1]:g} s ({len(rows_in)} rows), against OpenFOAM "
          f"({finest}); judged: at least 2h = {2 * h * 1000:.1f} mm from the walls and the cylinder")
    print("probe   x [m]    mean [m/s]   std [m/s]   OpenFOAM   error")
    for row in rows:
        mean = f"{row['mean']:.5f}" if row["mean"] is not None else "dry"
        std = f"{row['std']:.5f}" if row["std"] is not None else "-"
        ref = f"{row['reference']:.5f}" if row["reference"] is not None else "-"
        error = f"{100 * row['relative_error']:+.2f} %" if row["judged"] else "(not judged)"
        print(f"{row['probe']:5s} {row['x']:+.4f}   {mean:>10s}   {std:>9s}   {ref:>8s}   {error}")
    judged = [row for row in rows if row["judged"]]
    if not judged:
        raise SystemExit("analyze: no probe is 2h away from the walls and wet over the window; refine the spacing")
    worst = max(judged, key=lambda row: abs(row["relative_error"]))
    flux = [sensors["section_flux"][i] for i in rows_in]
    flux_mean = statistics.fmean(flux)
    drive = statistics.fmean(sensors["drive_force_y"][i] for i in rows_in)
    print(f"worst judged probe: {worst['probe']} at x = {worst['x']:+.4f} m, {100 * worst['relative_error']:+.2f} %; "
          f"mean |error| {100 * statistics.fmean(abs(r['relative_error']) for r in judged):.2f} % over {len(judged)} probes")
    print(f"flux through y = 0: {flux_mean:.5f} m^2/s against v0 W = {v0 * width:.5f} m^2/s "
          f"({100 * (flux_mean / (v0 * width) - 1):+.2f} %); the piston's drive force {drive:.2f} N/m")
    result = {"window": window, "smoothing_length": h, "reference_level": finest, "probes": rows,
              "max_relative_error": abs(worst["relative_error"]), "worst_probe": worst["probe"],
              "judged_probes": len(judged), "flux_mean": flux_mean, "flux_expected": v0 * width,
              "drive_force_mean": drive}
    write_analysis(args.run_dir, result)
    prefix = args.figure_prefix or os.path.join(args.run_dir, "cylinder")
    draw(prefix, rows, (ref_x, ref_u), sensors, window, 3)
    if args.tolerance is not None and result["max_relative_error"] > args.tolerance:
        print(f"analyze: {worst['probe']} is {100 * worst['relative_error']:+.2f} % off OpenFOAM, more than "
              f"--tolerance {100 * args.tolerance:g} %", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
