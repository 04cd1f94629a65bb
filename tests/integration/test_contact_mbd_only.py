#!/usr/bin/python3
"""Contact between structures in an --mbd-only run (issue 19): a block dropped on a corner onto a
tank floor with a Contact block rocks and comes to rest on its long side at the depth the default
penetration tolerance promises (1 mm: 0.5 mm on two vertices), its energy never rising; the same
scene without the Contact block stops at the step where the block's mesh crosses the floor, with
both names, the place and the fix, status "failed" and exit 1 — never "completed"."""
import os
import subprocess

from fsi_test import ENV, binary, check, cleanup, fail, load_sensors, manifest, work_dir

SCENE = """scene_language = 1
SolverOptions { end_time = 1.5; Timeint { step_size = 1e-3 } }
Gravity { acceleration = [0, -9.81] }
RigidBody2D { name = "block"; mass = 1; inertia = 0.0041667; position = [0, 0.1]; angle = 0.5
  Mesh { points = [[-0.1, -0.05], [0.1, -0.05], [0.1, 0.05], [-0.1, 0.05]]; closed = 1 } }
Ground { Mesh { points = [[-1, 0.3], [-1, 0], [1, 0], [1, 0.3]] } }
CONTACT
Sensor { name = "y"; type = "position"; body = "block"; component = "y" }
Sensor { name = "angle"; type = "position"; body = "block"; component = "angle" }
Sensor { name = "kinetic"; type = "kinetic_energy" }
Sensor { name = "potential"; type = "potential_energy" }
"""

output = work_dir("contact_mbd_only")
with_contact = os.path.join(output, "drop.scene")
without_contact = os.path.join(output, "no_contact.scene")
with open(with_contact, "w") as handle:
    handle.write(SCENE.replace("CONTACT", 'Contact { body_a = "block"; friction = 0.5 }'))
with open(without_contact, "w") as handle:
    handle.write(SCENE.replace("CONTACT", ""))

run_dir = os.path.join(output, "run")
result = subprocess.run([binary("fsi-server"), with_contact, "--mbd-only", "--output", run_dir],
                        env=ENV, capture_output=True, text=True, timeout=120)
if result.returncode != 0:
    fail(f"the dropped block exited {result.returncode}:\n{result.stderr[-3000:]}")
check(manifest(run_dir)["status"] == "completed", "the run with contact completes")
sensors = load_sensors(run_dir)
y, angle = sensors["y"][-1], sensors["angle"][-1]
check(abs(y - (0.05 - 0.5e-3)) < 1e-6, f"the block rests 0.5 mm deep on the floor (y = {y:.9f} m)")
check(abs(angle) < 1e-6, f"and lies flat (angle {angle:.3g} rad)")
energy = [k + p for k, p in zip(sensors["kinetic"], sensors["potential"])]
rise = max(b - a for a, b in zip(energy, energy[1:]))
check(rise < 1e-9, f"kinetic + potential + penalty energy never rises in a step (largest {rise:.3g} J)")
print(f"rest y = {y:.9f} m, angle = {angle:.3g} rad, largest energy rise {rise:.3g} J, "
      f"energy {energy[0]:.6f} -> {energy[-1]:.6f} J")

crossed_dir = os.path.join(output, "crossed")
crossed = subprocess.run([binary("fsi-server"), without_contact, "--mbd-only", "--output", crossed_dir],
                         env=ENV, capture_output=True, text=True, timeout=120)
check(crossed.returncode == 1, f"the run whose meshes cross exits 1 ({crossed.returncode})")
check(manifest(crossed_dir)["status"] == "failed", "its run.json says failed, not completed")
for part in ("mesh crossing check: the meshes of 'block' and the ground cross at (",
             "add Contact { body_a = \"block\"; body_b = \"ground\" }", "(t = 0.0"):
    check(part in crossed.stderr, f"the message says: {part}")
print(crossed.stderr.strip().splitlines()[-2])
cleanup(output)
print("PASS")
