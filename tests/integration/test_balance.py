#!/usr/bin/python3
"""The balanced decomposition on 2 ranks (docs/user-guide.md, "Ranks and balance").

1. Dam break, coarse: script 1 splits along x (`processors * 1 1`), and the column stands in the
   left tenth of the tank. With `--balance off` (LIGGGHTS' even cuts) rank 0 holds every particle
   (imbalance 2); balanced, each rank holds half at the set-up, and the cuts follow the surge.
2. The balanced run, re-balanced whenever the counts differ at all (threshold 1, a check every 50
   steps), gives the unbalanced run's sensor histories to 1e-11 of each sensor's scale: moving
   particles between ranks changes only the summation order, because the last step's forces and
   density rates are carried through the set-up a move needs (measured 1.4e-14 over 1000 steps;
   without the carry 9.4e-10: the set-up recomputes them from the step's end).
3. Static tank, coarse: script 1 names no grid, so the client chooses it from the fluid's extent
   (a shallow layer: 2 x 1 x 1) and balances the cuts.
"""
import os
import re

from fsi_test import check, cleanup, example, fail, load_sensors, read, run_pair, work_dir


def run(scene, run_dir, overrides, client_args):
    server_status, client_status = run_pair(scene, run_dir, 2, overrides, 600, client_args)
    log = read(run_dir, "client.stderr")
    check(server_status == 0 and client_status == 0,
          f"{run_dir}: server and client exit 0 ({server_status}, {client_status})\n{log[-3000:]}")
    return log


def ghosts(log):
    """(ghosts per rank, ghost cut-off) from the client's closing line."""
    match = re.search(r"ghosts: ([\d /]+) per rank \(ghost cut-off ([\d.eE+-]+) m\)", log)
    if not match:
        fail(f"no ghosts line in the client's log:\n{log[-3000:]}")
    return [int(value) for value in match.group(1).split("/")], float(match.group(2))


def boundary_share(log):
    """(sampling points generated per evaluation on each rank, sampling points of each rank's share of the
    mesh per evaluation)."""
    match = re.search(r"boundary: ([\d /]+) sampling points generated per evaluation per rank, of ([\d /]+) in its "
                      r"share of the mesh", log)
    if not match:
        fail(f"no boundary line in the client's log:\n{log[-3000:]}")
    return [int(value) for value in match.group(1).split("/")], [int(value) for value in match.group(2).split("/")]


def decomposition(log):
    """(grid, source, shares, imbalance) from the client's set-up line."""
    match = re.search(r"decomposition: (\d+ x \d+ x \d+) ranks \(([^)]*)\), \w+ cuts .*?; particles per "
                      r"rank ([\d /]+) \(imbalance ([\d.]+)\)", log)
    if not match:
        fail(f"no decomposition line in the client's log:\n{log[-3000:]}")
    shares = [int(value) for value in match.group(3).split("/")]
    return match.group(1), match.group(2), shares, float(match.group(4))


output = work_dir("balance")
scene = example("dam_break", "martin_moyce_coarse.scene")
overrides = ["Resolution.equilibration_steps=2000", "Resolution.end_time=1000*Resolution.time_step",
             "Resolution.snapshot_every_steps=0"]

even_log = run(scene, os.path.join(output, "even"), overrides, ["--balance", "off"])
grid, source, shares, even_imbalance = decomposition(even_log)
print(f"even cuts: {grid} ({source}), particles per rank {shares}, imbalance {even_imbalance}")
check(grid == "2 x 1 x 1" and "processors command" in source,
      f"the dam break's script chooses the grid 2 x 1 x 1 ({grid}, {source})")
check(even_imbalance == 2.0 and shares[1] == 0,
      f"even cuts leave rank 1 without particles (shares {shares})")

balanced_log = run(scene, os.path.join(output, "balanced"), overrides,
                   ["--rebalance-every", "50", "--rebalance-threshold", "1"])
grid, source, shares, balanced_imbalance = decomposition(balanced_log)
print(f"balanced: {grid}, particles per rank {shares}, imbalance {balanced_imbalance}")
check(balanced_imbalance <= 1.02, f"balanced cuts share the particles (imbalance {balanced_imbalance} <= 1.02)")
summary = re.search(r"balance: (\d+) re-balance\(s\) in ([\d.]+) s; largest imbalance found at a check "
                    r"([\d.]+)", balanced_log)
if not summary:
    fail(f"no balance summary in the client's log:\n{balanced_log[-3000:]}")
moves, largest = int(summary.group(1)), float(summary.group(3))
print(f"balanced: {moves} re-balance(s), largest imbalance at a check {largest}")
check(moves >= 1, f"the cuts followed the moving fluid ({moves} re-balances)")
# The halo: with even cuts the column is far from the cut (no ghosts); balanced, each rank holds a
# band of the other's particles across the cut (about 4 of the column's 10 lattice columns here:
# the ghost cut-off is 2h + skin = 4.3 d), not all of them.
even_ghosts, _ = ghosts(even_log)
balanced_ghosts, cutoff = ghosts(balanced_log)
print(f"ghosts per rank: even {even_ghosts}, balanced {balanced_ghosts} (cut-off {cutoff} m)")
check(even_ghosts == [0, 0], f"even cuts: no rank holds ghosts ({even_ghosts})")
check(all(0 < g < sum(shares) / 2 for g in balanced_ghosts) and cutoff > 0,
      f"balanced: each rank holds a halo of the other's particles, not all of them ({balanced_ghosts})")
# The distributed boundary: a rank generates only the sampling points within reach of its own
# particles, out of those of its share of the mesh. With even cuts rank 1 holds no particle and
# samples nothing; balanced, each rank samples the walls near its half of the column, not all of
# its share (most of the floor is beyond every particle's reach).
even_share, even_held = boundary_share(even_log)
balanced_share, balanced_held = boundary_share(balanced_log)
print(f"sampling points generated per evaluation: even {even_share} of {even_held}, balanced {balanced_share} "
      f"of {balanced_held}")
check(even_share[1] == 0 and 0 < even_share[0] < even_held[0],
      f"even cuts: rank 1 samples nothing, rank 0 only the walls near the column ({even_share} of {even_held})")
check(all(0 < s < h for s, h in zip(balanced_share, balanced_held)),
      f"balanced: each rank samples part of its share ({balanced_share} of {balanced_held})")
check(largest <= 1.1, f"the imbalance found at the checks stayed small ({largest} <= 1.1)")

even = load_sensors(os.path.join(output, "even"))
balanced = load_sensors(os.path.join(output, "balanced"))
check(len(even["time"]) == len(balanced["time"]) == 51, "51 sensor rows each (t = 0 and 50 x 20 steps)")
for name in even:
    scale = max(abs(v) for v in even[name]) or 1.0
    worst = max(abs(a - b) for a, b in zip(even[name], balanced[name])) / scale
    print(f"{name}: balanced and even differ by {worst:.2e} of its scale")
    check(worst <= 1e-11, f"{name}: balanced and even runs differ by {worst:.2e} of its scale (<= 1e-11)")

tank_log = run(example("static_tank", "static_tank_coarse.scene"), os.path.join(output, "tank"),
               ["Resolution.equilibration_steps=200", "Resolution.end_time=20*Resolution.time_step"], [])
grid, source, shares, tank_imbalance = decomposition(tank_log)
print(f"static tank: {grid} ({source}), particles per rank {shares}, imbalance {tank_imbalance}")
check(grid == "2 x 1 x 1" and source.startswith("automatic"),
      f"the static tank's grid comes from the fluid's extent: 2 x 1 x 1 ({grid}, {source})")
check(tank_imbalance <= 1.02, f"and its cuts share the particles ({tank_imbalance} <= 1.02)")
cleanup(output)
