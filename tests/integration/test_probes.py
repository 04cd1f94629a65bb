#!/usr/bin/python3
"""Probes with real LIGGGHTS (issue 13): the coarse water column of examples/water_column (about
1 200 particles, fsi-run with 2 ranks split along x, so the probes' partial sums come from both
ranks) with a point, a free-surface, a fluid-energy and two front probes. At rest after release:
- fluid_energy at t = 0 equals the client's own account at release (run.json "release", summed by
  another code path): kinetic energy exactly, potential energy sum m g y = the release's
  (heights above the lowest particle) + M g y_lowest, y_lowest read by the downward front probe;
- the free surface lies within one spacing d of the column's top from its centre of mass (a
  uniform column: top = 2 y_mean - y_lowest + d/2, y_mean = potential / (M g));
- the point probe's pressure, averaged over the run, is within 3 % of rho0 g (level - y) with the
  level of the free-surface probe, and the point is wet with 30-60 particles in its support;
- the rightward front lies within one kernel support 2h of the right wall.
Then a client offering only the capabilities of protocol 1.2 (fake_peer, no probes) is refused by
name before any set-up data."""
import os
import statistics
import subprocess

from fsi_test import (ENV, binary, check, cleanup, example, load_sensors, manifest, refused_client,
                      work_dir)

RHO0, G = 1000.0, 9.81
H = 0.004
D = H / 1.9
WIDTH = 0.05
GAUGE_Y = 0.04

output = work_dir("probes")
scene = os.path.join(output, "probes.scene")
with open(scene, "w") as handle:
    handle.write(f"""scene_language = 1
include "{example("water_column", "water_column.scene")}"
PointProbe {{ name = "gauge"; point = [0.025, {GAUGE_Y}] }}
FreeSurfaceProbe {{ name = "level"; bottom = [0.025, 0.0]; length = 0.2 }}
FluidEnergyProbe {{ name = "water" }}
FrontProbe {{ name = "bottom"; axis = "y"; direction = "decreasing" }}
FrontProbe {{ name = "right"; axis = "x" }}
""")

run_dir = os.path.join(output, "run")
result = subprocess.run([binary("fsi-run"), scene, "--np", "2", "--output", run_dir,
                         "--set", "SolverOptions.end_time=0.01"],
                        env=ENV, capture_output=True, text=True, timeout=900)
print(result.stderr[-3000:])
check(result.returncode == 0, f"fsi-run exits 0 (got {result.returncode})")
run = manifest(run_dir)
with open(os.path.join(run_dir, "sensors.csv")) as handle:
    units = [line for line in handle if line.startswith("# units")][0]
check("gauge_pressure [Pa]" in units and "water_potential [J/m]" in units and "level_elevation [m]" in units,
      "sensors.csv names the probes' columns with units")
s = load_sensors(run_dir)
rows = len(s["time"])
check(rows == 401, f"a row per step with the probes of that step: {rows} rows")

release = run["release"]
mass = release["fluid_mass"]
kinetic, potential, lowest = s["water_kinetic"][0], s["water_potential"][0], s["bottom_position"][0]
check(abs(kinetic - release["kinetic_energy"]) <= 1e-9 * release["kinetic_energy"],
      f"kinetic energy at t = 0: probe {kinetic:.12g} = release {release['kinetic_energy']:.12g} J/m")
expected = release["potential_energy"] + mass * G * lowest
check(abs(potential - expected) <= 1e-9 * expected,
      f"potential energy at t = 0: probe {potential:.12g} = release + M g y_lowest = {expected:.12g} J/m")
check(max(s["water_kinetic"]) < 1e-3 * min(s["water_potential"]), "the water stays at rest (kinetic < 1e-3 potential)")

check(all(w == 1.0 for w in s["level_wet"]), "the free-surface line is wet")
for k in (0, rows - 1):
    mean_height = s["water_potential"][k] / (mass * G)
    top = 2 * mean_height - s["bottom_position"][k] + D / 2
    level = s["level_elevation"][k]
    check(abs(level - top) <= D,
          f"t = {s['time'][k]:.3g} s: free surface {level:.5f} m within d = {D:.5f} m of the top from the centre of mass {top:.5f} m")

check(all(w == 1.0 for w in s["gauge_wet"]), "the point probe is wet")
check(all(30 <= n <= 60 for n in s["gauge_particles"]),
      f"30-60 particles within the kernel support of the point ({min(s['gauge_particles']):.0f}-{max(s['gauge_particles']):.0f})")
measured = statistics.mean(s["gauge_pressure"])
hydrostatic = statistics.mean(RHO0 * G * (level - GAUGE_Y) for level in s["level_elevation"])
check(abs(measured - hydrostatic) <= 0.03 * hydrostatic,
      f"pressure at the point {measured:.1f} Pa within 3 % of rho0 g (level - y) = {hydrostatic:.1f} Pa (mean over the run)")
check(all(WIDTH - 2 * H <= x <= WIDTH for x in s["right_position"]),
      f"the rightward front within 2h of the right wall ({min(s['right_position']):.5f}-{max(s['right_position']):.5f} m)")

# A client of protocol 1.2 knows no probes: the server refuses it by name before any set-up data
# (such a client would otherwise run its whole set-up and equilibration first).
said = refused_client(scene, os.path.join(output, "old_client"), 4)
check("session capabilities 6" in said, "the session agreed on heartbeats and settling, no probes")
check("error: [SetupFailed]" in said and "lacks probes (capability 'probes' of protocol 1.3)" in said
      and "use an fsi-client of protocol 1.3 or later" in said,
      "the client is told what it lacks and how to fix it")
cleanup(output)
