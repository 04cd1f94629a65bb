#!/usr/bin/python3
"""Sloshing in a pitching tank (Akyildiz & Unal 2006, examples/pitching_tank): a rigid tank turned
about the middle of its floor by a drive on its angle through a pin (RevoluteJoint +
PrescribedMotion + Assembly), the water inside, wall-pressure transducers that move with the tank.
The coarse scene (d = 20 mm, 1 058 particles, 2 ranks) over the first period and a half (4.8 s)
of the experiment's record. Checked:
- the run judges itself: completed, no particle lost, no physics warning, water at rest at
  release, action = reaction, no particle closer to the walls than 0.3 r0;
- the tank turned as prescribed: its angle spans 2 x 4 degrees;
- transducer 2 against the experiment (analyze.py, a fit at the pitching frequency over the
  experiment's points within the run): its amplitude within 15 % of the experiment's and its lag
  within 0.15 s; its mean within 5 % of the still water of the depth filled (this coarse run's own
  bounds, set before its first run; measured: docs/validation.md "Pitching tank");
- transducer 2 stays wet at every row (the patch moves with the wall)."""
import json
import math
import os

from fsi_test import boundary_checks, check, cleanup, load_sensors, run_example_checked

example_run = run_example_checked(("pitching_tank", "pitching_tank_coarse.scene"), 2, 900,
                                  ["--amplitude-tolerance", "0.15", "--lag-tolerance", "0.15", "--mean-tolerance", "0.05"],
                                  "transducer 2 follows the experiment (analyze.py)", boundary_checks,
                                  at_rest="the water is at rest at release", settings=["Resolution.end_time=4.8"])
sensors = load_sensors(example_run.run_dir)
swing = max(sensors["angle"]) - min(sensors["angle"])
check(abs(swing - 2 * 4 * math.pi / 180) < 1e-3, f"the tank turns by +-4 degrees (span {math.degrees(swing):.3f} deg)")
driest = min(sensors["p2_pairs"])
check(driest > 0, f"transducer 2 is wet at every row (fewest particle-wall pairs {driest:.0f})")
with open(os.path.join(example_run.run_dir, "analysis.json")) as handle:
    analysis = json.load(handle)
check(analysis["points"] >= 12, f"the fit takes at least 12 of the experiment's points ({analysis['points']})")
cleanup(example_run.work)
