#!/usr/bin/python3
"""Particle pairs along the walls (docs/theory.md): fsi-server counts, in every snapshot, the
particles closer than d/2, and the settled tank of examples/wave_flume/corner_tank.scene (320
particles, the flume's scripts) holds such a pair in each floor corner, which LIGGGHTS' Shepard
density filter lets form; the same tank without the filter holds none, and with its floor corners
rounded none as close. Runs the example's own particle_pairs.py for those three variants, then the
tank with a density limit its corner pair exceeds: the stop names the pair and says that the speed
of sound is not the cure (about 18 s)."""
import os
import subprocess
import sys

from fsi_test import ENV, binary, check, cleanup, example, work_dir
from run_manifest import read_run_manifest

work = work_dir("particle_pairs")
script = example("wave_flume", "particle_pairs.py")
result = subprocess.run([sys.executable, script, work, "--bin", os.path.dirname(binary("fsi-run")),
                         "--only", "as committed", "no filter", "rounded r = 4 d"],
                        env=ENV, capture_output=True, text=True, timeout=600)
print(result.stdout + result.stderr[-3000:])
check(result.returncode == 0, f"particle_pairs.py exits 0 (got {result.returncode})")

committed = read_run_manifest(os.path.join(work, "as_committed"))
checks = committed["checks"]
closest = checks["closest_particle_pair_over_spacing_at_snapshots"]
check(committed["status"] == "completed", "the committed tank's run completes")
check(checks["max_particle_pairs_at_snapshots"] >= 2,
      f"the committed tank holds a pair in each floor corner ({checks['max_particle_pairs_at_snapshots']} "
      "pairs < d/2 in one snapshot, at least 2)")
# Measured 2026-12-07: 0.13 d at (0.018, 0.018) m; the corner's site is 0.75 d from both walls.
check(closest is not None and closest < 0.25, f"the closest pair {closest} d apart (< 0.25 d)")
place = checks["closest_particle_pair_place"]
check(place is not None and min(abs(place[0]), abs(place[0] - 0.5)) < 0.05 and place[1] < 0.05,
      f"the closest pair sits in a floor corner: {place}")
with open(os.path.join(work, "as_committed", "fsi-server.log")) as handle:
    log = handle.read()
check("pairs < d/2 (closest" in log and "particle pairs: up to" in log,
      "the progress lines and the log's end name the pairs")

unfiltered = read_run_manifest(os.path.join(work, "no_filter"))
check(unfiltered["checks"]["max_particle_pairs_at_snapshots"] == 0
      and unfiltered["checks"]["closest_particle_pair_over_spacing_at_snapshots"] is None,
      "without the Shepard filter no pair closer than d/2 forms")

# Rounded floor corners (arcs of 4 d): no corner where two walls' first layers meet, and no pair as
# close as the corner's (measured 2026-12-07: the closest 0.37 d, on a side wall, against 0.13 d).
rounded = read_run_manifest(os.path.join(work, "rounded_r_4_d"))["checks"]
rounded_closest = rounded["closest_particle_pair_over_spacing_at_snapshots"]
check(rounded_closest is None or rounded_closest > 0.25,
      f"with rounded corners no pair closer than 0.25 d forms (closest {rounded_closest} d)")

# The corner pair is the densest place of the settled tank (1.0064 rho0, measured 2026-12-07): a
# limit of 0.0064 stops the run at release there.
stop_dir = os.path.join(work, "stop")
result = subprocess.run([binary("fsi-run"), example("wave_flume", "corner_tank.scene"), "--np", "1",
                         "--output", stop_dir, "--set", "FluidHealth.max_density_deviation=0.0064",
                         "--set", "FluidHealth.warn_density_deviation=0.005"],
                        env=ENV, capture_output=True, text=True, timeout=600)
stopped = read_run_manifest(stop_dir)
reason = stopped["reason"] or ""
print(reason[-1500:])
check(result.returncode == 1 and stopped["health"]["failed_check"] == "density_deviation",
      f"the tight limit stops the run on density_deviation (exit {result.returncode})")
check("it is one of a particle pair" in reason and "d apart (closer than d/2)" in reason,
      "the stop names the extreme particle's pair")
check("a larger speed of sound only delays such a stop" in reason
      and reason.index("only delays") < reason.index("raise Fluid.speed_of_sound"),
      "the advice says first that c is not the cure for a pair")
cleanup(work)
