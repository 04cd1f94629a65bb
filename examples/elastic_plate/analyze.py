#!/usr/bin/python3
"""Elastic plate under a water column: the plate's mid-span deflection, averaged over the settled
interval, against the closed form of a clamped-clamped plate under a uniform load
(O'Connor & Rogers 2021, eq. for the hydrostatic plate):

  w = -0.0026 g (rho_w H + rho_s h) L^4 / D,   D = E h^3 / (12 (1 - nu^2))

(0.0026 is 1/384 rounded; the exact 1/384 is printed beside it, 0.15 % larger).

  analyze.py RUN_DIR [--tolerance F] [--settle-start T] [--figure PNG]

The deflection is the centre line's y at mid-span (sensor mid_y, 0 before the plate carries
anything), averaged over t >= settle-start (default: the second half of the run). A cross-check
separates the fluid's share of the error from the structure's: the mean fluid load on the plate
(sensor plate_fluid_force_y) against the column's weight rho_w g H L. --tolerance F fails the run
when |w_sim / w - 1| exceeds F (issue 14: 0.05 at the finest resolution)."""
import argparse
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from fsi_results import finish_figure, read_run, write_analysis  # noqa: E402


def mean_over(time, values, start):
    window = [v for t, v in zip(time, values) if t >= start]
    return sum(window) / len(window), min(window), max(window), len(window)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("run_dir")
    parser.add_argument("--tolerance", type=float, help="fail if |w_sim / w - 1| exceeds this")
    parser.add_argument("--settle-start", type=float, help="start of the averaging window [s] (default: half the run)")
    parser.add_argument("--figure", help="write a figure of w(t) against the closed form here (PNG)")
    args = parser.parse_args()

    run, sensors = read_run(args.run_dir)
    p = run["parameters_flat"]
    length, thickness, young, poisson = p["Geometry.L"], p["Geometry.h"], p["Geometry.E"], p["Geometry.nu"]
    rho_s, rho_w, height, g = p["Geometry.rho_s"], p["Geometry.rho_w"], p["Geometry.H"], p["Geometry.g"]
    rigidity = young * thickness ** 3 / (12.0 * (1.0 - poisson ** 2))
    load = g * (rho_w * height + rho_s * thickness)
    closed_form = -0.0026 * load * length ** 4 / rigidity
    exact = -load * length ** 4 / (384.0 * rigidity)
    time = sensors["time"]
    start = args.settle_start if args.settle_start is not None else 0.5 * time[-1]
    if start >= time[-1]:
        raise SystemExit(f"analyze: the averaging window starts at {start} s, after the run's end {time[-1]} s")
    deflection, low, high, rows = mean_over(time, sensors["mid_y"], start)
    fluid_load, _, _, _ = mean_over(time, sensors["plate_fluid_force_y"], start)
    weight = rho_w * g * height * length
    error = deflection / closed_form - 1.0
    result = {
        "spacing": p["Fluid.spacing"], "window": [start, time[-1]],
        "deflection": deflection, "deflection_min": low, "deflection_max": high,
        "closed_form": closed_form, "closed_form_1_384": exact, "relative_error": error,
        "relative_error_1_384": deflection / exact - 1.0,
        "fluid_load": -fluid_load, "column_weight": weight, "fluid_load_error": -fluid_load / weight - 1.0,
    }
    print(f"elastic plate, d = {result['spacing']} m, mean over t = {start:.3g}-{time[-1]:.3g} s ({rows} rows): "
          f"mid-span deflection {deflection:.4e} m (range {low:.3e} to {high:.3e}) against the closed form "
          f"-0.0026 g (rho_w H + rho_s h) L^4 / D = {closed_form:.4e} m: {100 * error:+.2f} % "
          f"(against 1/384: {exact:.4e} m, {100 * result['relative_error_1_384']:+.2f} %)")
    print(f"  the fluid's load on the plate {-fluid_load:.1f} N/m against the column's weight rho_w g H L = "
          f"{weight:.1f} N/m: {100 * result['fluid_load_error']:+.2f} %")
    if args.figure:
        draw(time, sensors["mid_y"], result, args.figure)
    write_analysis(args.run_dir, result)
    if args.tolerance is not None and abs(error) > args.tolerance:
        print(f"FAIL: deflection error {100 * error:+.2f} % outside +-{100 * args.tolerance:g} %")
        return 1
    return 0


def draw(time, deflection, result, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    figure, axes = plt.subplots(figsize=(7.2, 3.6))
    axes.plot(time, [1e6 * w for w in deflection], lw=0.8, label=f"SPH + ANCF, d = {1000 * result['spacing']:g} mm")
    axes.axhline(1e6 * result["closed_form"], color="k", ls="--", label="closed form (O'Connor & Rogers 2021)")
    axes.axvspan(*result["window"], color="0.9", label=f"mean {1e6 * result['deflection']:.2f} µm "
                 f"({100 * result['relative_error']:+.2f} %)")
    axes.set_xlabel("t [s]")
    axes.set_ylabel("mid-span deflection [µm]")
    finish_figure(figure, axes, "Elastic plate under a 2 m water column", path, legend_location="lower right")


if __name__ == "__main__":
    sys.exit(main())
