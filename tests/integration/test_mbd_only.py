#!/usr/bin/python3
"""`fsi-server --mbd-only`: the coarse static tank's multibody part alone, without fsi-client, 1000
steps. It must finish by itself (no client is waited for) and write sensors.csv and run.json like
a coupled run. Without fluid the answer is known exactly: the piston follows y = 0.0725 - 0.05 t,
the held bottom and the driven piston each carry their own weight through the constraint
(-(constraint force) = gravity, so the constraint force is +m g = +0.981 N/m), fluid forces are 0."""
import math
import os
import subprocess

from fsi_test import (ENV, binary, check, cleanup, example, fail, load_sensors, manifest, read, static_tank_variant,
                      work_dir)

STEPS = 1000
DT = 1e-5
WEIGHT = 0.1 * 9.81

output = work_dir("mbd_only")
run_dir = os.path.join(output, "run")
command = [binary("fsi-server"), example("static_tank", "static_tank_coarse.scene"), "--mbd-only",
           "--output", run_dir, "--set", f"Resolution.end_time={STEPS}*{DT}"]
try:
    result = subprocess.run(command, env=ENV, capture_output=True, text=True, timeout=120)
except subprocess.TimeoutExpired:
    fail("fsi-server --mbd-only did not finish within 120 s (is it waiting for a client?)")
if result.returncode != 0:
    fail(f"fsi-server --mbd-only exited {result.returncode}:\n{result.stderr[-3000:]}")
check(True, "fsi-server --mbd-only exits 0 without a client")

run = manifest(run_dir)
check(run.get("mode") == "mbd-only", "run.json says mode mbd-only")
check(run["status"] == "completed", "run.json says completed")
check(run["steps"] == STEPS, f"run.json counts {STEPS} steps")
check(run["newton"]["iterations"] >= STEPS, "run.json has the Newton statistics")
check(run["scene"]["overrides"] == [f"Resolution.end_time={STEPS}*{DT}"],
      f"run.json records the --set overrides ({run['scene']['overrides']})")

sensors = load_sensors(run_dir)
times = sensors["time"] if "time" in sensors else sensors[list(sensors)[0]]
check(len(times) == STEPS + 1 and times[0] == 0.0, f"sensors.csv has {STEPS + 1} rows, the first at t = 0")
check(all(math.isfinite(v) for column in sensors.values() for v in column), "no NaN or inf in sensors.csv")
check(abs(times[-1] - STEPS * DT) < 1e-12, f"the last row is t = {STEPS * DT}")
piston = max(abs(y - (0.0725 - 0.05 * t)) for t, y in zip(times, sensors["piston_position_y"]))
check(piston < 1e-12, f"piston y = 0.0725 - 0.05 t to {piston:.1e} m (< 1e-12)")
for name in ("bottom_constraint_force_y", "piston_constraint_force_y"):
    error = max(abs(f - WEIGHT) for f in sensors[name])
    check(error < 1e-9 * WEIGHT, f"{name} = m g = {WEIGHT:.3f} N/m to {error:.1e}")
for name in ("bottom_fluid_force_y", "piston_fluid_force_y", "total_fluid_force_y"):
    check(all(f == 0.0 for f in sensors[name]), f"{name} is zero without fluid")
log = read(run_dir, "fsi-server.log")
check("multibody alone" in log, "the log says the multibody part runs alone")
check(run["model"]["integrator"] == "Radau IIA, 3 stages", f"run.json names the integrator ({run['model']['integrator']})")

# The scene's tableau is the one that runs: Lobatto IIIA asked for, Lobatto IIIA used and named.
lobatto_dir = os.path.join(output, "lobatto")
result = subprocess.run([binary("fsi-server"), example("static_tank", "static_tank_coarse.scene"), "--mbd-only",
                         "--output", lobatto_dir, "--set", "Resolution.end_time=100*1e-5",
                         "--set", 'SolverOptions.Timeint.tableau="LobattoIIIA"'],
                        env=ENV, capture_output=True, text=True, timeout=60)
if result.returncode != 0:
    fail(f"fsi-server --mbd-only with Lobatto IIIA exited {result.returncode}:\n{result.stderr[-3000:]}")
lobatto = manifest(lobatto_dir)
check(lobatto["model"]["integrator"] == "Lobatto IIIA, 3 stages",
      f"Lobatto IIIA asked for: run.json names {lobatto['model']['integrator']}")
check("(Lobatto IIIA, 3 stages)" in read(lobatto_dir, "fsi-server.log"), "the log names Lobatto IIIA")

# Bad input: a free body and one Newton iteration allowed cannot converge. The run must stop with
# exit 1, naming step and time, run.json "failed", and no NaN written.
bad_dir = os.path.join(output, "bad")
free_body_scene = static_tank_variant(bad_dir, "free_body.scene",
                                      '\nRigidBody2D { name = "stone"; mass = 1; inertia = 1; position = [0.2, 0.2] }\n')
bad_run = os.path.join(bad_dir, "run")
result = subprocess.run([binary("fsi-server"), free_body_scene, "--mbd-only",
                         "--output", bad_run, "--set", "Resolution.end_time=1e-4",
                         "--set", "SolverOptions.Newton.max_iterations=1"],
                        env=ENV, capture_output=True, text=True, timeout=60)
check(result.returncode == 1, f"Newton failure: exit 1 (got {result.returncode})")
check("step 1 (t = 0 s)" in result.stderr and "Newton iterations of Radau IIA" in result.stderr,
      "the message names the step, the time and the Newton failure")
bad = manifest(bad_run)
check(bad["status"] == "failed" and "step 1" in bad.get("reason", ""), "run.json says failed, with the step")
check("nan" not in read(bad_run, "sensors.csv").lower(), "no NaN in sensors.csv")

# Output.snapshot_every_steps in an --mbd-only run: the structure's shape for ParaView (a user saw
# it ignored without a word). The CSM3 flag, 1 s, a snapshot every 50 steps: beams.pvd and
# boundary.pvd with an entry each at t = 0, 0.25, ..., 1 s, the flag's tip in beams_*.vtp where
# sensors.csv has point A, and no fluid or bodies series (none in the scene).
import xml.etree.ElementTree as ElementTree  # noqa: E402

import vtk  # noqa: E402
from vtk.util.numpy_support import vtk_to_numpy  # noqa: E402
from fsi_test import read_vtk  # noqa: E402

vtk_run = os.path.join(output, "csm3")
result = subprocess.run([binary("fsi-server"), example("mbd_mechanisms", "turek_hron_csm3.scene"), "--mbd-only",
                         "--output", vtk_run, "--set", "SolverOptions.end_time=1",
                         "--set", "Output.snapshot_every_steps=50"],
                        env=ENV, capture_output=True, text=True, timeout=60)
if result.returncode != 0:
    fail(f"fsi-server --mbd-only of the CSM3 flag exited {result.returncode}:\n{result.stderr[-3000:]}")
vtk_dir = os.path.join(vtk_run, "vtk")
series = {}
for name in ("beams", "boundary"):
    root = ElementTree.parse(os.path.join(vtk_dir, f"{name}.pvd")).getroot()
    series[name] = [(float(item.get("timestep")), item.get("file")) for item in root.iter("DataSet")]
times = [t for t, _ in series["beams"]]
check(times == [t for t, _ in series["boundary"]] and len(times) == 5 and abs(times[-1] - 1.0) < 1e-12,
      f"vtk/beams.pvd and boundary.pvd: an entry every 50 steps ({times})")
check(not os.path.exists(os.path.join(vtk_dir, "fluid.pvd")) and not os.path.exists(os.path.join(vtk_dir, "bodies.pvd")),
      "no fluid or bodies series without fluid or rigid bodies")
csm3 = load_sensors(vtk_run)
last = read_vtk(os.path.join(vtk_dir, series["beams"][-1][1]), vtk.vtkXMLPolyDataReader)
tip = vtk_to_numpy(last.GetPoints().GetData())[-1]
check(abs(tip[0] - csm3["A_x"][-1]) < 1e-12 and abs(tip[1] - csm3["A_y"][-1]) < 1e-12,
      f"the flag's tip in the last beams file is point A of sensors.csv ({tip[:2]})")
cleanup(output)
print("mbd-only: 4 passed, 0 failed")
