#!/usr/bin/python3
"""The dam break of Martin & Moyce (1952), n^2 = 2, a = 1.125 in, at the coarse resolution
(examples/dam_break/martin_moyce_coarse.scene: 10 particles across the column, 200 particles,
fsi-run with 1 rank): the surge front Z(T) of the front probe against the experiment's Fig. 3.

The run judges itself: completed, no particle lost (the scene allows none), no health warning,
the column at rest against its gate at release (the release check). Then analyze.py compares
Z = (x_front + d/2)/a with the experiment at its ten points and fails when the RMS of
(Z_sim - Z_exp)/Z_exp over the seven points with T > 2 exceeds this test's tolerance, 8 % (the
acceptance of issue 13, which every resolution meets: docs/validation.md, "Dam break").

The ten experimental points (T = t sqrt(2g/a), Z = z/a) are typed into analyze.py: Martin & Moyce
(1952), Phil. Trans. R. Soc. Lond. A 244, 312-324, Fig. 3, as digitised by PySPH
(pysph/examples/db_exp_data.py)."""
import json
import os

from fsi_test import check, cleanup, run_example_checked

TOLERANCE = 0.08


def own_checks(run):
    check(run["health"]["warnings"] == [], f"no health warning: {run['health']['warnings']}")


example_run = run_example_checked(("dam_break", "martin_moyce_coarse.scene"), 1, 900, ["--tolerance", str(TOLERANCE)],
                                  f"RMS of the surge front's relative error over T > 2 within {TOLERANCE:.0%} (analyze.py)",
                                  own_checks, at_rest="the column is at rest against its gate at release")
with open(os.path.join(example_run.run_dir, "analysis.json")) as handle:
    measured = json.load(handle)
# The front must have run: a gate that stayed, or a front probe that reads the column's edge,
# leaves Z at about 1 and fails above; this states the measured value in the log.
print(f"measured RMS {measured['rms_relative_error_T_above_2']:.4f}")
cleanup(example_run.work)
