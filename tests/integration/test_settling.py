#!/usr/bin/python3
"""The water starts at rest (issue 19): a coarse 13 cm column (examples/water_column) settled by the
built-in drag carries at least 99 % of its weight on the floor at release, and the check at release
says so in run.json and the log; the same column with the drag off and a quarter of the
equilibration is not at rest, and the check's warning names what to change. Two runs of seconds
each (about 1 200 particles, fsi-run with 2 ranks)."""
import math
import os
import subprocess

from fsi_test import binary, check, cleanup, example, work_dir, ENV
from run_manifest import read_run_manifest

SCENE = example("water_column", "water_column.scene")


def run(output, *overrides):
    command = [binary("fsi-run"), SCENE, "--np", "2", "--output", output]
    for item in overrides:
        command += ["--set", item]
    result = subprocess.run(command, env=ENV, capture_output=True, text=True, timeout=600)
    print(result.stderr[-3000:])
    check(result.returncode == 0, f"fsi-run exits 0 (got {result.returncode})")
    with open(os.path.join(output, "fsi-server.log")) as handle:
        return read_run_manifest(output), handle.read()


work = work_dir("settling")

# Built-in settling: the default (no settling_drag in the scene) derives 2 pi sqrt(g/H).
settled, log = run(os.path.join(work, "settled"))
release = settled["release"]
check(release is not None, "run.json has the fluid at release")
height = release["column_height"]
check(abs(height - 61 * 0.004 / 1.9) < 1e-9, f"H = 61 lattice spacings = {height:.6g} m (the server's lattice)")
expected_drag = 2 * math.pi * math.sqrt(9.81 / height)
check(abs(release["settling_drag"] - expected_drag) < 1e-9 * expected_drag,
      f"settling drag {release['settling_drag']:.6g} 1/s = 2 pi sqrt(g/H)")
fraction = release["weight_fraction"]
check(0.99 <= fraction <= 1.01, f"the floor carries {100 * fraction:.2f} % of the fluid's weight at release (99..101 %)")
weight = settled["fluid"]["particle_count"] * settled["fluid"]["particle_mass"] * 9.81
check(abs(release["weight"] - weight) < 1e-9 * weight, f"weight M g = N m g = {weight:.6g} N/m")
check(release["kinetic_over_potential"] <= 1e-3,
      f"kinetic / potential energy {release['kinetic_over_potential']:.3e} <= 1e-3")
check(release["at_rest"] is True and release["warning"] is None, "at rest: no warning")
check("fluid at release: settling drag" in log and "not at rest" not in log, "the log reports the release, without a warning")

# No drag and a quarter of the equilibration: the column is still falling when it is released.
moving, log = run(os.path.join(work, "moving"), "LIGGGHTS.settling_drag=0", "LIGGGHTS.equilibration_steps=1000")
release = moving["release"]
check(moving["status"] == "completed", "the run still completes (the check warns, it does not stop the run)")
check(release["settling_drag"] == 0, "no settling drag")
check(not 0.99 <= release["weight_fraction"] <= 1.01,
      f"the floor carries {100 * release['weight_fraction']:.1f} % of the weight: outside 99..101 %")
check(release["kinetic_over_potential"] > 1e-3,
      f"kinetic / potential energy {release['kinetic_over_potential']:.3e} > 1e-3")
warning = release["warning"] or ""
check(release["at_rest"] is False and "not at rest" in warning, f"the check warns: {warning}")
check("equilibration_steps }, now 1000" in warning and "settling_drag = 0 } turns the settling drag off" in warning,
      "the warning names what to change: more equilibration_steps, the settling drag")
check(not any("not at rest" in w for w in moving["warnings"]),
      "run.json's warnings stay the scene's physics checks (the release has its own entry)")
check("[warning] the fluid is not at rest when the bodies are released" in log, "and in the server's log")
cleanup(work)
