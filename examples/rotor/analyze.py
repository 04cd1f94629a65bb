#!/usr/bin/python3
"""The flexibly mounted rotor in a duct (thesis Figs 7.3-7.5): the flux it pumps, its centre's
trajectory about the mounting point and the hub forces, for one run or for several rates
(run_rates.py).

  analyze.py RUN_DIR [RUN_DIR ...] [--figure-prefix PATH] [--window-start T] [--require-growth]

Per run (its analysis.json), over the window from --window-start (default: half the run) to the
end, where the flow has spun up:
  - flux: the mean of the two FluxProbes (the duct's whole section a quarter period up- and
    downstream; equal in a steady flow, as the duct is periodic) and their relative difference;
  - the centre's displacement from where it started (the mounting point): its mean over the window
    and its largest distance over the whole run;
  - the hub forces (what the carrier's bearing exerts on the rotor), the drive torque, the thrust
    (minus the fluid's force on the rotor along x) and the drive's power T w;
  - the drive's work over the run, integral of T w dt, against the work the structure did on the
    fluid (run.json energy_audit): the fluid takes what the motor gives, less the rotor's and the
    mount's kinetic and spring energies;
  - action = reaction and the particle count (run.json checks).
--require-growth: exit status 1 unless the mean flux grows with the rate from run to run (the
issue's acceptance). Figures: PREFIX_flux.png (the flux in time per rate, and its mean against the
rate), PREFIX_trajectory.png (the centre's path across the axis, y-z, and along it in time),
PREFIX_hub.png (the hub forces and the drive torque). Default prefix: the first run's folder +
"/rotor".
"""
import argparse
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from fsi_results import finish_figure, read_run, require_run, write_analysis  # noqa: E402


def mean(values):
    return sum(values) / len(values) if values else float("nan")


def label_panel(axes, xlabel, ylabel, legend_size=8):
    """Axis labels, grid and legend of a figure's left panel (the right one: finish_figure)."""
    axes.set_xlabel(xlabel)
    axes.set_ylabel(ylabel)
    axes.grid(True, alpha=0.3)
    axes.legend(fontsize=legend_size)


def analyse(run_dir, window_start=None):
    run, s = read_run(run_dir)
    p = run["parameters_flat"]
    time = s["time"]
    start = 0.5 * time[-1] if window_start is None else window_start
    window = [i for i, t in enumerate(time) if t >= start]
    if len(window) < 2:
        raise SystemExit(f"analyze: {run_dir} has fewer than two samples after t = {start} s "
                         f"(it ends at {time[-1]} s): give a smaller --window-start")

    def over(name):
        return [s[name][i] for i in window]

    flux = [0.5 * (u + d) for u, d in zip(s["upstream_flux"], s["downstream_flux"])]
    up, down = mean(over("upstream_flux")), mean(over("downstream_flux"))
    moved = {axis: [v - s[f"centre_{axis}"][0] for v in s[f"centre_{axis}"]] for axis in "xyz"}
    distance = [math.sqrt(moved["x"][i] ** 2 + moved["y"][i] ** 2 + moved["z"][i] ** 2)
                for i in range(len(time))]
    rate = p["Rotor.rate"]
    # The drive's work: trapezoidal rule over the sensor samples of T w.
    drive_work = sum(0.5 * (s["drive_torque"][i] + s["drive_torque"][i - 1]) * rate *
                     (time[i] - time[i - 1]) for i in range(1, len(time)))
    section = p["Geometry.width"] * p["Geometry.depth"]
    result = {
        "rate": rate, "spacing": p["Fluid.spacing"], "status": run.get("status", "?"),
        "end_time": time[-1], "window_start": time[window[0]],
        "flux": mean([flux[i] for i in window]),
        "flux_upstream": up, "flux_downstream": down,
        "flux_probe_difference": abs(up - down) / max(abs(0.5 * (up + down)), 1e-30),
        "mean_speed_in_section": mean([flux[i] for i in window]) / section,
        "centre_mean_displacement": {axis: mean([moved[axis][i] for i in window]) for axis in "xyz"},
        "centre_max_distance": max(distance),
        "centre_max_distance_at": time[max(range(len(time)), key=lambda i: distance[i])],
        "hub_force_mean": {axis: mean(over(f"hub_{axis}")) for axis in "xyz"},
        "thrust_mean": -mean(over("rotor_fluid_x")),
        "drive_torque_mean": mean(over("drive_torque")),
        "drive_power_mean": rate * mean(over("drive_torque")),
        "drive_work": drive_work,
        "work_structure_on_fluid": run.get("energy_audit", {}).get("work_structure_on_fluid"),
        "max_action_reaction_relative": run["checks"]["max_action_reaction_relative"],
        "particles_lost": run["checks"]["particles_initial"] - run["checks"]["particles_final"],
    }
    return result, time, flux, moved, s


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("run_dirs", nargs="+")
    parser.add_argument("--figure-prefix", help="write PREFIX_flux.png, PREFIX_trajectory.png, PREFIX_hub.png")
    parser.add_argument("--window-start", type=float, help="average from this time on [s] (default: half the run)")
    parser.add_argument("--require-growth", action="store_true",
                        help="exit status 1 unless the mean flux grows with the rotation rate")
    args = parser.parse_args()

    analysed = []
    for run_dir in args.run_dirs:
        require_run(run_dir, "rotor")
        result, time, flux, moved, sensors = analyse(run_dir, args.window_start)
        write_analysis(run_dir, result)
        analysed.append((result, time, flux, moved, sensors))
        r = result
        print(f"{run_dir}: rate {r['rate']:g} rad/s, d = {1e3 * r['spacing']:.3g} mm, run {r['status']} "
              f"to t = {r['end_time']:.4f} s; means over t >= {r['window_start']:.4f} s:")
        print(f"  flux {1e6 * r['flux']:.4f} cm^3/s (mean speed in the section {1e3 * r['mean_speed_in_section']:.3f} mm/s; "
              f"the two probes differ by {100 * r['flux_probe_difference']:.1f} %)")
        c = r["centre_mean_displacement"]
        print(f"  centre from the mounting point: mean ({1e6 * c['x']:+.1f}, {1e6 * c['y']:+.1f}, "
              f"{1e6 * c['z']:+.1f}) um; farthest {1e6 * r['centre_max_distance']:.1f} um at "
              f"{r['centre_max_distance_at']:.4f} s")
        h = r["hub_force_mean"]
        print(f"  hub force on the rotor ({1e3 * h['x']:+.3f}, {1e3 * h['y']:+.3f}, {1e3 * h['z']:+.3f}) mN, "
              f"thrust {1e3 * r['thrust_mean']:+.3f} mN, drive torque {1e6 * r['drive_torque_mean']:+.2f} uN m "
              f"({1e3 * r['drive_power_mean']:.3f} mW)")
        audit = r["work_structure_on_fluid"]
        print(f"  drive work {1e3 * r['drive_work']:.4f} mJ, work on the fluid "
              f"{'?' if audit is None else f'{1e3 * audit:.4f}'} mJ; action = reaction to "
              f"{r['max_action_reaction_relative']:.1e}, particles lost {r['particles_lost']}")

    failed = False
    if len(analysed) > 1:
        ordered = sorted(analysed, key=lambda item: item[0]["rate"])
        print("flux against rate: " + ", ".join(f"{a[0]['rate']:g} rad/s: {1e6 * a[0]['flux']:.4f} cm^3/s"
                                                for a in ordered))
        grows = all(b[0]["flux"] > a[0]["flux"] for a, b in zip(ordered, ordered[1:]))
        print(f"the flux {'grows' if grows else 'does NOT grow'} with the rate")
        if args.require_growth and not grows:
            failed = True

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    prefix = args.figure_prefix or os.path.join(args.run_dirs[0], "rotor")
    figure, (left, right) = plt.subplots(1, 2, figsize=(10, 4))
    for result, time, flux, _, _ in analysed:
        left.plot(time, [1e6 * q for q in flux], label=f"{result['rate']:g} rad/s")
    label_panel(left, "t [s]", "flux through the duct [cm^3/s]")
    rates = [a[0]["rate"] for a in analysed]
    right.plot(rates, [1e6 * a[0]["flux"] for a in analysed], "o-", label="mean over the window")
    right.set_xlabel("rotation rate [rad/s]")
    right.set_ylabel("flux [cm^3/s]")
    finish_figure(figure, right, "Flux against rotation rate", prefix + "_flux.png")
    plt.close(figure)

    figure, (left, right) = plt.subplots(1, 2, figsize=(10, 4))
    for result, time, _, moved, _ in analysed:
        label = f"{result['rate']:g} rad/s"
        left.plot([1e6 * v for v in moved["y"]], [1e6 * v for v in moved["z"]], lw=0.8, label=label)
        right.plot(time, [1e6 * v for v in moved["x"]], label=label)
    left.plot([0], [0], "k+", ms=12, label="mounting point")
    left.set_aspect("equal", adjustable="datalim")
    label_panel(left, "y - y0 [um]", "z - z0 [um]")
    left.set_title("Rotor centre across the axis")
    right.set_xlabel("t [s]")
    right.set_ylabel("x - x0 along the axis [um]")
    finish_figure(figure, right, "Rotor centre along the axis", prefix + "_trajectory.png")
    plt.close(figure)

    figure, (left, right) = plt.subplots(1, 2, figsize=(10, 4))
    for result, time, _, _, sensors in analysed:
        label = f"{result['rate']:g} rad/s"
        line, = left.plot(time, [1e3 * v for v in sensors["hub_x"]], label=f"{label}: x")
        left.plot(time, [1e3 * v for v in sensors["hub_z"]], ls="--", color=line.get_color(), label=f"{label}: z")
        right.plot(time, [1e6 * v for v in sensors["drive_torque"]], label=label)
    label_panel(left, "t [s]", "hub force on the rotor [mN]", legend_size=7)
    right.set_xlabel("t [s]")
    right.set_ylabel("drive torque [uN m]")
    finish_figure(figure, right, "Hub forces and drive torque", prefix + "_hub.png")
    plt.close(figure)
    if failed:
        sys.exit("analyze: the flux does not grow with the rotation rate (--require-growth)")


if __name__ == "__main__":
    main()
