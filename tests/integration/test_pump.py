#!/usr/bin/python3
"""Pump-driven channel flow with two valves (issue 14, thesis §6.5, examples/pump): the scene
(d = 2.5 mm, 6 262 particles, fsi-run with 2 ranks) for two piston periods of 0.6 s, after half the
example's equilibration (7 500 LIGGGHTS-only steps, 27 s less: the loop's water is at rest at
release all the same, kinetic over potential energy 4.2e-5 against 7.0e-6 after 15 000 steps and
the check's 1e-3). A piston
drives water clockwise round a closed loop through a rigid inlet flap (revolute joint, non-linear
spring, spring actor) and an elastic outlet strip (planar ANCF beam with two spring actors).
analyze.py judges the second cycle (issue 14: every cycle after the first): the net volume through
the inlet port and through the riser above the outlet positive, the backflow through each below
20 % of its forward volume, and each valve opening and shutting in its phase (the inlet opens in
the expansion and shuts in the compression, the outlet the other way round) or at most a tenth of
the half period before it.
The run judges itself: completed, no particle lost, no physics warning, at rest at release, action
= reaction to round-off, no particle closer to the valves or the walls than 0.3 r0. The checks
were seen to fail on a pump that does not work: with the inlet flap hinged at the port's left edge
(a layout tried on 2026-12-04, T = 0.4 s) the compression's flow held it open, the backflow
through the inlet was 33 % of the forward volume and the flap shut in 0 % of the compression;
with the thesis' nu = 1e-3 m^2/s the water tore off the piston and 39 % of the swept volume came
through the inlet (examples/pump/README.md, "Set-up, and why")."""
import json
import os

from fsi_test import boundary_checks, check, cleanup, run_example_checked

example_run = run_example_checked(("pump", "pump.scene"), 2, 900,
                                  ["--min-net", "0", "--max-backflow", "0.2", "--phase-lead", "0.1"],
                                  "the pump delivers, without backflow, its valves in their phases (analyze.py)",
                                  boundary_checks, at_rest="the loop's water is at rest at release",
                                  settings=["Resolution.cycles=2", "Resolution.equilibration_steps=7500"])
with open(os.path.join(example_run.run_dir, "analysis.json")) as handle:
    analysis = json.load(handle)
second = analysis["cycles"][1]
check(second["outlet_max_opening"] > 0.003,
      f"the elastic valve opens by millimetres: {1000 * second['outlet_max_opening']:.1f} mm")
cleanup(example_run.work)
