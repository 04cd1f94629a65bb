#!/usr/bin/python3
"""The 3D hydrostatic box (examples/hydrostatic_box_3d) as a real co-simulation, fsi-run with 2
ranks: a dimension = 3 scene whose structure is a static ground STL box. The fluid force on the
container along z, averaged over the settled second half of the coupled phase, equals the weight
N rho0 d^3 g within 3 % (the mass from the scene's own parameters, not from the server's report);
no particle is lost; action = reaction at every exchange; run.json counts triangles; the VTK
files hold 3D particles and the 12 triangles and read back with VTK; fsi-plot renders 3D frames
headless (a view and a section: PNGs of the figure's size whose plot area holds the coloured
particles; a section above the water holds none, the check's control). The same fluid block given
as a closed STL surface (hydrostatic_box_3d_stl.scene) runs too (briefly): the same particles."""
import os
import subprocess
import time
import xml.etree.ElementTree as ElementTree

import numpy
import vtk
from vtk.util.numpy_support import vtk_to_numpy

from fsi_test import binary, check, cleanup, example, manifest, read_vtk, work_dir, ENV

output = work_dir("hydrostatic_box_3d")
run_dir = os.path.join(output, "run")
started = time.monotonic()
result = subprocess.run([binary("fsi-run"), example("hydrostatic_box_3d", "hydrostatic_box_3d.scene"),
                         "--np", "2", "--output", run_dir], env=ENV, capture_output=True, text=True,
                        timeout=600)
wall = time.monotonic() - started
print(result.stderr[-4000:])
check(result.returncode == 0, f"fsi-run exits 0 (got {result.returncode})")
run = manifest(run_dir)
check(run["status"] == "completed", "run.json says completed")
check(run["dimension"] == 3, "run.json: dimension 3")
steps = round(run["end_time"] / run["time_step"])
check(run["steps"] == steps, f"{steps} coupled steps (got {run['steps']})")
check(run["mesh"] == {"vertices": 8, "dynamic_vertices": 0, "triangles": 12,
                      "refinement_resolution": run["mesh"]["refinement_resolution"]},
      f"run.json counts the box's 8 static vertices and 12 triangles: {run['mesh']}")
# The physics checks run in 3D; the two warnings are the example's deliberate 10x wall friction
# (README.md), against the declared nu and against the fluid's alpha; the 2D-only checks are
# skipped, not mis-reported.
warnings = run.get("warnings", [])
check(len(warnings) == 2 and any("wall_viscosity" in w for w in warnings)
      and any("viscosity_match" in w for w in warnings), f"run.json lists the scene's warnings: {warnings}")
checks = run["checks"]
check(checks["particles_initial"] == run["fluid"]["generated_particles"] > 500,
      f"LIGGGHTS holds the {run['fluid']['generated_particles']} generated particles")
check(checks["particles_final"] == checks["particles_initial"], "no particle lost")
check(checks["max_action_reaction_relative"] <= 1e-12,
      f"action = reaction at every exchange: max {checks['max_action_reaction_relative']:.3e} <= 1e-12")
# The particle mass from the scene's definition (rho0 d^3), independent of what the server sent.
params = run["parameters_flat"]
rho0 = params["LIGGGHTS_SPH_parameters.SPHdensity"]
d = params["LIGGGHTS_SPH_parameters.particlespacing"]
mass = rho0 * d ** 3
check(abs(run["fluid"]["particle_mass"] / mass - 1) < 1e-12,
      f"particle mass {run['fluid']['particle_mass']:.6g} kg = rho0 d^3 = {mass:.6g} kg")
check(run["model"]["gravity"] == [0, 0, -9.81], f"gravity (0, 0, -9.81): {run['model']['gravity']}")

rows = [line for line in open(os.path.join(run_dir, "sensors.csv")) if not line.startswith("#")]
header = rows[0].strip().split(",")
data = numpy.array([[float(v) for v in row.split(",")] for row in rows[1:]])
t = data[:, header.index("time")]
fz = data[:, header.index("total_fluid_force_z")]
fx = data[:, header.index("total_fluid_force_x")]
settled = t >= 0.5 * run["end_time"]
weight = checks["particles_final"] * mass * 9.81
ratio = -fz[settled].mean() / weight
print(f"measured: weight ratio -F_z/(N rho0 d^3 g) = {ratio:.4f} (N = {checks['particles_final']}, "
      f"W = {weight:.6g} N, {settled.sum()} samples); |F_x|/W = {abs(fx[settled].mean()) / weight:.2e}; "
      f"fsi-run wall time {wall:.1f} s", flush=True)
check(abs(ratio - 1) <= 0.03, f"fluid force on the container along z = weight within 3 %: ratio {ratio:.4f}")
check(abs(fx[settled].mean()) <= 0.03 * weight, "no net horizontal force (x) at rest")

analysis = subprocess.run(["/usr/bin/python3", example("hydrostatic_box_3d", "analyze.py"), run_dir,
                           "--weight-tolerance", "0.03"], capture_output=True, text=True)
print(analysis.stdout, analysis.stderr)
check(analysis.returncode == 0, "analyze.py: weight within 3 %, no particle lost")


def last_file(name):
    """The last DataSet of vtk/NAME.pvd."""
    entries = list(ElementTree.parse(os.path.join(vtk_dir, f"{name}.pvd")).getroot().iter("DataSet"))
    check(len(entries) == run["snapshots"] > 0, f"{name}.pvd lists the {run['snapshots']} snapshots")
    return os.path.join(vtk_dir, entries[-1].get("file"))


vtk_dir = os.path.join(run_dir, "vtk")
fluid = read_vtk(last_file("fluid"))
check(fluid.GetNumberOfPoints() == checks["particles_final"], "fluid VTK: one point per particle")
points = vtk_to_numpy(fluid.GetPoints().GetData())
check(points[:, 2].min() > 0.0 and points[:, 2].max() < 0.02 and numpy.ptp(points[:, 2]) > 0.005,
      f"fluid VTK: 3D positions inside the box (z {points[:, 2].min():.4f}-{points[:, 2].max():.4f} m)")
boundary = read_vtk(last_file("boundary"))
check(boundary.GetNumberOfPoints() == 8 and boundary.GetNumberOfCells() == 12,
      f"boundary VTK: 8 points, 12 cells (got {boundary.GetNumberOfPoints()}, {boundary.GetNumberOfCells()})")
check(all(boundary.GetCellType(c) == vtk.VTK_TRIANGLE for c in range(12)), "boundary VTK: triangles")
corners = vtk_to_numpy(boundary.GetPoints().GetData())
check(numpy.allclose(corners.max(axis=0), [0.012, 0.012, 0.02]) and numpy.allclose(corners.min(axis=0), 0), "boundary VTK: the box's corners")


def coloured_pixels(path):
    """(width, height, pixels of a colour map's hue in the left 70 % of the image): the plot area
    without the colour bar; axes, panes, text and the box's static mesh are grey."""
    reader = vtk.vtkPNGReader()
    reader.SetFileName(path)
    reader.Update()
    image = reader.GetOutput()
    width, height, _ = image.GetDimensions()
    pixels = vtk_to_numpy(image.GetPointData().GetScalars()).reshape(height, width, -1)[:, :, :3].astype(int)
    left = pixels[:, : int(0.7 * width)]
    return width, height, int(((left.max(axis=2) - left.min(axis=2)) > 60).sum())


# 3D frames from fsi-plot, headless (matplotlib's Agg renderer): the view and a section.
last_step = max(int(name[len("particles_"):-len(".csv")]) for name in os.listdir(os.path.join(run_dir, "snapshots")))
for name, extra, size, least in (("view", [], (770, 660), 500), ("section", ["--cut", "y=0.006"], (660, 660), 500),
                                 ("dry section", ["--cut", "z=0.019"], (660, 660), None)):
    plots = os.path.join(output, "plots_" + name.replace(" ", "_"))
    result = subprocess.run([binary("fsi-plot"), run_dir, "--frames", "1", "--output", plots, *extra],
                            capture_output=True, text=True, timeout=300)
    check(result.returncode == 0, f"fsi-plot {name} exits 0 (got {result.returncode}: {result.stderr[-500:]})")
    frame = os.path.join(plots, "frames", f"frame_{last_step:09d}.png")
    check(os.path.exists(frame), f"fsi-plot {name}: {os.path.basename(frame)} written")
    width, height, coloured = coloured_pixels(frame)
    check((width, height) == size, f"fsi-plot {name}: {width} x {height} pixels (expected {size[0]} x {size[1]})")
    if least is not None:
        check(coloured >= least, f"fsi-plot {name}: {coloured} pixels of coloured particles (at least {least})")
    else:
        check(coloured < 50, f"fsi-plot {name}: no particle there, {coloured} coloured pixels (fewer than 50)")

# The fluid from a closed STL surface (FluidRegion shape "stl") end to end, short (its lattice is
# the box's, tested in scene_unit_tests): it runs, LIGGGHTS holds the same particles, none is lost.
stl_dir = os.path.join(output, "stl")
result = subprocess.run([binary("fsi-run"), example("hydrostatic_box_3d", "hydrostatic_box_3d_stl.scene"),
                         "--np", "2", "--output", stl_dir, "--set", "LIGGGHTS.equilibration_steps=200",
                         "--set", "SolverOptions.end_time=0.0025"], env=ENV, capture_output=True, text=True,
                        timeout=600)
print(result.stderr[-2000:])
check(result.returncode == 0, f"STL fluid: fsi-run exits 0 (got {result.returncode})")
stl_run = manifest(stl_dir)
check(stl_run["status"] == "completed" and stl_run["steps"] == 100, "STL fluid: 100 steps completed")
check(stl_run["fluid"]["generated_particles"] == run["fluid"]["generated_particles"],
      f"STL fluid: the surface fill gives the box's {run['fluid']['generated_particles']} particles")
check(stl_run["checks"]["particles_initial"] == stl_run["checks"]["particles_final"] ==
      run["fluid"]["generated_particles"], "STL fluid: LIGGGHTS holds them all, none lost")
cleanup(output)
