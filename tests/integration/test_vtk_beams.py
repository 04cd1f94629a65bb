#!/usr/bin/python3
"""ANCF beams in the server's ParaView output, read back with VTK's own readers: the coarse static
tank plus a cantilever clamped to the left wall above the fluid, sagging under gravity in a short
coupled run. vtk/beams.pvd has an entry per particle snapshot at the fluid's times; each file is
one polyline of 8 segments per element named after the beam, starting exactly at the clamp with
zero velocity there; and the beam's face mesh in vtk/boundary.pvd lies half a thickness from that
centre line (the faces and the line are drawn from the same beam coordinates)."""
import os
import xml.etree.ElementTree as ElementTree

import numpy
import vtk
from vtk.util.numpy_support import vtk_to_numpy

from fsi_test import check, cleanup, fail, manifest, read, read_vtk, run_pair, static_tank_variant, work_dir

ELEMENTS, SAMPLES, THICKNESS, FACE_POINTS = 4, 8, 0.002, 4
START, LENGTH = (0.0, 0.08), 0.03
output = work_dir("vtk_beams")
scene = static_tank_variant(os.path.join(output, "scene"), "beam.scene", f"""
AncfBeam2D {{ name = "cantilever"; start = [{START[0]}, {START[1]}]; end = [{START[0] + LENGTH}, {START[1]}]
             elements = {ELEMENTS}; thickness = {THICKNESS}; face_points_per_element = {FACE_POINTS}
             axial_stiffness = 1e5; bending_stiffness = 0.01; mass_per_length = 2 }}
BeamClamp {{ beam = "cantilever" }}
""")
run_dir = os.path.join(output, "run")
server_status, client_status = run_pair(scene, run_dir, 2,
                                        overrides=["Resolution.end_time=600*1e-5", "Resolution.equilibration_steps=200",
                                                   "Resolution.snapshot_every_steps=200"], timeout=180)
if server_status != 0:
    fail(f"fsi-server exited {server_status}:\n{read(run_dir, 'server.stderr')[-3000:]}")
check(client_status == 0, "fsi-client exits 0")
vtk_dir = os.path.join(run_dir, "vtk")


def entries(name):
    root = ElementTree.parse(os.path.join(vtk_dir, f"{name}.pvd")).getroot()
    return [(float(item.get("timestep")), os.path.join(vtk_dir, item.get("file"))) for item in root.iter("DataSet")]


beams, boundaries = entries("beams"), entries("boundary")
check(len(beams) == manifest(run_dir)["snapshots"] == 4 and [t for t, _ in beams] == [t for t, _ in boundaries],
      f"beams.pvd has an entry per snapshot at the boundary's times ({[t for t, _ in beams]})")
sag = []
for (time, beam_file), (_, boundary_file) in zip(beams, boundaries):
    lines = read_vtk(beam_file, vtk.vtkXMLPolyDataReader)
    points = vtk_to_numpy(lines.GetPoints().GetData())[:, :2]
    velocities = vtk_to_numpy(lines.GetPointData().GetArray("velocity"))
    name = lines.GetFieldData().GetAbstractArray("line_name")
    check(lines.GetNumberOfLines() == 1 and len(points) == ELEMENTS * SAMPLES + 1,
          f"t = {time:.4f}: one polyline of {ELEMENTS * SAMPLES + 1} points ({lines.GetNumberOfLines()}, {len(points)})")
    check(name is not None and name.GetValue(0) == "cantilever", "the line is named after the beam")
    check(numpy.abs(points[0] - START).max() < 1e-12 and numpy.abs(velocities[0]).max() < 1e-12,
          f"it starts at the clamp {START} at rest ({points[0]}, {velocities[0][:2]})")
    length = numpy.hypot(*numpy.diff(points, axis=0).T).sum()
    check(abs(length / LENGTH - 1) < 1e-3, f"its length is the beam's to {abs(length / LENGTH - 1):.1e}")
    sag.append(START[1] - points[-1][1])
    # The beam's face vertices in boundary.vtu: the dynamic ones above the piston (top at y <= 0.075).
    grid = read_vtk(boundary_file, vtk.vtkXMLUnstructuredGridReader)
    dynamic = vtk_to_numpy(grid.GetPointData().GetArray("dynamic")).astype(bool)
    vertices = vtk_to_numpy(grid.GetPoints().GetData())[:, :2]
    faces = vertices[dynamic & (vertices[:, 1] > 0.077)]
    check(len(faces) == 2 * (ELEMENTS * FACE_POINTS + 1),
          f"the mesh has both faces' {2 * (ELEMENTS * FACE_POINTS + 1)} vertices ({len(faces)})")
    a, b = points[:-1], points[1:]
    worst = 0.0
    for p in faces:
        t = numpy.clip(numpy.einsum("ij,ij->i", p - a, b - a) / numpy.einsum("ij,ij->i", b - a, b - a), 0, 1)
        distance = numpy.hypot(*(a + t[:, None] * (b - a) - p).T).min()
        worst = max(worst, abs(distance - THICKNESS / 2))
    check(worst < 1e-3 * THICKNESS, f"the face vertices lie thickness/2 from the centre line to {worst:.1e} m")
# The first frame is t = 0, the beam as given (straight).
check(abs(sag[0]) < 1e-12 and sag[1] > 0 and sag[-1] > sag[1],
      f"the tip sags under gravity from straight at t = 0: {', '.join(f'{s:.2e}' for s in sag)} m")
cleanup(output)
