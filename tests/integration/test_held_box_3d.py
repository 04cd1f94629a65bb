#!/usr/bin/python3
"""The 3D hydrostatic box with a container that is a body (examples/hydrostatic_box_3d/
hydrostatic_box_3d_held.scene) as a real co-simulation, fsi-run with 2 ranks: box.stl carried
by a RigidBody3D and held by a FixedJoint3D. The fluid forces act on the body's 8 dynamic
vertices; at every sensor row the joint's force from the Lagrange multipliers balances the
body's weight plus the fluid force on it (the 3D form of the thesis' §6.3 check, to 1e-9 of the
fluid weight), the fluid force on the body is the total fluid force (every vertex is the body's),
the settled fluid force is the fluid weight within 3 %, the held body does not move, and
--mbd-only runs the same scene without a fluid (joint force = body weight)."""
import os
import subprocess

import numpy

from fsi_test import binary, check, example, manifest, work_dir, ENV

output = work_dir("held_box_3d")
run_dir = os.path.join(output, "run")
scene = example("hydrostatic_box_3d", "hydrostatic_box_3d_held.scene")
result = subprocess.run([binary("fsi-run"), scene, "--np", "2", "--output", run_dir], env=ENV,
                        capture_output=True, text=True, timeout=600)
print(result.stderr[-3000:])
check(result.returncode == 0, f"fsi-run exits 0 (got {result.returncode})")
run = manifest(run_dir)
check(run["status"] == "completed" and run["dimension"] == 3, "run.json: completed, dimension 3")
check(run["mesh"]["dynamic_vertices"] == 8 and run["mesh"]["vertices"] == 8 and
      run["mesh"]["triangles"] == 12, f"run.json: the body's 8 dynamic vertices, 12 triangles: {run['mesh']}")
bodies = run["model"]["bodies"]
check(len(bodies) == 1 and bodies[0]["type"] == "rigid_body_3d", f"run.json: one rigid_body_3d: {bodies}")
container_mass = bodies[0]["mass"]
checks = run["checks"]
check(checks["particles_final"] == checks["particles_initial"] > 500, "no particle lost")
check(checks["max_action_reaction_relative"] <= 1e-12,
      f"action = reaction: {checks['max_action_reaction_relative']:.3e}")

rows = [line for line in open(os.path.join(run_dir, "sensors.csv")) if not line.startswith("#")]
header = rows[0].strip().split(",")
data = numpy.array([[float(v) for v in row.split(",")] for row in rows[1:]])
column = {name: data[:, header.index(name)] for name in header}
params = run["parameters_flat"]
particle_mass = params["LIGGGHTS_SPH_parameters.SPHdensity"] * params["LIGGGHTS_SPH_parameters.particlespacing"] ** 3
fluid_weight = checks["particles_final"] * particle_mass * 9.81
# The joint force on the body balances its weight (-m g along z) and the fluid's force on it.
residual = column["mount_force_z"] - container_mass * 9.81 + column["fluid_force_z"]
worst = numpy.abs(residual).max() / fluid_weight
print(f"measured: |joint force - m g + fluid force| <= {worst:.2e} of the fluid weight over "
      f"{len(residual)} rows", flush=True)
check(worst <= 1e-9, f"joint force (lambda) = body weight + fluid force at every row: {worst:.2e} <= 1e-9")
same = numpy.abs(column["fluid_force_z"] - column["total_fluid_force_z"]).max() / fluid_weight
check(same <= 1e-12, f"fluid force on the body = total fluid force: {same:.2e}")
settled = column["time"] >= 0.5 * run["end_time"]
ratio = -column["fluid_force_z"][settled].mean() / fluid_weight
print(f"measured: settled fluid force on the body / fluid weight = {ratio:.4f}", flush=True)
check(abs(ratio - 1) <= 0.03, f"fluid force = fluid weight within 3 %: {ratio:.4f}")
drift = numpy.abs(column["container_z"] - 0.01).max()
check(drift <= 1e-12, f"the held container stays at z = 0.01 m: {drift:.2e}")

# Without a fluid: the joint carries the body's weight alone.
alone_dir = os.path.join(output, "alone")
result = subprocess.run([binary("fsi-server"), "--mbd-only", scene, "--output", alone_dir,
                         "--set", "SolverOptions.end_time=0.0025"], env=ENV, capture_output=True,
                        text=True, timeout=120)
print(result.stderr[-2000:])
check(result.returncode == 0, f"--mbd-only exits 0 (got {result.returncode})")
rows = [line for line in open(os.path.join(alone_dir, "sensors.csv")) if not line.startswith("#")]
header = rows[0].strip().split(",")
alone = numpy.array([[float(v) for v in row.split(",")] for row in rows[1:]])
mount = alone[:, header.index("mount_force_z")]
check(numpy.abs(mount - container_mass * 9.81).max() <= 1e-9 * container_mass * 9.81,
      f"--mbd-only: joint force = m g = {container_mass * 9.81:.6g} N (max {mount.max():.9g})")
print("PASS")
