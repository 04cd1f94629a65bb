#!/usr/bin/python3
"""The true shape: a 20 mm block drawn with its true outline and held 3.5 cm under water (d = 2 mm,
fsi-run with 2 ranks, the built-in settling) feels Archimedes' buoyancy rho0 g V within 3 % over the
second half of the run (analyze.py; measured 0.980 on 2026-12-02, docs/validation.md "True shape")
where the thesis' wall (k = 17500, r0 = r_c = 2h) gave 1.78 rho0 g V. The issue asked for 2 %: at
a/d = 10 the particle lattice at rest carries a history-dependent part of the load (docs/theory.md,
"The true shape", limits), so 2 % holds at d = 1 mm, not here. The run judges itself: completed,
no particle lost, no physics warning but the documented viscosity_match, the water at rest at
release."""
from fsi_test import check, cleanup, run_example_checked


def own_checks(run):
    # The one expected warning: the example keeps the fluid of its measurements, alpha = nu/(c h), a
    # fluid of nu/16 under the thesis' wall friction (README.md, docs/theory.md "Viscosity").
    warnings = run.get("warnings", [])
    check(len(warnings) == 1 and "viscosity_match" in warnings[0], f"only the viscosity_match warning: {warnings}")


example_run = run_example_checked(("immersed_block", "immersed_block_coarse.scene"), 2, 1500, ["--tolerance", "0.03"],
                                  "fluid force on the block within 3 % of rho0 g V (analyze.py)", own_checks,
                                  at_rest="the water is at rest at release")
cleanup(example_run.work)
