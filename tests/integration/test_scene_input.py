#!/usr/bin/python3
"""Scene input on the command line (issue 18): `--set` adds a key the scene schema declares and the
file lacks, and refuses one it does not declare; `--check` reports an end time the step does not
divide, at its line, with the step and end times that would fit."""
import subprocess

from fsi_test import ENV, binary, check, example

SCENE = example("static_tank", "static_tank_coarse.scene")


def server(*arguments):
    return subprocess.run([binary("fsi-server"), *arguments], capture_output=True, text=True, env=ENV,
                          timeout=60)


# The coarse tank's Timeint block gives no constraint_form.
added = server(SCENE, "--print-params", "--set", 'SolverOptions.Timeint.constraint_form="index2"')
check(added.returncode == 0 and 'constraint_form = "index2"  % --set SolverOptions.Timeint.constraint_form'
      in added.stdout, f"--set adds a key the schema declares and the file lacks\n{added.stderr}")

unknown = server(SCENE, "--check", "--set", "SolverOptions.Timeint.stepsize=1e-5")
check(unknown.returncode == 2 and "the scene file has no parameter 'SolverOptions.Timeint.stepsize'" in unknown.stderr
      and "did you mean 'SolverOptions.Timeint.step_size'?" in unknown.stderr,
      f"--set refuses a key the schema does not declare, suggesting the right one\n{unknown.stderr}")

# 0.15 s / 5e-6 s = 30000 steps: divides; 0.15 s / 7e-6 s = 21428.57 does not.
fits = server(SCENE, "--check", "--set", "Resolution.time_step=5e-6")
check(fits.returncode == 0 and "end_time / step_size" not in fits.stdout, "a step that divides the end time: silent")
shifted = server(SCENE, "--check", "--set", "Resolution.time_step=7e-6")
model = example("static_tank", "static_tank_model.inc")
line = next(i for i, text in enumerate(open(model), 1) if "end_time = Resolution.end_time" in text)
expected = (f"{model}:{line}:3: warning (end_time): end_time / step_size = 0.15 s / 7e-06 s = 21428.57 is not "
            "a whole number: the run takes 21429 steps and ends at t = 0.150003 s")
check(shifted.returncode == 0 and expected in shifted.stdout,
      f"--check reports an end time the step does not divide, at its line\n{shifted.stdout}")
check("use step_size = 0.15/21428 (21428 steps) or 0.15/21429 (21429 steps)" in shifted.stdout,
      "... with the steps that divide it")
