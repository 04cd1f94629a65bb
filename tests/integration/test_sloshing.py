#!/usr/bin/python3
"""Sloshing tank (issue 13, examples/sloshing): the tank is a rigid body moved sideways by the
experiment's forcing (Faltinsen et al. 2000: amplitude 0.032 m, period 1.3 s), its wave gauges
are probes that move with it (protocol 1.4, ProbePlacement). Coarse: d = 20 mm, 2 ranks, the
first 3 s of the record. Checked:
- a client of protocol 1.3 (probes, but none that move) is refused by name before any set-up;
- the run judges itself: completed, no particle lost, no physics warning, water at rest at release;
- the probes move with the tank: the point probe 0.01 m inside the right wall sees at least 10
  particles at every row (24 measured; with fsi-server's placement switched off it stays in space,
  5.4 cm outside the wall when the tank is at its left end, and saw 5: measured on 2026-12-02);
- the tank moved as prescribed (its x sensor spans 2 A = 0.064 m);
- the wave at the left gauge against the experiment (analyze.py): the deviation of the maximum,
  of the minimum and the RMS of eta_sim - eta_exp each within 25 % of the experiment's range over
  the window (issue 13 asks 15 % at the resolutions of docs/validation.md; this coarse run's own,
  looser bound: measured on 2026-12-02, see docs/validation.md "Sloshing")."""
import os
import subprocess

from fsi_test import check, cleanup, example, load_sensors, refused_client, run_example_checked, work_dir

output = work_dir("sloshing")
scene = example("sloshing", "faltinsen_coarse.scene")

# A client of protocol 1.3 evaluates probes but cannot move them: the server refuses it by name
# before any set-up data.
said = refused_client(scene, os.path.join(output, "old_client"), 0x1C)
check("error: [SetupFailed]" in said and "lacks probes that move (capability 'moving probes' of protocol 1.4)" in said
      and "use an fsi-client of protocol 1.4 or later, or fix the probe in space" in said,
      "a client without moving probes is told what it lacks and how to fix it")
cleanup(output)


def own_checks(run):
    check(run.get("warnings", []) == [], f"no physics warning: {run.get('warnings')}")


example_run = run_example_checked(("sloshing", "faltinsen_coarse.scene"), 2, 1200, analyze_args=["--tolerance", "0.25"],
                                  analyze_claim="the wave at the gauge within 25 % of the experiment's range (analyze.py)",
                                  own_checks=own_checks, at_rest="the water is at rest at release")
sensors = load_sensors(example_run.run_dir)
travel = max(sensors["tank_x"]) - min(sensors["tank_x"])
check(abs(travel - 0.064) < 0.002, f"the tank travels 2 A = 0.064 m (got {travel:.4f} m)")
fewest = min(sensors["right_wall_particles"])
check(fewest >= 10, f"the probe inside the right wall moves with the tank: it sees >= 10 particles at every row "
                    f"(fewest {fewest:.0f})")
cleanup(example_run.work)
