#!/usr/bin/python3
"""A block three times as heavy as the water it displaces, turned by 0.3 rad and let go under water (d =
2 mm, fsi-run with 2 ranks), sinks to the tank floor, lands on a corner and stays above the floor
with the Contact between its mesh and the tank's (examples/immersed_block/falling_block_coarse.scene):
its lowest corner never goes below the floor by more than 5 penetration tolerances (impact), and
it comes to rest within 2 d of the floor (a layer of particles stays trapped under a flat face).
A run whose meshes cross without contact is tested in --mbd-only (test_contact_mbd_only.py); the
same check runs in coupled runs (StructureSide::advance). """
import math

from fsi_test import check, cleanup, load_sensors, run_example_checked

side = 0.02          # the block's side (immersed_block_model.inc)
tolerance = 1e-4     # the scene's penetration tolerance
spacing = 0.002      # d

example_run = run_example_checked(("immersed_block", "falling_block_coarse.scene"), 2, 1500, label="with contact: ")
sensors = load_sensors(example_run.run_dir)


def lowest_corner(y, angle):
    # The corners of the a x a square at the centre + R(angle) (+-a/2, +-a/2).
    return y - 0.5 * side * (abs(math.sin(angle)) + abs(math.cos(angle)))


corners = [lowest_corner(y, a) for y, a in zip(sensors["block_y"], sensors["block_angle"])]
lowest, final = min(corners), corners[-1]
# Under a flat face one layer of particles stays trapped (the wall holds it 0.75 d from both
# surfaces, docs/theory.md "The true shape"): the block comes to rest on it, about 1.5 d up.
check(final < 2 * spacing, f"the block sank to the floor: its lowest corner ends at {final * 1e3:.4f} mm (< 2 d)")
last = [c for t, c in zip(sensors["time"], corners) if t >= sensors["time"][-1] - 0.2]
check(max(last) - min(last) < 1e-5, f"it is at rest: its lowest corner moved {(max(last) - min(last)) * 1e3:.2e} mm over the last 0.2 s")
check(lowest >= -5 * tolerance, f"the lowest corner never went below the floor by more than 5 tolerances: {lowest * 1e3:.4f} mm")
check(final >= -2 * tolerance, f"it ends within 2 tolerances of the floor: {final * 1e3:.4f} mm")
print(f"measured: lowest corner {lowest * 1e3:.4f} mm, final {final * 1e3:.4f} mm, "
      f"final angle {sensors['block_angle'][-1]:.4f} rad", flush=True)

cleanup(example_run.work)
