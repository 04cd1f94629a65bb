#!/usr/bin/python3
"""A block twice as heavy as the water it displaces, turned by 0.3 rad and let go under water (d =
2 mm, fsi-run with 2 ranks), sinks to the tank floor, lands on a corner and stays on the floor
through the Contact between its mesh and the tank's (examples/immersed_block/falling_block_coarse.scene):
its lowest corner never goes below the floor by more than 5 penetration tolerances (impact) and
ends within 2. The same scene without the Contact
block stops with the crossing diagnosis naming both meshes: exit 1, run.json "failed", never
"completed"."""
import glob
import math
import os
import shutil
import subprocess

from fsi_test import binary, check, cleanup, example, load_sensors, manifest, work_dir, ENV

output = work_dir("falling_block")
side = 0.02          # the block's side (immersed_block_model.inc)
tolerance = 1e-4     # the scene's penetration tolerance

run_dir = os.path.join(output, "contact")
result = subprocess.run([binary("fsi-run"), example("immersed_block", "falling_block_coarse.scene"), "--np", "2",
                         "--output", run_dir], env=ENV, capture_output=True, text=True, timeout=1500)
print(result.stderr[-3000:])
check(result.returncode == 0, f"with contact: fsi-run exits 0 (got {result.returncode})")
run = manifest(run_dir)
check(run["status"] == "completed", "with contact: run.json says completed")
check(run["checks"]["particles_final"] == run["checks"]["particles_initial"], "with contact: no particle lost")
sensors = load_sensors(run_dir)


def lowest_corner(y, angle):
    # The corners of the a x a square at the centre + R(angle) (+-a/2, +-a/2).
    return y - 0.5 * side * (abs(math.sin(angle)) + abs(math.cos(angle)))


corners = [lowest_corner(y, a) for y, a in zip(sensors["block_y"], sensors["block_angle"])]
lowest, final = min(corners), corners[-1]
check(final < 1e-3, f"the block reached the floor: its lowest corner ends at {final * 1e3:.4f} mm (< 1 mm)")
check(lowest >= -5 * tolerance, f"the lowest corner never went below the floor by more than 5 tolerances: {lowest * 1e3:.4f} mm")
check(final >= -2 * tolerance, f"it ends within 2 tolerances of the floor: {final * 1e3:.4f} mm")
print(f"measured: lowest corner {lowest * 1e3:.4f} mm, final {final * 1e3:.4f} mm, "
      f"final angle {sensors['block_angle'][-1]:.4f} rad", flush=True)

# Without contact: copy the example, drop the Contact line, and expect the crossing diagnosis.
bare = os.path.join(output, "bare")
os.makedirs(bare, exist_ok=True)
for path in glob.glob(example("immersed_block", "*.in*")) + [example("immersed_block", "immersed_block_model.inc")]:
    shutil.copy(path, bare)
with open(example("immersed_block", "falling_block_coarse.scene")) as handle:
    text = "".join(line for line in handle if not line.startswith("Contact"))
scene = os.path.join(bare, "falling_without_contact.scene")
with open(scene, "w") as handle:
    handle.write(text)
run_dir = os.path.join(output, "without")
result = subprocess.run([binary("fsi-run"), scene, "--np", "2", "--output", run_dir], env=ENV,
                        capture_output=True, text=True, timeout=1500)
log = result.stderr + open(os.path.join(run_dir, "fsi-server.log"), errors="replace").read() \
    if os.path.exists(os.path.join(run_dir, "fsi-server.log")) else result.stderr
check(result.returncode == 1, f"without contact: fsi-run exits 1 (got {result.returncode})")
check("mesh crossing check" in log and "'block'" in log and "ground" in log and "add Contact" in log,
      "without contact: the crossing diagnosis names the block and the ground and says how to fix it" +
      ("" if "mesh crossing check" in log else "\n" + log[-3000:]))
run = manifest(run_dir)
check(run["status"] == "failed", f"without contact: run.json says failed (got {run['status']})")
cleanup(output)
