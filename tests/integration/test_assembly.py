#!/usr/bin/python3
"""The scene's Assembly block end to end: `fsi-server --mbd-only` on a parallelogram four-bar
whose coupler and rocker are written turned by 1e-3 rad. Without the block the scene is refused
(the joints do not close); with it the run completes, the log and `--check` say how far each body
moved, the driving crank starts where it was written (its angle sensor's first row), and a rocker
too short to reach is refused at the block's line naming the open joint."""
import os
import subprocess

from fsi_test import ENV, binary, check, cleanup, fail, load_sensors, manifest, read, work_dir

FOUR_BAR = """scene_language = 1
SolverOptions {{ end_time = 0.1; Timeint {{ step_size = 1e-3 }} }}
{assembly}
Gravity {{ acceleration = [0, -9.81] }}
RigidBody2D {{ name = "crank"; mass = 1; inertia = 0.02; position = [0, 0.25]; angular_velocity = 0.4
              velocity = [-0.1, 0]; Mesh {{ points = [[0, -0.25], [0, 0.25]] }} }}
RigidBody2D {{ name = "coupler"; mass = 2; inertia = 0.17; position = [0.5, 0.5]; angle = 1e-3 }}
RigidBody2D {{ name = "rocker"; mass = 1; inertia = 0.02; position = [1, {half}]; angle = -1e-3 }}
RevoluteJoint {{ name = "O1"; body_a = "crank"; point_a = [0, -0.25]; point_b = [0, 0] }}
RevoluteJoint {{ name = "A"; body_a = "crank"; point_a = [0, 0.25]; body_b = "coupler"; point_b = [-0.5, 0] }}
RevoluteJoint {{ name = "B"; body_a = "coupler"; point_a = [0.5, 0]; body_b = "rocker"; point_b = [0, {half}] }}
RevoluteJoint {{ name = "O2"; body_a = "rocker"; point_a = [0, -{half}]; point_b = [1, 0] }}
Sensor {{ name = "crank_angle"; type = "position"; body = "crank"; component = "angle" }}
Sensor {{ name = "rocker_angle"; type = "position"; body = "rocker"; component = "angle" }}
LIGGGHTS {{ script1 = "s.in"; script2 = "s.in" }}
Coupling {{ refinement_resolution = 0.002 }}
"""

output = work_dir("assembly")
with open(os.path.join(output, "s.in"), "w") as handle:
    handle.write("# placeholder: the multibody part runs alone\n")


def scene(name, assembly, rocker=0.5):
    path = os.path.join(output, name)
    with open(path, "w") as handle:
        handle.write(FOUR_BAR.format(assembly=assembly, half=rocker / 2))
    return path


def server(*arguments):
    return subprocess.run([binary("fsi-server"), *arguments], env=ENV, capture_output=True,
                          text=True, timeout=120)


result = server(scene("plain.scene", ""), "--check")
check(result.returncode != 0 and "inconsistent with the constraints" in result.stderr + result.stdout,
      "without Assembly the turned links are refused")

assembled = scene("assembled.scene", 'Assembly { driving = "crank.angle" }')
result = server(assembled, "--check")
if result.returncode != 0:
    fail(f"--check refuses the scene with Assembly:\n{result.stderr[-2000:]}")
check("body 'coupler': position by 0.001 (coordinate angle)" in result.stdout,
      "--check says the coupler moved by 1e-3 rad")

run_dir = os.path.join(output, "run")
result = server(assembled, "--mbd-only", "--output", run_dir)
if result.returncode != 0:
    fail(f"fsi-server --mbd-only exited {result.returncode}:\n{result.stderr[-3000:]}")
check(manifest(run_dir)["status"] == "completed", "the assembled four-bar runs to its end")
log = read(run_dir, "fsi-server.log")
check("initial assembly:" in log and "body 'rocker': position by 0.001" in log,
      "the log says how far each body moved")
sensors = load_sensors(run_dir)
# A parallelogram keeps the rocker parallel to the crank: true only if the assembly closed it on
# the crank's angle (the rocker was written 1e-3 rad off).
parallel = max(abs(c - r) for c, r in zip(sensors["crank_angle"], sensors["rocker_angle"]))
check(parallel < 1e-9, f"rocker angle = crank angle in every row (to {parallel:.1e} rad)")
check(abs(sensors["crank_angle"][-1]) > 0.01, "the mechanism moves")

result = server(scene("open.scene", '\nAssembly { driving = "crank.angle" }', rocker=0.05), "--check")
message = result.stderr + result.stdout
if result.returncode == 0:
    fail("a rocker too short to reach was accepted")
print(message)
check("open.scene:4:1" in message and "revolute joint 'B'" in message, "refused at the block, naming joint B")
# Crank held upright: B must lie 1 m from A = (0, 0.5), 1.118 m from O2; 1 + 0.05 m leave 0.0680 m.
check("the loop misses by 0.068033988" in message, "the miss is |A O2| - coupler - rocker = 0.0680340 m")
cleanup(output)
