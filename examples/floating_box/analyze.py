#!/usr/bin/python3
"""Evaluates a floating-box run (issue 19, the still-floating-box case of SPHinXsys) from
DIR/sensors.csv, DIR/run.json and the particle snapshots DIR/snapshots/particles_*.csv.

Prints and writes DIR/analysis.json with
  - the equilibrium draft: the free surface (top particle centres + d/2, away from the box and the
    walls, averaged over the snapshots of the settled part) minus the box's bottom (its mean over
    whole heave periods of the settled part), against Archimedes' m / (rho0 B);
  - the heave period from the crossings of the box's height through its mean, and the damping
    ratio from the decay of successive extremes, against the linear estimates
        T_open = 2 pi sqrt((m + a33) / (rho0 g B))                   (open water)
        T_tank = 2 pi sqrt((m + a33) / (rho0 g B W / (W - B)))      (closed tank of width W: the
                 water level falls by B/(W - B) of the box's rise, so the draft changes faster)
    with the added mass a33 given on the command line (README: its source and uncertainty);
  - the mean fluid force on the box over the settled part against its weight m g.
Exit status 1 if a tolerance given on the command line is not met (none by default: the lead
re-runs with --draft-tolerance 0.03 after the wall law's stand-off is handled, issue 19).
"""
import argparse
import glob
import math
import os
import sys

import numpy

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from fsi_results import read_run, write_analysis  # noqa: E402 (examples/fsi_results.py)


def crossings(time, signal, level):
    """Times where signal crosses level (linear interpolation), with +1 (upward) or -1."""
    found = []
    for i in range(1, len(time)):
        a, b = signal[i - 1] - level, signal[i] - level
        if (a < 0.0) != (b < 0.0) and a != b:
            found.append((time[i - 1] + (time[i] - time[i - 1]) * a / (a - b), 1 if b > a else -1))
    return found


def settled_mean(time, signal, start):
    """The mean of signal over whole periods after `start` (between its first and last upward
    crossing of the mean, refined twice), so an oscillation does not bias it; the plain mean when
    fewer than two periods are seen."""
    window = time >= start
    mean = float(signal[window].mean())
    for _ in range(3):
        upward = [t for t, direction in crossings(time[window], signal[window], mean) if direction > 0]
        if len(upward) < 2:
            return mean, None
        whole = (time >= upward[0]) & (time <= upward[-1])
        mean = float(signal[whole].mean())
    return mean, (upward[0], upward[-1])


def beside_box(x, box_left, box_right, tank_width, margin):
    """The water beside the box, farther than `margin` from the box and from the tank walls."""
    return ((x > margin) & (x < box_left - margin)) | \
           ((x > box_right + margin) & (x < tank_width - margin))


def settled_snapshots(run_dir, settle_start):
    """(time, data) of each particle snapshot at or after settle_start."""
    for path in sorted(glob.glob(os.path.join(run_dir, "snapshots", "particles_*.csv"))):
        with open(path) as handle:
            header = handle.readline()  # "# SPH particles at step N, t = T s"
        snapshot_time = float(header.split("t =")[1].split()[0])
        if snapshot_time >= settle_start:
            yield snapshot_time, numpy.genfromtxt(path, delimiter=",", skip_header=2)


def free_surface(run_dir, settle_start, box_left, box_right, tank_width, spacing, margin):
    """Two free surfaces beside the box, each averaged over the settled snapshots:
      - by volume: per bin of width 2 d the top particle centre + d/2 (a particle fills a d x d
        cell);
      - by pressure, a cross-check: where the hydrostatic pressure of the water beside the box,
        fitted as a straight line p = a + b y over its middle 60 % (away from the floor and the
        surface layers), vanishes: y = -a / b. Measured, it lies 0.43 d below the volume's at
        d = 0.05 m and 0.31 d below at d = 0.025 m: both are the SPH surface to within O(d).
    The draft is measured from the volume's surface.
    Returns a dict with both levels, their spread over the snapshots, the fitted slope -b (against
    rho0 g) and the snapshot times; None without a settled snapshot."""
    volume_levels, pressure_levels, slopes, times = [], [], [], []
    for snapshot_time, data in settled_snapshots(run_dir, settle_start):
        x, y, pressure = data[:, 1], data[:, 2], data[:, 6]
        beside = beside_box(x, box_left, box_right, tank_width, margin)
        tops = []
        for low in numpy.arange(0.0, tank_width, 2.0 * spacing):
            in_bin = beside & (x >= low) & (x < low + 2.0 * spacing)
            if in_bin.any():
                tops.append(y[in_bin].max() + 0.5 * spacing)
        if not tops:
            continue
        volume_level = float(numpy.mean(tops))
        middle = beside & (y > 0.2 * volume_level) & (y < 0.8 * volume_level)
        if middle.sum() < 10:
            continue
        slope, intercept = numpy.polyfit(y[middle], pressure[middle], 1)
        volume_levels.append(volume_level)
        pressure_levels.append(float(-intercept / slope))
        slopes.append(float(-slope))
        times.append(snapshot_time)
    if not times:
        return None

    def spread(values):
        return float(numpy.max(values) - numpy.min(values))
    return {"volume": float(numpy.mean(volume_levels)), "volume_spread": spread(volume_levels),
            "pressure": float(numpy.mean(pressure_levels)), "pressure_spread": spread(pressure_levels),
            "pressure_gradient": float(numpy.mean(slopes)), "times": times}


def heave_period(time, height, mean, start):
    """Period from all crossings of the mean after `start` (half a period apart), and the damping
    ratio from the logarithmic decrement of the extremes between them (None if too few)."""
    window = time >= start
    found = [t for t, _ in crossings(time[window], height[window], mean)]
    if len(found) < 3:
        return None, None, len(found)
    period = 2.0 * (found[-1] - found[0]) / (len(found) - 1)
    amplitudes = []
    for a, b in zip(found[:-1], found[1:]):
        between = (time >= a) & (time <= b)
        if between.any():
            amplitudes.append(float(numpy.max(numpy.abs(height[between] - mean))))
    damping = None
    if len(amplitudes) >= 2 and amplitudes[-1] > 0.0:
        # Successive half-period extremes decay by exp(-zeta omega T/2) = exp(-pi zeta / sqrt(1 - zeta^2)).
        decrement = math.log(amplitudes[0] / amplitudes[-1]) / (len(amplitudes) - 1)
        damping = decrement / math.sqrt(math.pi ** 2 + decrement ** 2)
    return period, damping, len(found)


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("run_dir")
    parser.add_argument("--settle-start", type=float, default=2.0,
                        help="start of the settled part [s] (default 2.0: the first period's "
                             "start-up is left out)")
    parser.add_argument("--added-mass", type=float, default=636.0,
                        help="heave added mass a33 [kg/m] (default 636: the infinite-frequency "
                             "value of the 1 x 0.7 m section, README)")
    parser.add_argument("--surface-margin", type=float, default=0.25,
                        help="free surface measured this far from the box and the walls [m]")
    parser.add_argument("--draft-tolerance", type=float,
                        help="fail if |draft / (m / (rho0 B)) - 1| exceeds this (issue 19: 0.03)")
    parser.add_argument("--period-tolerance", type=float,
                        help="fail if |T / T_tank - 1| exceeds this")
    args = parser.parse_args()

    run, sensors = read_run(args.run_dir)
    params = run["parameters_flat"]
    rho0 = run["fluid"]["density"]
    gravity = math.hypot(*run["model"]["gravity"])
    mass = {body["name"]: body for body in run["model"]["bodies"]}["box"]["mass"]
    size = params["Geometry.box_size"]
    tank_width = params["Geometry.tank_width"]
    box_x = params["Geometry.box_x"]
    spacing = params["LIGGGHTS_SPH_parameters.particlespacing"]

    time = numpy.array(sensors["time"])
    height = numpy.array(sensors["box_y"])
    force = numpy.array(sensors["box_fluid_force_y"])
    if time[-1] <= args.settle_start:
        print(f"analyze: the run ends at {time[-1]:.3f} s, before the settled part starts at "
              f"{args.settle_start} s; run longer", file=sys.stderr)
        return 1

    centre, whole_periods = settled_mean(time, height, args.settle_start)
    bottom = centre - 0.5 * size
    surface = free_surface(
        args.run_dir, args.settle_start, box_x - 0.5 * size, box_x + 0.5 * size, tank_width,
        spacing, args.surface_margin)
    archimedes = mass / (rho0 * size)
    result = {"box_mass": mass, "archimedes_draft": archimedes, "settle_start": args.settle_start,
              "mean_box_centre_y": centre, "mean_box_bottom_y": bottom,
              "whole_periods_interval": whole_periods}
    print(f"box {size} x {size} m, m = {mass} kg/m, d = {spacing} m; Archimedes' draft "
          f"m/(rho0 B) = {archimedes:.4f} m")
    interval = (f"{whole_periods[0]:.3f} .. {whole_periods[1]:.3f} s (whole periods)"
                if whole_periods else f"{args.settle_start:.3f} s .. end (fewer than two periods)")
    print(f"settled part {interval}: mean box centre y = {centre:.4f} m, bottom {bottom:.4f} m")
    failed = False
    if surface is None:
        print("no particle snapshot in the settled part: no free surface, no draft")
        if args.draft_tolerance is not None:
            print("FAIL: a draft tolerance was given but the draft could not be measured")
            failed = True
    else:
        draft = surface["volume"] - bottom
        ratio = draft / archimedes
        pressure_draft = surface["pressure"] - bottom
        result.update({"free_surface_y": surface["volume"],
                       "free_surface_spread": surface["volume_spread"],
                       "free_surface_by_pressure_y": surface["pressure"],
                       "free_surface_by_pressure_spread": surface["pressure_spread"],
                       "pressure_gradient": surface["pressure_gradient"],
                       "free_surface_snapshot_times": surface["times"], "draft": draft,
                       "draft_ratio": ratio, "draft_by_pressure": pressure_draft,
                       "draft_by_pressure_ratio": pressure_draft / archimedes})
        print(f"free surface beside the box, {len(surface['times'])} snapshots:")
        print(f"  by volume (top particle centres + d/2) {surface['volume']:.4f} m, spread "
              f"{surface['volume_spread']:.4f} m")
        print(f"  by pressure (cross-check: where the fitted hydrostatic pressure vanishes) "
              f"{surface['pressure']:.4f} m, {(surface['pressure'] - surface['volume']) / spacing:+.2f} d "
              f"from the volume's; gradient {surface['pressure_gradient']:.0f} Pa/m "
              f"= {surface['pressure_gradient'] / (rho0 * gravity):.4f} rho0 g")
        print(f"equilibrium draft {draft:.4f} m = {ratio:.4f} x Archimedes ({archimedes:.4f} m), "
              f"off by {100 * (ratio - 1):+.1f} % (from the pressure's surface: {pressure_draft:.4f} m, "
              f"{100 * (pressure_draft / archimedes - 1):+.1f} %)")
        if args.draft_tolerance is not None and abs(ratio - 1.0) > args.draft_tolerance:
            print(f"FAIL: draft ratio {ratio:.4f} outside 1 +- {args.draft_tolerance}")
            failed = True

    period, damping, count = heave_period(time, height, centre, 0.0)
    stiffness_open = rho0 * gravity * size
    stiffness_tank = stiffness_open * tank_width / (tank_width - size)
    t_open = 2 * math.pi * math.sqrt((mass + args.added_mass) / stiffness_open)
    t_tank = 2 * math.pi * math.sqrt((mass + args.added_mass) / stiffness_tank)
    result.update({"added_mass": args.added_mass, "period_open_water": t_open,
                   "period_tank": t_tank, "crossings": count})
    print(f"linear estimates with a33 = {args.added_mass:.0f} kg/m: open water "
          f"T = 2 pi sqrt((m + a33)/(rho0 g B)) = {t_open:.3f} s; in the tank (W = {tank_width} m, "
          f"stiffness x W/(W - B) = {tank_width / (tank_width - size):.3f}) {t_tank:.3f} s")
    if period is None:
        print(f"only {count} crossings of the mean height: no period measured; run longer")
        if args.period_tolerance is not None:
            print("FAIL: a period tolerance was given but no period was measured")
            failed = True
    else:
        result.update({"period": period, "damping_ratio": damping})
        damping_text = f", damping ratio {damping:.3f}" if damping is not None else ""
        print(f"heave period {period:.3f} s from {count} crossings of the mean "
              f"({period / t_tank:.3f} x T_tank, {period / t_open:.3f} x T_open){damping_text}")
        if args.period_tolerance is not None and abs(period / t_tank - 1.0) > args.period_tolerance:
            print(f"FAIL: period ratio {period / t_tank:.4f} outside 1 +- {args.period_tolerance}")
            failed = True

    settled = time >= args.settle_start
    mean_force = float(force[settled].mean())
    result.update({"mean_fluid_force_y": mean_force, "weight": mass * gravity})
    print(f"mean fluid force on the box after {args.settle_start} s: {mean_force:.1f} N/m "
          f"(its weight m g = {mass * gravity:.1f} N/m, ratio {mean_force / (mass * gravity):.4f})")

    write_analysis(args.run_dir, result)
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
