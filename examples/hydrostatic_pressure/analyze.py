#!/usr/bin/python3
"""Hydrostatic wall pressure (issue 13): the ten wall pressure probes on the tank's left wall
against rho0 g (H - y). Reads DIR/run.json and DIR/sensors.csv of a run of
hydrostatic_pressure*.scene, averages every probe over the rows from --settle-start on (the water is
at rest from its release), prints each patch's pressure and its error against the reference, draws
DIR/hydrostatic_pressure.png and writes DIR/analysis.json.

H is the water's level from its mass, H = N m / (rho0 b), b the tank's width (the FluidRegion is
the water itself, N d^2 = b H). The acceptance covers the patches that lie wholly below the top two
smoothing lengths, y_centre + radius <= H - 2h: there the mean pressure of each patch
must be within --tolerance of rho0 g (H - y_centre) (over a patch the reference is linear, so its
mean is its value at the centre). Exit status 1 when one is not.

Usage: analyze.py DIR [--tolerance 0.02] [--settle-start 0]"""
import argparse
import math
import os
import re
import statistics
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from fsi_results import read_run, write_analysis  # noqa: E402



def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("run_dir")
    parser.add_argument("--tolerance", type=float, default=0.02,
                        help="largest |p / (rho0 g (H - y)) - 1| of a patch below H - 2h (default 0.02)")
    parser.add_argument("--settle-start", type=float, default=0.02,
                        help="start of the averaging [s] (default 0.02: the release's ringing has decayed)")
    parser.add_argument("--no-figure", action="store_true")
    args = parser.parse_args()
    run, sensors = read_run(args.run_dir)
    parameters = run["parameters_flat"]
    width = parameters["Geometry.width"]
    patch_radius = parameters["Geometry.patch_radius"]
    # The Fluid block's h (run.json lists its derived values too); a hand-written block's otherwise.
    h = parameters.get("Fluid.smoothing_length", parameters.get("LIGGGHTS_SPH_parameters.smoothinglength"))
    fluid = run["fluid"]
    rho0, spacing = fluid["density"], fluid["spacing"]
    g = math.hypot(*run["model"]["gravity"])
    count = fluid["particle_count"]
    level = count * fluid["particle_mass"] / (rho0 * width)
    rows = [k for k, t in enumerate(sensors["time"]) if t >= args.settle_start - 1e-12]
    if not rows:
        print(f"analyze: no sensors.csv row from t = {args.settle_start} s on")
        return 1
    print(f"{count} particles, d = {1e3 * spacing:.3g} mm, h = {1e3 * h:.3g} mm; H = N m / (rho0 b) = "
          f"{1e3 * level:.3f} mm; {len(rows)} rows from t = {sensors['time'][rows[0]]:.4g} s to "
          f"{sensors['time'][rows[-1]]:.4g} s")
    surface = None
    if "level_elevation" in sensors:
        surface = statistics.mean(sensors["level_elevation"][k] for k in rows)
        print(f"free surface at the centre (FreeSurfaceProbe 'level'): {1e3 * surface:.3f} mm, "
              f"{(surface - level) / spacing:+.2f} d above H (informative: the last column's reference)")
    top = level - 2.0 * h
    patches = []
    for name in sensors:
        match = re.fullmatch(r"p(\d\d)_pressure", name)
        if not match:
            continue
        y = 1e-3 * int(match.group(1))
        values = [sensors[name][k] for k in rows]
        pairs = min(sensors[f"p{match.group(1)}_pairs"][k] for k in rows)
        reference = rho0 * g * (level - y)
        mean = statistics.mean(values)
        patches.append({"name": f"p{match.group(1)}", "y": y, "pressure": mean,
                        "pressure_std": statistics.pstdev(values), "reference": reference,
                        "relative_error": mean / reference - 1.0, "min_pairs": pairs,
                        "relative_error_to_surface": (mean / (rho0 * g * (surface - y)) - 1.0
                                                      if surface is not None else None),
                        "judged": y + patch_radius <= top + 1e-12})
    patches.sort(key=lambda patch: patch["y"])
    print(f"patch   y [mm]   p [Pa]  (std)   rho0 g (H - y) [Pa]   error    judged (below H - 2h = {1e3 * top:.2f} mm)"
          "   [error against the free surface's level]")
    for patch in patches:
        to_surface = patch["relative_error_to_surface"]
        print(f"{patch['name']:>5}  {1e3 * patch['y']:6.1f}  {patch['pressure']:8.2f} ({patch['pressure_std']:5.2f})"
              f"  {patch['reference']:10.2f}          {100 * patch['relative_error']:+6.2f} %  "
              f"{'yes' if patch['judged'] else 'no ':3}"
              + (f"        [{100 * to_surface:+6.2f} %]" if to_surface is not None else ""))
    judged = [patch for patch in patches if patch["judged"]]
    worst = max(judged, key=lambda patch: abs(patch["relative_error"])) if judged else None
    rms = math.sqrt(statistics.mean(p["relative_error"] ** 2 for p in judged)) if judged else float("nan")
    result = {"particles": count, "spacing": spacing, "smoothing_length": h, "level": level,
              "judged_below": top, "tolerance": args.tolerance, "patches": patches,
              "max_abs_relative_error": abs(worst["relative_error"]) if worst else None,
              "rms_relative_error": rms}
    write_analysis(args.run_dir, result)
    if not args.no_figure:
        draw(args.run_dir, patches, rho0, g, level, top, count, spacing, patch_radius)
    if len(judged) < 8:
        print(f"FAIL: only {len(judged)} patches lie below H - 2h (8 or more expected)")
        return 1
    print(f"largest |error| below H - 2h: {100 * abs(worst['relative_error']):.2f} % ({worst['name']}), "
          f"RMS {100 * rms:.2f} %, tolerance {100 * args.tolerance:.1f} %")
    if abs(worst["relative_error"]) > args.tolerance:
        print("FAIL: a patch's pressure is outside the tolerance")
        return 1
    return 0


def draw(run_dir, patches, rho0, g, level, top, count, spacing, patch_radius):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    figure, (profile, error) = plt.subplots(1, 2, figsize=(9, 5), sharey=True)
    heights = [1e3 * patch["y"] for patch in patches]
    profile.plot([rho0 * g * level, 0.0], [0.0, 1e3 * level], "k-", label=r"$\rho_0 g (H - y)$")
    profile.errorbar([p["pressure"] for p in patches], heights, xerr=[p["pressure_std"] for p in patches],
                     yerr=1e3 * patch_radius, fmt="o", capsize=2, label="wall pressure probes (patch, std over time)")
    for axis in (profile, error):
        axis.axhspan(1e3 * top, 1e3 * level, color="0.9", label="top 2h (not judged)")
    profile.set_xlabel("pressure on the left wall [Pa]")
    profile.set_ylabel("height y [mm]")
    profile.legend(loc="upper right", fontsize=8)
    error.plot([100 * p["relative_error"] for p in patches], heights, "o-")
    error.axvline(0.0, color="k", linewidth=0.8)
    error.set_xlabel(r"$p / (\rho_0 g (H - y)) - 1$ [%]")
    figure.suptitle(f"hydrostatic wall pressure, {count} particles, d = {1e3 * spacing:.3g} mm")
    figure.tight_layout()
    path = os.path.join(run_dir, "hydrostatic_pressure.png")
    figure.savefig(path, dpi=120)
    print(f"figure: {path}")


if __name__ == "__main__":
    sys.exit(main())
