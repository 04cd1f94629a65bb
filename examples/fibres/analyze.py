#!/usr/bin/python3
"""Fibres in a flow (thesis Figs 7.9 and 7.10): the flow speed in front of the array and the
tip deflections of the fibres, for one run or for the four runs of run_four.py.

  analyze.py RUN_DIR [RUN_DIR ...] [--figure-prefix PATH] [--until T]

Per run (its analysis.json): the largest speed |v| of the probe `front` in front of the array and
when the surge reaches it (the first wet sample), and for each sensed fibre tip its largest
deflection along the flow, dx = x(t) - x(0), with its time. With several runs, each run's label
is its viscosity and bending stiffness (run.json), and the figures put them side by side:
PREFIX_speed.png (Fig. 7.9) and PREFIX_tips.png (Fig. 7.10: the row next to the back wall,
fibre_13, fibre_23, fibre_33 in the order the water reaches them). Default prefix: the first
run's folder + "/fibres". --until T: only t <= T (runs that ended at different times compared over
the same interval; a run stopped by a health check keeps its sensors up to the stop).
"""
import argparse
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from fsi_results import finish_figure, read_run, require_run, write_analysis  # noqa: E402

TIPS = ["13", "23", "33", "12", "22", "32"]


def analyse(run_dir, until=None):
    run, sensors = read_run(run_dir)
    if until is not None:
        keep = [i for i, t in enumerate(sensors["time"]) if t <= until + 1e-12]
        sensors = {name: [values[i] for i in keep] for name, values in sensors.items()}
    status = run.get("status", "?")
    p = run["parameters_flat"]
    time = sensors["time"]
    speed = [math.sqrt(vx * vx + vy * vy + vz * vz)
             for vx, vy, vz in zip(sensors["front_vx"], sensors["front_vy"], sensors["front_vz"])]
    wet = [t for t, w in zip(time, sensors["front_wet"]) if w > 0]
    peak = max(range(len(speed)), key=lambda i: speed[i])
    result = {
        "viscosity": p["Fibres.viscosity"], "bending_stiffness": p["Fibres.bending_stiffness"],
        "spacing": p["Fluid.spacing"], "end_time": time[-1], "status": status,
        "front_arrival": wet[0] if wet else None,
        "front_peak_speed": speed[peak], "front_peak_time": time[peak],
        "front_mean_speed_second_half": sum(v for t, v in zip(time, speed) if t >= 0.5 * time[-1])
        / max(1, sum(1 for t in time if t >= 0.5 * time[-1])),
        "tips": {},
    }
    for tip in TIPS:
        column = f"tip_{tip}_x"
        if column not in sensors:
            continue
        x = sensors[column]
        deflection = [value - x[0] for value in x]
        largest = max(range(len(deflection)), key=lambda i: abs(deflection[i]))
        result["tips"][tip] = {"max_deflection": deflection[largest], "at": time[largest],
                               "final_deflection": deflection[-1]}
    return result, time, speed, sensors


def label(result):
    return f"nu = {result['viscosity']:.3g} m^2/s, EI = {result['bending_stiffness']:.3g} N m^2"


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("run_dirs", nargs="+")
    parser.add_argument("--figure-prefix", help="write PREFIX_speed.png and PREFIX_tips.png")
    parser.add_argument("--until", type=float, help="only the samples with t <= this [s]")
    args = parser.parse_args()

    analysed = []
    for run_dir in args.run_dirs:
        require_run(run_dir, "fibres")
        result, time, speed, sensors = analyse(run_dir, args.until)
        write_analysis(run_dir, result)
        analysed.append((run_dir, result, time, speed, sensors))
        arrival = result["front_arrival"]
        print(f"{run_dir}: {label(result)}, d = {1e3 * result['spacing']:.3g} mm, run {result['status']}, "
              f"analysed to t = {result['end_time']:.4f} s")
        print(f"  front probe: wet from {arrival if arrival is None else f'{arrival:.4f}'} s, "
              f"peak |v| {result['front_peak_speed']:.4f} m/s at {result['front_peak_time']:.4f} s, "
              f"mean over the second half {result['front_mean_speed_second_half']:.4f} m/s")
        for tip, values in result["tips"].items():
            print(f"  fibre_{tip} tip: largest dx {1e3 * values['max_deflection']:+.4f} mm at "
                  f"{values['at']:.4f} s, at the end {1e3 * values['final_deflection']:+.4f} mm")

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    prefix = args.figure_prefix or os.path.join(args.run_dirs[0], "fibres")
    figure, axes = plt.subplots(figsize=(7, 4))
    for _, result, time, speed, _ in analysed:
        axes.plot(time, speed, label=label(result))
    axes.set_xlabel("t [s]")
    axes.set_ylabel("|v| in front of the fibres [m/s]")
    finish_figure(figure, axes, "Flow speed in front of the fibres (thesis Fig. 7.9)",
                  prefix + "_speed.png")
    plt.close(figure)

    figure, panels = plt.subplots(1, len(analysed), figsize=(4.2 * len(analysed), 3.8), squeeze=False,
                                  sharey=True)
    for axes, (_, result, time, _, sensors) in zip(panels[0], analysed):
        for tip in ("13", "23", "33"):
            column = f"tip_{tip}_x"
            if column in sensors:
                x = sensors[column]
                axes.plot(time, [1e3 * (value - x[0]) for value in x], label=f"fibre_{tip}")
        axes.set_xlabel("t [s]")
        axes.set_title(label(result), fontsize=8)
        axes.grid(True, alpha=0.3)
        axes.legend(fontsize=7)
    panels[0][0].set_ylabel("tip deflection along x [mm]")
    figure.suptitle("Tip deflections, row next to the back wall (thesis Fig. 7.10)")
    figure.tight_layout()
    figure.savefig(prefix + "_tips.png", dpi=110)
    print(f"figure: {prefix}_tips.png")


if __name__ == "__main__":
    main()
