#!/usr/bin/python3
"""Plots a static tank run (thesis Figs. 6.3-6.5): piston displacement, fluid force on the piston,
and the fluid weight on the bottom (vertex forces and Lagrange multipliers) against N m g.
Usage: plot.py RUN_DIR   -> RUN_DIR/sensors.png"""
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main():
    run_dir = sys.argv[1]
    rows = [line for line in open(os.path.join(run_dir, "sensors.csv")) if not line.startswith("#")]
    header = rows[0].strip().split(",")
    data = {name: [] for name in header}
    for line in rows[1:]:
        for name, value in zip(header, line.strip().split(",")):
            data[name].append(float(value))
    run = json.load(open(os.path.join(run_dir, "run.json")))
    fluid = run["fluid"]
    gravity = run["model"]["gravity"]
    weight = fluid["particle_count"] * fluid["particle_mass"] * abs(gravity[1])
    bottom_mass = {b["name"]: b["mass"] for b in run["model"]["bodies"]}["bottom"]
    t = data["time"]
    figure, axes = plt.subplots(3, 1, figsize=(8, 9), sharex=True)
    y0 = data["piston_position_y"][0]
    axes[0].plot(t, [y0 - y for y in data["piston_position_y"]])
    axes[0].set_ylabel("piston displacement [m]")
    axes[1].plot(t, data["piston_fluid_force_y"])
    axes[1].set_ylabel("fluid force on piston, y [N/m]")
    axes[2].plot(t, [-f for f in data["bottom_fluid_force_y"]], label="sum of vertex forces")
    axes[2].plot(t, [c + bottom_mass * gravity[1] for c in data["bottom_constraint_force_y"]], "--",
                 label="from Lagrange multipliers")
    if "total_fluid_force_y" in data:
        axes[2].plot(t, [-f for f in data["total_fluid_force_y"]], ":", label="on all boundaries")
    axes[2].axhline(weight, color="k", linewidth=0.8, label="N m g")
    axes[2].set_ylabel("fluid weight on bottom [N/m]")
    axes[2].set_xlabel("time [s]")
    axes[2].legend(loc="lower right")
    figure.suptitle(f"static tank, {fluid['particle_count']} particles")
    figure.tight_layout()
    path = os.path.join(run_dir, "sensors.png")
    figure.savefig(path, dpi=110)
    print(path)


if __name__ == "__main__":
    main()
