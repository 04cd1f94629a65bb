#!/usr/bin/python3
"""How far the water stands off the cylinder and off the channel's flat walls, from a run's particle
snapshots: does the cylinder hold the fluid further out than the flat walls (README.md, "What to
expect": the residual after the effective geometry)?

  standoff.py RUN_DIR [--window T0,T1] [--band B]

Two measures, each averaged over the snapshots in the window (default 2,6 s) and given in units of
the particle spacing d:
- first layer: the nearest particle's distance to the wall, per 24th of the cylinder's
  circumference and per d of wall height (|y| < 0.15 m), averaged over the pieces that have a
  particle within the band; the cylinder's others are counted as dry;
- excluded thickness: in a band B d wide along the wall (default 3), the band's area less the
  particles' volume (d^2 rho0/rho each), spread over the wall: the thickness the fluid leaves
  empty as the flow sees it (for the cylinder, the radius by which a solid cylinder would have to
  grow to exclude that area).
Around the cylinder, per twelfth (30 degrees, counted from +x; the flow runs along +y, so 0-180 is
the downstream half): the first layer and the mean pressure of the particles within 1.5 d of the
surface, and the same pressure beside the flat walls: a wall cannot pull, so where that pressure
falls below zero the water leaves the wall (README.md, "Gravity, and the water behind the
cylinder").
W, r and d come from the run's run.json; RUN_DIR/standoff.json holds the numbers (in metres, Pa)."""
import argparse
import json
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from fsi_results import read_snapshots  # noqa: E402


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("run_dir")
    parser.add_argument("--window", default="2,6", help="T0,T1 in seconds (default 2,6)")
    parser.add_argument("--band", type=float, default=3.0, help="band width in spacings (default 3)")
    args = parser.parse_args()
    t0, t1 = (float(v) for v in args.window.split(","))
    with open(os.path.join(args.run_dir, "run.json")) as handle:
        run = json.load(handle)
    flat = run["parameters_flat"]
    W, r = flat["Geometry.W"], flat["Geometry.r"]
    d, rho0 = run["fluid"]["spacing"], run["fluid"]["density"]
    band, height = args.band * d, 0.15
    rows, twelfths, wall_pressures = [], [], []
    for t, a in read_snapshots(args.run_dir, t0, t1):
        x, y, density, pressure = a["x"], a["y"], a["density"], a["pressure"]
        volume = d * d * rho0 / density
        radius = np.hypot(x, y)
        near = radius < r + band
        # 24ths of the circumference counted from +x (the flow along +y: 0-12 is downstream).
        sector = np.floor((np.arctan2(y, x)[near] % (2 * np.pi)) / (2 * np.pi / 24)).astype(int)
        gap = radius[near] - r
        cylinder_layer = np.mean([gap[sector == s].min() for s in np.unique(sector)])
        dry = 24 - len(np.unique(sector))  # 24ths with no particle within the band
        # Per twelfth: the first layer and the pressure within 1.5 d.
        twelfth = sector // 2
        touching = gap < 1.5 * d
        twelfths.append([(gap[twelfth == k].min() if np.any(twelfth == k) else np.nan,
                          pressure[near][(twelfth == k) & touching].mean()
                          if np.any((twelfth == k) & touching) else np.nan) for k in range(12)])
        deficit = np.pi * ((r + band) ** 2 - r ** 2) - volume[near].sum()
        cylinder_excluded = np.sqrt(r * r + deficit / np.pi) - r
        wall_layer, wall_excluded = [], []
        for side in (-1.0, 1.0):
            distance = 0.5 * W - side * x
            strip = (np.abs(y) < height) & (distance < band)
            piece = np.floor((y[strip] + height) / d).astype(int)
            wall_layer.append(np.mean([distance[strip][piece == p].min() for p in np.unique(piece)]))
            wall_excluded.append((band * 2 * height - volume[strip].sum()) / (2 * height))
            wall_pressures.append(pressure[strip & (distance < 1.5 * d)].mean())
        rows.append((cylinder_layer, np.mean(wall_layer), cylinder_excluded, np.mean(wall_excluded), dry))
        print(f"t = {t:5.2f} s   first layer: cylinder {cylinder_layer / d:.3f} d, walls "
              f"{np.mean(wall_layer) / d:.3f} d   excluded: cylinder {cylinder_excluded / d:.3f} d, "
              f"walls {np.mean(wall_excluded) / d:.3f} d   dry 24ths of the cylinder {dry}")
    if not rows:
        sys.exit(f"standoff.py: no snapshot of {args.run_dir} lies in {t0}-{t1} s (Output "
                 "{ snapshot_every_steps } sets how often the run writes them)")
    dry = np.array(rows)[:, 4]
    rows = np.array(rows)[:, :4]
    m, s = np.mean(rows, axis=0) / d, np.std(rows, axis=0) / d
    print(f"d = {1000 * d:g} mm, {len(rows)} snapshots in {t0:g}-{t1:g} s (mean ± std over them):")
    print(f"  first layer:        cylinder {m[0]:.2f} ± {s[0]:.2f} d (over its wet 24ths), flat walls "
          f"{m[1]:.2f} ± {s[1]:.2f} d")
    print(f"  dry 24ths of the cylinder (no particle within {args.band:g} d): {dry.min():.0f}-{dry.max():.0f}")
    print(f"  excluded thickness: cylinder {m[2]:.2f} ± {s[2]:.2f} d, flat walls {m[3]:.2f} ± {s[3]:.2f} d")
    twelfths = np.array(twelfths)
    wet = np.isfinite(twelfths)
    around = np.where(wet.any(axis=0), np.nansum(twelfths, axis=0) / np.maximum(wet.sum(axis=0), 1), np.nan)
    wall_pressure = float(np.mean(wall_pressures))
    print(f"  around the cylinder (degrees from +x, the flow along +y), against the flat walls' "
          f"{wall_pressure:.1f} Pa within 1.5 d:")
    for k, (layer, p) in enumerate(around):
        if np.isnan(layer):
            print(f"    {30 * k:3d}-{30 * k + 30:<3d}  dry: no particle within {args.band:g} d in any snapshot")
        else:
            print(f"    {30 * k:3d}-{30 * k + 30:<3d}  first layer {layer / d:.2f} d   pressure within 1.5 d "
                  f"{p:7.1f} Pa")
    names = ("cylinder_first_layer", "walls_first_layer", "cylinder_excluded", "walls_excluded")
    result = {"spacing": d, "window": [t0, t1], "snapshots": len(rows)}
    for k, name in enumerate(names):
        result[name] = {"mean": float(m[k] * d), "std": float(s[k] * d)}
    result["cylinder_dry_24ths"] = {"min": int(dry.min()), "max": int(dry.max())}
    result["cylinder_twelfths"] = [{"from_degrees": 30 * k,
                                    "first_layer": None if np.isnan(layer) else float(layer),
                                    "pressure": None if np.isnan(p) else float(p)}
                                   for k, (layer, p) in enumerate(around)]
    result["walls_pressure"] = wall_pressure
    with open(os.path.join(args.run_dir, "standoff.json"), "w") as handle:
        json.dump(result, handle, indent=2)


if __name__ == "__main__":
    main()
