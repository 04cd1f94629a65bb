#!/usr/bin/python3
"""U-tube liquid column (issue 13, examples/u_tube): the coarse column (d = 5 mm, 8 particles across
the tube, fsi-run with 2 ranks), released displaced by 25 mm per leg, swings with the natural
period of linear theory 2 pi sqrt(L / (2 g)) = 1.042 s within 3 % (analyze.py's fit of a damped sinusoid:
-1.77 % measured on 2026-12-02 with 1 rank; docs/validation.md "U-tube" has the finer resolutions). The run judges
itself: completed, no particle lost, no physics warning, the column at rest at release (held by
script 1's body force, which script 2 removes), and the decay reported."""
from fsi_test import check, cleanup, run_example_checked


def own_checks(run):
    check(run.get("warnings", []) == [], f"no physics warning: {run.get('warnings')}")


example_run = run_example_checked(("u_tube", "u_tube_coarse.scene"), 2, 900, ["--tolerance", "0.03"],
                                  "natural period within 3 % of 2 pi sqrt(L/2g) (analyze.py)", own_checks,
                                  at_rest="the column is at rest at release")
check("damping ratio" in example_run.analysis.stdout, "the decay is reported")
cleanup(example_run.work)
