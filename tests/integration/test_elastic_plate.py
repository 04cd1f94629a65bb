#!/usr/bin/python3
"""Elastic plate under a water column (issue 14, examples/elastic_plate; O'Connor & Rogers 2021):
the coarse scene (d = 50 mm, 800 particles, fsi-run with 2 ranks split along y, so the plate's
forces come from the lower rank and the column's weight through both). A clamped-clamped planar
ANCF plate (L = 1 m, h = 0.05 m, E = 67.5 GPa) carries a 2 m water column and its own weight;
its mid-span deflection, averaged over the second half of the run, must be within 3 % of the
closed form -0.0026 g (rho_w H + rho_s h) L^4 / D = -7.048e-5 m (analyze.py; -0.79 % measured on
2026-12-02 with 1 rank; issue 14's 5 % holds at every resolution: docs/validation.md
"Elastic plate"). The run judges itself: completed, no particle lost, no physics warning, at rest
at release, action = reaction to round-off, no particle closer to a wall than 0.3 r0 (the plate
is a moving wall); the fluid's load on the plate within 2 % of the column's weight (the fluid's
share of the deflection's error, reported by analyze.py)."""
import json
import os

from fsi_test import boundary_checks, check, cleanup, run_example_checked

DEFLECTION_TOLERANCE = 0.03
LOAD_TOLERANCE = 0.02


example_run = run_example_checked(("elastic_plate", "elastic_plate_coarse.scene"), 2, 900,
                                  ["--tolerance", str(DEFLECTION_TOLERANCE)],
                                  f"mid-span deflection within {100 * DEFLECTION_TOLERANCE:g} % of the closed form "
                                  "(analyze.py)", boundary_checks, at_rest="the column is at rest on the plate at release")
with open(os.path.join(example_run.run_dir, "analysis.json")) as handle:
    analysis = json.load(handle)
check(abs(analysis["fluid_load_error"]) < LOAD_TOLERANCE,
      f"the fluid's load on the plate within {100 * LOAD_TOLERANCE:g} % of rho_w g H L: "
      f"{100 * analysis['fluid_load_error']:+.2f} %")
check(analysis["deflection_max"] < 0, "the plate sags under the water over the whole window")
cleanup(example_run.work)
