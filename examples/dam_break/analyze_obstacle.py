#!/usr/bin/python3
"""The dam break through an elastic obstacle (elastic_obstacle*.scene; README "Elastic
obstacle"): what the surge does to the obstacle, and whether the run's own numbers agree with
each other. No measured reference is in our reference data for this set-up: the case shows the
capability (a flexible structure hit by a free-surface flow) and checks it for consistency.

For each run folder, from sensors.csv: the first contact (the water's force on the obstacle
first above 1 N/m), the peak of the top's horizontal displacement dx and its time, the top's
vertical displacement there, the water's force and the clamp's moment M at the peak. At the
peak the obstacle is momentarily at rest, so its clamp moment and its deflection are those of a
cantilever under the water's distributed load: linear beam theory gives dx EI / (M L^2) = 1/4 for
a uniform load, 1/5 for one rising linearly to the base, 1/3 for a load at the top. The ratio is
checked to lie in --ratio-range (default 0.18 0.36): it ties the fluid's forces (through the
clamp's multipliers) to the beam's shape, and fails if either is wrong by more than the load's
shape allows. With several folders (resolutions of the same case, coarsest first) the two finest
peaks must agree within --convergence-tolerance (default 0.05).

Usage: analyze_obstacle.py DIR [DIR ...] [--ratio-range 0.18 0.36] [--convergence-tolerance 0.05]
       [--figure F.png]"""
import argparse
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from fsi_results import finish_figure, pyplot, read_run, write_analysis  # noqa: E402

CONTACT_FORCE = 1.0  # N/m: the water's force that counts as contact


def obstacle_of(run_dir):
    run, sensors = read_run(run_dir)
    time = sensors["time"]
    dx = [x - sensors["tip_x"][0] for x in sensors["tip_x"]]
    dy = [y - sensors["tip_y"][0] for y in sensors["tip_y"]]
    force, moment = sensors["obstacle_fluid_force_x"], sensors["clamp_moment"]
    peak = max(range(len(dx)), key=lambda i: dx[i])
    contact = next((time[i] for i, f in enumerate(force) if abs(f) > CONTACT_FORCE), None)
    params = run["parameters_flat"]
    length = params["Geometry.hb"]
    stiffness = params["Geometry.E"] * params["Geometry.w"] ** 3 / 12.0
    ratio = dx[peak] * stiffness / (moment[peak] * length ** 2) if moment[peak] != 0.0 else float("nan")
    return {"run": run_dir, "spacing": params["Resolution.spacing"], "contact_time": contact,
            "peak_dx": dx[peak], "peak_time": time[peak], "dy_at_peak": dy[peak],
            "force_at_peak": force[peak], "moment_at_peak": moment[peak], "beam_ratio": ratio,
            "max_force": max(force), "time": time, "dx": dx}


def draw(results, path):
    plt = pyplot("analyze_obstacle.py")
    figure, axes = plt.subplots(figsize=(7, 4))
    for result in results:
        axes.plot(result["time"], [1000.0 * v for v in result["dx"]],
                  label=f"d = {1000.0 * result['spacing']:g} mm")
    axes.set_xlabel("t [s]")
    axes.set_ylabel("obstacle top dx [mm]")
    finish_figure(figure, axes, "Dam break through an elastic obstacle", path)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("run_dirs", nargs="+")
    parser.add_argument("--ratio-range", type=float, nargs=2, default=[0.18, 0.36],
                        help="allowed dx EI / (M L^2) at the peak")
    parser.add_argument("--convergence-tolerance", type=float, default=0.05,
                        help="allowed relative difference of the two finest peaks")
    parser.add_argument("--figure", help="draw the top's dx of every run into this PNG")
    args = parser.parse_args()
    results, failures = [], []
    for run_dir in args.run_dirs:
        result = obstacle_of(run_dir)
        results.append(result)
        contact = "none" if result["contact_time"] is None else f"{result['contact_time']:.4f}"
        print(f"{run_dir} (d = {1000.0 * result['spacing']:g} mm): first contact at t = "
              f"{contact} s; peak dx {1000.0 * result['peak_dx']:.2f} mm at "
              f"t = {result['peak_time']:.4f} s (dy {1000.0 * result['dy_at_peak']:.2f} mm), force "
              f"{result['force_at_peak']:.1f} N/m, clamp moment {result['moment_at_peak']:.3f} N m/m; "
              f"dx EI / (M L^2) = {result['beam_ratio']:.3f}; largest force {result['max_force']:.1f} N/m")
        low, high = args.ratio_range
        if not low <= result["beam_ratio"] <= high:
            failures.append(f"{run_dir}: dx EI / (M L^2) = {result['beam_ratio']:.3f} outside [{low}, {high}]")
        summary = {k: v for k, v in result.items() if k not in ("time", "dx")}
        write_analysis(run_dir, summary)
    if len(results) >= 2:
        fine, next_fine = sorted(results, key=lambda r: r["spacing"])[:2]
        difference = (next_fine["peak_dx"] - fine["peak_dx"]) / fine["peak_dx"]
        print(f"peak dx at d = {1000.0 * next_fine['spacing']:g} mm against d = "
              f"{1000.0 * fine['spacing']:g} mm: {100.0 * difference:+.2f} %")
        if abs(difference) > args.convergence_tolerance:
            failures.append(f"the two finest peaks differ by {100.0 * difference:+.2f} %")
    if args.figure:
        draw(results, args.figure)
    for failure in failures:
        print("FAIL:", failure)
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
