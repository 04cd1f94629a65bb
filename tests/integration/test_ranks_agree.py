#!/usr/bin/python3
"""-np 1 and -np 2 give the same sensor histories over the first 100 coupled steps (relative
1e-6 of each sensor's largest magnitude): the fix's per-rank evaluation and the reduction of the
vertex forces over ranks change only the summation order."""
import os

from fsi_test import check, cleanup, example, load_sensors, run_pair, work_dir

scene = example("static_tank", "static_tank_coarse.scene")
overrides = ["Resolution.end_time=100*Resolution.time_step", "Resolution.equilibration_steps=500"]
output = work_dir("ranks")
histories = {}
for ranks in (1, 2):
    run_dir = os.path.join(output, f"np{ranks}")
    server, client = run_pair(scene, run_dir, ranks, overrides, timeout=600)
    check(server == 0 and client == 0, f"-np {ranks}: server and client exit 0 ({server}, {client})")
    histories[ranks] = load_sensors(run_dir)

one, two = histories[1], histories[2]
check(len(one["time"]) == 101 and len(two["time"]) == 101, "101 sensor rows each (t = 0 and 100 steps)")
for name in one:
    scale = max(abs(v) for v in one[name]) or 1.0
    worst = max(abs(a - b) for a, b in zip(one[name], two[name])) / scale
    check(worst <= 1e-6, f"{name}: -np 1 and -np 2 differ by {worst:.2e} of its scale (<= 1e-6)")
cleanup(output)
