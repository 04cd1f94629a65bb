#!/usr/bin/python3
"""The distributed boundary (thesis §7.1; docs/user-guide.md, "Ranks and balance"): on 2 ranks
each rank holds only its share of the mesh plus a halo, and the forces are those of 1 rank to the
summation order.

The 3D paddle of examples/hydrostatic_box_3d in a trough four times as long as that box (48 x 8 x
20 mm, its faces cut into 16 x 16 squares: 3 072 static triangles; 2 208 particles) with the
paddle's faces as 4 x 4 squares (192 moving triangles) hinged over the middle, where the ranks'
cut falls, and released from 60 degrees: it swings into the water and moves more than half the
margin, so the shares are chosen again during the run. -np 1 and -np 2, 0.02 s after the
settling:

- both complete and lose no particle;
- on 2 ranks neither rank ever holds the whole mesh (its half of the trough, the paddle and a
  halo of the wall's range plus twice the margin), and the shares were chosen again as the paddle
  moved;
- every sensor (the fluid forces on the paddle, the paddle's motion, the total fluid force) agrees
  between 1 and 2 ranks to 1e-9 of its scale (summation order only; measured at most 2.7e-11),
  the hinge torque to 1e-6 (a Lagrange multiplier, as exact as the structure's Newton iteration).
"""
import os
import re
import shutil
import subprocess
import sys

from fsi_test import check, cleanup, example, fail, fsi_run_checked, load_sensors, work_dir

LENGTH, WIDTH, HEIGHT = 0.048, 0.008, 0.02
SCENE = f"""scene_language = 1
include "hydrostatic_box_3d_model.inc"

Ground {{ Mesh {{ stl = "trough.stl" }} }}

FluidHealth {{ min_wall_distance = 0 }}

Paddle
{{
  mass = 2.4e-4
  length = 0.012
  angle = 60*pi/180
  hinge_x = {LENGTH / 2}
  hinge_y = {WIDTH / 2}
  hinge_z = 0.0199
}}

RigidBody3D
{{
  name = "paddle"
  mass = Paddle.mass
  inertia = [Paddle.mass*(0.001^2 + 0.012^2)/12, Paddle.mass*(0.008^2 + 0.012^2)/12,
             Paddle.mass*(0.008^2 + 0.001^2)/12]
  position = [Paddle.hinge_x + 0.5*Paddle.length*sin(Paddle.angle), Paddle.hinge_y,
              Paddle.hinge_z - 0.5*Paddle.length*cos(Paddle.angle)]
  axis = [0, 1, 0]
  angle = -Paddle.angle
  Mesh {{ stl = "paddle.stl" }}
}}

RevoluteJoint3D
{{
  name = "hinge"
  body_a = "paddle"
  point_a = [0, 0, 0.5*Paddle.length]
  point_b = [Paddle.hinge_x, Paddle.hinge_y, Paddle.hinge_z]
  axis = [0, 1, 0]
}}

Sensor {{ name = "tip_x"; type = "position"; body = "paddle"; point = [0, 0, -0.006]; component = "x" }}
Sensor {{ name = "tip_z"; type = "position"; body = "paddle"; point = [0, 0, -0.006]; component = "z" }}
Sensor {{ name = "paddle_fluid_x"; type = "fluid_force"; body = "paddle"; component = "x" }}
Sensor {{ name = "paddle_fluid_z"; type = "fluid_force"; body = "paddle"; component = "z" }}
Sensor {{ name = "hinge_torque_y"; type = "joint_force"; joint = "hinge"; component = "torque_y" }}

FluidRegion
{{
  shape = "box"
  lower = [LIGGGHTS_SPH_parameters.smoothinglength, LIGGGHTS_SPH_parameters.smoothinglength, 0.0008]
  upper = [{LENGTH} - LIGGGHTS_SPH_parameters.smoothinglength, {WIDTH} - LIGGGHTS_SPH_parameters.smoothinglength,
           0.0008 + Geometry.fill_height]
  spacing = LIGGGHTS_SPH_parameters.particlespacing
  density = LIGGGHTS_SPH_parameters.SPHdensity
}}
"""

output = work_dir("distributed_boundary")
case = os.path.join(output, "case")
shutil.copytree(os.path.dirname(example("hydrostatic_box_3d", "hydrostatic_box_3d_paddle.scene")), case,
                ignore=shutil.ignore_patterns("__pycache__"))
maker = os.path.join(case, "make_box_stl.py")
for name, arguments in (("trough.stl", ["--subdivide", "16", str(LENGTH), str(WIDTH), str(HEIGHT)]),
                        ("paddle.stl", ["--subdivide", "4", "0.008", "0.001", "0.012", "-0.004", "-0.0005",
                                        "-0.006"])):
    with open(os.path.join(case, name), "w") as handle:
        subprocess.run([sys.executable, maker] + arguments, stdout=handle, check=True)
scene = os.path.join(case, "trough_paddle.scene")
with open(scene, "w") as handle:
    handle.write(SCENE)
settings = ["SolverOptions.end_time=0.02", "Output.snapshot_every_steps=0", "LIGGGHTS.equilibration_steps=600",
            f"LIGGGHTS_SPH_parameters.xmax={LENGTH + 0.004}", f"LIGGGHTS_SPH_parameters.ymax={WIDTH + 0.004}"]


def shares(log):
    """(held per rank at the end, most held per rank, whole, selections during the coupled steps)."""
    match = re.search(r"boundary mesh: ([\d /]+) of (\d+) elements held per rank at the end \(at most "
                      r"([\d /]+); vertices [\d /]+ of \d+\), \d+ selection\(s\) of the shares, (\d+) of them "
                      r"during the coupled steps", log)
    if not match:
        fail(f"no 'boundary mesh' line in the client's log:\n{log[-3000:]}")
    held = [int(v) for v in match.group(1).split("/")]
    most = [int(v) for v in match.group(3).split("/")]
    return held, most, int(match.group(2)), int(match.group(4))


runs = {}
for ranks in (1, 2):
    run_dir = os.path.join(output, f"np{ranks}")
    fsi_run_checked(scene, run_dir, ranks, settings, timeout=600, label=f"-np {ranks}: ")
    with open(os.path.join(run_dir, "fsi-client.log")) as handle:
        runs[ranks] = (shares(handle.read()), load_sensors(run_dir))

(held1, most1, whole, selections1), one = runs[1]
(held2, most2, whole2, selections2), two = runs[2]
print(f"elements held: 1 rank {held1} (at most {most1}), 2 ranks {held2} (at most {most2}) of {whole}; "
      f"selections {selections1} and {selections2}")
check(whole == whole2 == 3072 + 192, f"the whole mesh: 3 264 triangles ({whole}, {whole2})")
check(all(0 < m < whole for m in most2),
      f"2 ranks: each rank holds only its share plus the halo, never the whole mesh ({most2} of {whole})")
check(sum(most2) < 1.5 * whole, f"2 ranks: the shares overlap only in the halo ({sum(most2)} < 1.5 x {whole})")
check(selections2 >= 1, f"the shares were chosen again as the paddle moved ({selections2} times during the "
      f"coupled steps)")
check(len(one["time"]) == len(two["time"]) > 10, f"the same sensor rows ({len(one['time'])}, {len(two['time'])})")
# The hinge torque is a Lagrange multiplier out of the structure's Newton iteration, which stops at
# its tolerance: a force changed in the last digits moves it by more (measured 6.8e-8 of its scale).
TOLERANCE = {"hinge_torque_y": 1e-6}
for name in one:
    scale = max(abs(v) for v in one[name]) or 1.0
    worst = max(abs(a - b) for a, b in zip(one[name], two[name])) / scale
    limit = TOLERANCE.get(name, 1e-9)
    print(f"{name}: -np 1 and -np 2 differ by {worst:.2e} of its scale")
    check(worst <= limit, f"{name}: -np 1 and -np 2 differ by {worst:.2e} of its scale (<= {limit:g})")
cleanup(output)
