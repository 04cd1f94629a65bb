#!/usr/bin/python3
"""Tuned liquid column damper on a flexible building: the damping of the building's first mode
after the push is removed, from the logarithmic decrement of its tip's swing, with and without
the water in the damper.

  analyze.py RUN_DIR [--empty EMPTY_DIR] [--cycles N] [--min-ratio R]

RUN_DIR is a coupled run (fsi-run tlcd*.scene), EMPTY_DIR the same scene run with
`fsi-server ... --mbd-only` (the building with the empty damper: no water is read there).

After the release at Geometry.release the tip's displacement x(t) (sensor tip_x; the building
stands upright at rest, x = 0) swings about 0. Its positive extrema a_0, a_1, ... (a_0 at the
release, then one per period between an upward and the next downward zero crossing) give the
logarithmic decrement over the first n periods, delta = ln(a_0 / a_n) / n, n = --cycles (default
4) or fewer when the run holds fewer, and the damping ratio zeta = delta / sqrt(4 pi^2 + delta^2).
A damper's water swings against the building and the two exchange energy, so the extrema of a
damped building need not fall by one ratio per period (beating); delta over n periods is their
mean rate. A cross-check: the least-squares slope of ln a_i over i (the same n periods).

With --empty, the same for the empty building and the ratio zeta / zeta_empty; --min-ratio R
fails (exit 1) when the ratio is below R (issue 14 asks for 3). The figure DIR/tlcd_tip.png draws
both tip curves (thesis Fig. 7.2). Also printed: the column's largest swing s = (eta_right -
eta_left) / 2 from the free-surface probes, and the column's period by linear theory
2 pi sqrt(L / (2 g)). DIR/analysis.json holds the numbers."""
import argparse
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from fsi_results import finish_figure, pyplot, read_run, require_run, write_analysis, zero_crossings  # noqa: E402


def swing(run_dir, cycles):
    """The tip's swing after the release of the run in `run_dir`: (run.json, sensors, result)."""
    require_run(run_dir, "TLCD")
    run, sensors = read_run(run_dir)
    params = run["parameters_flat"]
    release = params["Geometry.release"]
    pairs = [(t, x) for t, x in zip(sensors["time"], sensors["tip_x"]) if t >= release]
    if len(pairs) < 3:
        raise SystemExit(f"analyze: {run_dir} ends at t = {sensors['time'][-1]:.3f} s, before the release at "
                         f"{release} s plus a period; run longer (Resolution.end_time)")
    time = [t for t, _ in pairs]
    x = [v for _, v in pairs]
    crossings = zero_crossings(time, x)
    # Positive lobes: from the release (x > 0: the push was along +x) to the first crossing, then
    # from every upward crossing to the next downward one.
    bounds = [(time[0], crossings[0])] if crossings else []
    for a, b in zip(crossings[1:], crossings[2:]):
        if x[next(i for i, t in enumerate(time) if t > a)] > 0:
            bounds.append((a, b))
    peaks = []
    for a, b in bounds:
        window = [(v, t) for t, v in zip(time, x) if a <= t <= b]
        if window:
            value, when = max(window)
            peaks.append((when, value))
    if len(peaks) < 3:
        raise SystemExit(f"analyze: only {len(peaks)} positive extrema of tip_x after the release in {run_dir}; "
                         f"run at least two periods past Geometry.release = {release} s")
    n = min(cycles, len(peaks) - 1)
    amplitudes = [value for _, value in peaks]
    delta = math.log(amplitudes[0] / amplitudes[n]) / n
    zeta = delta / math.sqrt(4.0 * math.pi ** 2 + delta ** 2)
    logs = [math.log(a) for a in amplitudes[:n + 1]]
    mean_i, mean_log = n / 2.0, sum(logs) / (n + 1)
    slope = sum((i - mean_i) * (v - mean_log) for i, v in enumerate(logs)) / sum((i - mean_i) ** 2 for i in range(n + 1))
    zeta_fit = -slope / math.sqrt(4.0 * math.pi ** 2 + slope ** 2)
    period = (peaks[n][0] - peaks[0][0]) / n
    result = {"release": release, "cycles": n, "peak_times": [t for t, _ in peaks], "amplitudes": amplitudes,
              "log_decrement": delta, "damping_ratio": zeta, "damping_ratio_least_squares": zeta_fit,
              "period": period}
    return run, sensors, result


def column(run, sensors):
    """The water column's largest swing and its period by linear theory (None without probes)."""
    params = run["parameters_flat"]
    g = math.hypot(*run["model"]["gravity"])
    theory = 2.0 * math.pi * math.sqrt(params["Geometry.L"] / (2.0 * g))
    if "left_elevation" not in sensors:
        return {"column_period_theory": theory}
    s = [0.5 * (r - l) for l, r in zip(sensors["left_elevation"], sensors["right_elevation"])]
    return {"column_period_theory": theory, "column_swing_max": max(abs(v) for v in s),
            "column_room": params["Geometry.top"] - params["Geometry.fill"]}


def draw(path, runs):
    """Thesis Fig. 7.2: the tip's displacement with and without the water."""
    plt = pyplot("analyze")
    if plt is None:
        return
    figure, axes = plt.subplots(figsize=(9, 4.5))
    for label, sensors, style in runs:
        axes.plot(sensors["time"], [1000.0 * v for v in sensors["tip_x"]], style, label=label, linewidth=1.0)
    axes.set_xlabel("time [s]")
    axes.set_ylabel("tip displacement x [mm]")
    finish_figure(figure, axes, "Building tip: pushed, released, damped by the water column", path,
                  legend_location="upper right")
    plt.close(figure)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("run_dir")
    parser.add_argument("--empty", help="output folder of the same scene run with fsi-server --mbd-only")
    parser.add_argument("--cycles", type=int, default=4, help="periods of the decrement (default 4)")
    parser.add_argument("--min-ratio", type=float, help="fail if zeta / zeta_empty is below this")
    args = parser.parse_args()
    if args.cycles < 1:
        parser.error("--cycles must be at least 1")
    if args.min_ratio is not None and not args.empty:
        parser.error("--min-ratio compares with the empty building: give --empty DIR too")

    run, sensors, result = swing(args.run_dir, args.cycles)
    result.update(column(run, sensors))
    label = "with water: " if "left_elevation" in sensors else "this run:   "
    print(f"{label} zeta = {result['damping_ratio']:.4f} (log decrement {result['log_decrement']:.4f} over "
          f"{result['cycles']} periods; least squares {result['damping_ratio_least_squares']:.4f}), period "
          f"{result['period']:.4f} s, extrema [mm] " + ", ".join(f"{1000 * a:.2f}" for a in result["amplitudes"]))
    if "column_swing_max" in result:
        print(f"column: largest swing s = {1000 * result['column_swing_max']:.1f} mm (room above the water "
              f"{1000 * result['column_room']:.0f} mm); period by linear theory {result['column_period_theory']:.4f} s")
    curves = [("with water", sensors, "k-")]
    status = 0
    if args.empty:
        _, empty_sensors, empty = swing(args.empty, args.cycles)
        ratio = result["damping_ratio"] / empty["damping_ratio"] if empty["damping_ratio"] > 0 else math.inf
        result.update({"damping_ratio_empty": empty["damping_ratio"], "period_empty": empty["period"],
                       "amplitudes_empty": empty["amplitudes"], "damping_ratio_over_empty": ratio})
        print(f"empty:       zeta = {empty['damping_ratio']:.4f} (log decrement {empty['log_decrement']:.4f} over "
              f"{empty['cycles']} periods), period {empty['period']:.4f} s")
        print(f"the damper multiplies the building's damping ratio by {ratio:.2f}")
        curves.insert(0, ("empty damper", empty_sensors, "r-"))
        if args.min_ratio is not None and not ratio >= args.min_ratio:
            print(f"analyze: zeta / zeta_empty = {ratio:.2f} is below --min-ratio {args.min_ratio:g}", file=sys.stderr)
            status = 1
    draw(os.path.join(args.run_dir, "tlcd_tip.png"), curves)
    write_analysis(args.run_dir, result)
    return status


if __name__ == "__main__":
    sys.exit(main())
