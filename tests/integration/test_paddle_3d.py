#!/usr/bin/python3
"""A moving 3D body in the fluid (examples/hydrostatic_box_3d/hydrostatic_box_3d_paddle.scene):
a RigidBody3D paddle on a RevoluteJoint3D swings from 25 degrees into the water of the box, fsi-run
with 2 ranks, 0.06 s. Its 8 mesh vertices move with every step. Against the same paddle in air
(fsi-server --mbd-only: it swings through under the hinge and keeps its energy to 1e-6), the
fluid holds it back: it does not pass under the hinge, loses energy, and the fluid's force on it
opposes the motion. No particle is lost, action = reaction at every exchange, and the VTK boundary
frames show the vertices moved."""
import os
import subprocess
import xml.etree.ElementTree as ElementTree

import numpy
import vtk
from vtk.util.numpy_support import vtk_to_numpy

from fsi_test import binary, check, example, manifest, work_dir, ENV

output = work_dir("paddle_3d")
scene = example("hydrostatic_box_3d", "hydrostatic_box_3d_paddle.scene")
end = ["--set", "SolverOptions.end_time=0.06", "--set", "Output.snapshot_every_steps=600"]


def sensors(run_dir):
    rows = [line for line in open(os.path.join(run_dir, "sensors.csv")) if not line.startswith("#")]
    header = rows[0].strip().split(",")
    data = numpy.array([[float(v) for v in row.split(",")] for row in rows[1:]])
    return {name: data[:, header.index(name)] for name in header}


air_dir = os.path.join(output, "air")
result = subprocess.run([binary("fsi-server"), "--mbd-only", scene, "--output", air_dir] + end,
                        env=ENV, capture_output=True, text=True, timeout=120)
if result.returncode != 0:
    print(result.stderr[-2000:])
check(result.returncode == 0, f"--mbd-only exits 0 (got {result.returncode})")
air = sensors(air_dir)
hinge_x = 0.006
air_energy = air["kinetic"] + air["potential"]
air_drift = numpy.abs(air_energy - air_energy[0]).max() / abs(air_energy[0])
print(f"measured: in air the tip reaches x = {air['tip_x'].min():.5f} m (hinge at {hinge_x}), "
      f"energy drift {air_drift:.2e}", flush=True)
check(air["tip_x"].min() < hinge_x - 0.002, "in air the paddle swings through under the hinge")
check(air_drift <= 1e-6, f"in air the energy is kept: {air_drift:.2e} <= 1e-6")

run_dir = os.path.join(output, "fluid")
result = subprocess.run([binary("fsi-run"), scene, "--np", "2", "--output", run_dir] + end,
                        env=ENV, capture_output=True, text=True, timeout=600)
print(result.stderr[-3000:])
check(result.returncode == 0, f"fsi-run exits 0 (got {result.returncode})")
run = manifest(run_dir)
check(run["status"] == "completed", "run.json: completed")
check(run["mesh"]["dynamic_vertices"] == 8 and run["mesh"]["vertices"] == 16,
      f"run.json: 8 dynamic (paddle) and 8 static (box) vertices: {run['mesh']}")
checks = run["checks"]
check(checks["particles_final"] == checks["particles_initial"], "no particle lost")
check(checks["max_action_reaction_relative"] <= 1e-12,
      f"action = reaction at every exchange: {checks['max_action_reaction_relative']:.3e}")
fluid = sensors(run_dir)
energy = fluid["kinetic"] + fluid["potential"]
loss = (energy[0] - energy[-1]) / abs(energy[0])
moving = fluid["time"] > 0.005
print(f"measured: in the fluid the tip reaches x = {fluid['tip_x'].min():.5f} m, the paddle loses "
      f"{100 * loss:.2f} % of its energy, mean fluid force on it along x "
      f"{fluid['paddle_fluid_x'][moving].mean():.3e} N; closest particle "
      f"{checks['closest_approach_over_r0']:.2e} r0", flush=True)
check(fluid["tip_x"].min() > hinge_x, "the fluid holds the paddle back: it does not pass under the hinge")
check(fluid["tip_x"][-1] < fluid["tip_x"][0] - 0.001, "but it moves (the tip by more than 1 mm)")
check(loss > 0.005, f"the paddle loses energy to the fluid: {100 * loss:.2f} % > 0.5 %")
check(fluid["paddle_fluid_x"][moving].mean() > 0.0, "the fluid's force opposes the motion (-x)")

# The boundary frames: the dynamic vertices move, the static ones do not.
vtk_dir = os.path.join(run_dir, "vtk")
entries = list(ElementTree.parse(os.path.join(vtk_dir, "boundary.pvd")).getroot().iter("DataSet"))
check(len(entries) >= 2, f"boundary.pvd holds {len(entries)} frames")


def points(entry):
    reader = vtk.vtkXMLUnstructuredGridReader()
    reader.SetFileName(os.path.join(vtk_dir, entry.get("file")))
    reader.Update()
    return vtk_to_numpy(reader.GetOutput().GetPoints().GetData())


first, last = points(entries[0]), points(entries[-1])
check(numpy.abs(last[:8] - first[:8]).max() > 1e-4, "boundary VTK: the paddle's vertices moved")
check(numpy.abs(last[8:] - first[8:]).max() == 0.0, "boundary VTK: the box's vertices did not")
print("PASS")
