#!/usr/bin/python3
"""The server's ParaView output, read back with VTK's own XML readers (Debian python3-vtk9): a short
coarse static tank with a snapshot every 250 steps. Every .pvd entry exists with the step's time;
each fluid file holds the run's N particles with ids 1..N, densities near 1000 kg/m^3 and the very
values of the CSV snapshot of the same step; the boundary file has the run's vertices, segments as
VTK_LINE, the dynamic vertices first, and fluid forces that sum to the fluid-force sensors; the
body file puts the piston where its position sensor says, with frame axes (axis_x, axis_y,
axis_z) that are the rotation by each body's angle."""
import csv
import os
import xml.etree.ElementTree as ElementTree

import numpy
import vtk
from vtk.util.numpy_support import vtk_to_numpy

from fsi_test import check, cleanup, example, fail, load_sensors, manifest, read, read_vtk, run_pair, work_dir

SNAPSHOT_EVERY = 250
STEPS = 1000
VTK_VERTEX, VTK_LINE = 1, 3

output = work_dir("vtk_output")
run_dir = os.path.join(output, "run")
server_status, client_status = run_pair(
    example("static_tank", "static_tank_coarse.scene"), run_dir, 2,
    overrides=[f"Resolution.end_time={STEPS}*1e-5", "Resolution.equilibration_steps=500",
               f"Resolution.snapshot_every_steps={SNAPSHOT_EVERY}"], timeout=120)
if server_status != 0:
    fail(f"fsi-server exited {server_status}:\n{read(run_dir, 'server.stderr')[-3000:]}")
check(client_status == 0, "fsi-client exits 0")
run = manifest(run_dir)
particle_count = run["fluid"]["particle_count"]
vertex_count = run["mesh"]["vertices"]
dynamic_count = run["mesh"]["dynamic_vertices"]
segment_count = run["mesh"]["segments"]
time_step = run["time_step"]
# The first snapshot is at t = 0: the fluid as equilibrated, before the first step.
snapshot_steps = list(range(0, STEPS + 1, SNAPSHOT_EVERY))
check(run["snapshots"] == len(snapshot_steps), f"run.json counts {len(snapshot_steps)} snapshots")
vtk_dir = os.path.join(run_dir, "vtk")


def collection(name):
    """(timestep, file) of every DataSet of vtk/NAME.pvd."""
    path = os.path.join(vtk_dir, f"{name}.pvd")
    if not os.path.exists(path):
        fail(f"{path} is missing")
    root = ElementTree.parse(path).getroot()
    check(root.tag == "VTKFile" and root.get("type") == "Collection", f"{name}.pvd is a VTK collection")
    return [(float(entry.get("timestep")), entry.get("file")) for entry in root.iter("DataSet")]


def point_array(grid, name):
    array = grid.GetPointData().GetArray(name)
    if array is None:
        fail(f"point data '{name}' missing")
    return vtk_to_numpy(array)


def time_value(grid):
    return vtk_to_numpy(grid.GetFieldData().GetArray("TimeValue"))[0]


def csv_snapshot(step):
    path = os.path.join(run_dir, "snapshots", f"particles_{step:09d}.csv")
    with open(path) as handle:
        rows = [row for row in csv.reader(line for line in handle if not line.startswith("#"))]
    header, values = rows[0], numpy.array(rows[1:], dtype=float)
    return {name: values[:, k] for k, name in enumerate(header)}


def same(a, b):
    """Equal to round-off, relative to the field's magnitude."""
    return numpy.max(numpy.abs(a - b)) <= 1e-13 * max(1.0, numpy.max(numpy.abs(b)))


sensors = load_sensors(run_dir)
sensor_time = numpy.array(sensors["time"])

for name in ("fluid", "boundary", "bodies"):
    entries = collection(name)
    check(len(entries) == len(snapshot_steps), f"{name}.pvd has {len(snapshot_steps)} entries (got {len(entries)})")
    for (timestep, _), step in zip(entries, snapshot_steps):
        if abs(timestep - step * time_step) > 1e-12:
            fail(f"{name}.pvd: timestep {timestep} for step {step}, expected {step * time_step}")

for (timestep, file_name), step in zip(collection("fluid"), snapshot_steps):
    grid = read_vtk(os.path.join(vtk_dir, file_name))
    where = f"{file_name}"
    check(grid.GetNumberOfPoints() == particle_count,
          f"{where}: {grid.GetNumberOfPoints()} points = particle_count {particle_count} of run.json")
    check(grid.GetNumberOfCells() == particle_count and
          set(vtk_to_numpy(grid.GetCellTypesArray())) == {VTK_VERTEX}, f"{where}: one VTK_VERTEX per particle")
    check(abs(time_value(grid) - timestep) < 1e-15, f"{where}: TimeValue = pvd timestep")
    ids = point_array(grid, "id")
    check(sorted(ids.tolist()) == list(range(1, particle_count + 1)), f"{where}: ids are 1..{particle_count}")
    density = point_array(grid, "density")
    check(numpy.all(numpy.abs(density / 1000.0 - 1.0) < 0.02),
          f"{where}: density within 2 % of 1000 (range {density.min():.2f}..{density.max():.2f})")
    reference = csv_snapshot(step)
    order = numpy.argsort(reference["id"])
    mine = numpy.argsort(ids)
    points = vtk_to_numpy(grid.GetPoints().GetData())[mine]
    velocity = point_array(grid, "velocity")[mine]
    check(same(ids[mine], reference["id"][order]), f"{where}: same ids as the CSV snapshot")
    check(numpy.all(points[:, 2] == 0.0) and numpy.all(velocity[:, 2] == 0.0), f"{where}: z components are 0 in 2D")
    for label, values, column in (("x", points[:, 0], "x"), ("y", points[:, 1], "y"), ("vx", velocity[:, 0], "vx"),
                                  ("vy", velocity[:, 1], "vy"), ("density", density[mine], "density"),
                                  ("pressure", point_array(grid, "pressure")[mine], "pressure")):
        if not same(values, reference[column][order]):
            fail(f"{where}: {label} differs from the CSV snapshot by "
                 f"{numpy.max(numpy.abs(values - reference[column][order])):.3e}")
    print(f"ok: {where}: x, y, vx, vy, density, pressure equal the CSV snapshot of step {step}", flush=True)

for (timestep, file_name), step in zip(collection("boundary"), snapshot_steps):
    grid = read_vtk(os.path.join(vtk_dir, file_name))
    where = f"{file_name}"
    check(grid.GetNumberOfPoints() == vertex_count, f"{where}: {vertex_count} vertices as in run.json")
    check(grid.GetNumberOfCells() == segment_count and
          set(vtk_to_numpy(grid.GetCellTypesArray())) == {VTK_LINE}, f"{where}: {segment_count} VTK_LINE segments")
    dynamic = point_array(grid, "dynamic")
    check(dynamic.tolist() == [1] * dynamic_count + [0] * (vertex_count - dynamic_count),
          f"{where}: the first {dynamic_count} vertices are dynamic, the rest static")
    velocity = point_array(grid, "velocity")
    force = point_array(grid, "fluid_force")
    check(numpy.all(velocity[dynamic == 0] == 0.0) and numpy.all(force[dynamic == 0] == 0.0),
          f"{where}: static vertices have zero velocity and (unsent) force")
    # The forces received after step n act during step n+1: the sensors of t_(n+1) sum them.
    if step < STEPS:
        row = int(numpy.argmin(numpy.abs(sensor_time - (step + 1) * time_step)))
        expected = sensors["bottom_fluid_force_y"][row] + sensors["piston_fluid_force_y"][row]
        total = float(numpy.sum(force[:, 1]))
        check(abs(total - expected) <= 1e-12 * max(1.0, abs(expected)),
              f"{where}: fluid forces sum to {total:.6f} N/m = the bodies' fluid-force sensors at the next step")
    check(numpy.any(numpy.abs(velocity[:, 1] + 0.05) < 1e-12), f"{where}: piston vertices move at -0.05 m/s")

for (timestep, file_name), step in zip(collection("bodies"), snapshot_steps):
    grid = read_vtk(os.path.join(vtk_dir, file_name), vtk.vtkXMLPolyDataReader)
    names = grid.GetFieldData().GetAbstractArray("body_name")
    body_names = [names.GetValue(k) for k in range(names.GetNumberOfValues())]
    check(body_names == [body["name"] for body in run["model"]["bodies"]], f"{file_name}: body names {body_names}")
    piston = body_names.index("piston")
    row = int(numpy.argmin(numpy.abs(sensor_time - step * time_step)))
    y = vtk_to_numpy(grid.GetPoints().GetData())[piston, 1]
    check(abs(y - sensors["piston_position_y"][row]) <= 1e-15,
          f"{file_name}: piston at y = {y:.9f} m as its position sensor")
    angle = point_array(grid, "angle")
    axis_x, axis_y, axis_z = (point_array(grid, name) for name in ("axis_x", "axis_y", "axis_z"))
    expected_x = numpy.column_stack([numpy.cos(angle), numpy.sin(angle), numpy.zeros_like(angle)])
    expected_y = numpy.column_stack([-numpy.sin(angle), numpy.cos(angle), numpy.zeros_like(angle)])
    check(axis_x.shape == (len(body_names), 3) and numpy.max(numpy.abs(axis_x - expected_x)) <= 1e-15 and
          numpy.max(numpy.abs(axis_y - expected_y)) <= 1e-15 and numpy.all(axis_z == [0.0, 0.0, 1.0]),
          f"{file_name}: frame axes axis_x, axis_y, axis_z are the rotation by each body's angle {angle.tolist()}")
    # Both bodies have their angle held by a constraint: their frames stay aligned with x and y.
    check(numpy.max(numpy.abs(axis_x - [1.0, 0.0, 0.0])) <= 1e-12,
          f"{file_name}: bottom and piston (angle held at 0) keep axis_x = (1, 0, 0)")

output_share = run["timings_seconds"]["output"] / run["timings_seconds"]["total"]
print(f"output time: {run['timings_seconds']['output']:.3f} s of {run['timings_seconds']['total']:.3f} s "
      f"({100 * output_share:.1f} %) with a snapshot every {SNAPSHOT_EVERY} steps")
cleanup(output)
