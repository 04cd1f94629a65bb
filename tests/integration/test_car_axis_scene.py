#!/usr/bin/python3
"""The integrator chosen in the scene (SolverOptions.Timeint.method) on the car axis problem of the
IVP Test Set, written as a scene (examples/mbd_mechanisms/car_axis.scene), run by fsi-server
--mbd-only, against the test set's reference y(3) to the digits the engine's own C++ tests reach
on the same problem (mbd_server/mbd/tests/car_axis_test.cpp, ida_test.cpp,
adaptive_radau_test.cpp):
  fixed-step Radau IIA 3, h = 1e-4:              >= 6 significant digits in all 10 components;
  IDA, rtol 1e-10, atol 1e-12:                   >= 6 significant digits in all 10 components;
  adaptive Radau IIA 3, rtol 1e-6, atol 1e-8:    relative error of positions and velocities < 1e-6.
The multipliers are read through the joints' forces: the test set's lambda_1 from phi1's force on
the arm (the left wheel feels the opposite; G_1 = (xb, yb)), lambda_2 from the axle's force on the
left wheel (G_2 = 2 (r_l - r_r))."""
import math
import os
import subprocess

from fsi_test import ENV, binary, check, cleanup, example, fail, mbd_only_checked, work_dir

# IVP Test Set (Mazzia & Magherini), car axis, y(3): xl, yl, xr, yr, ul, vl, ur, vr, lambda_1,
# lambda_2 (/work/shared/reference-data/ivp_testset_caraxis_crank_reference.dat, as typed into
# mbd_server/mbd/tests/reference_problems.hpp).
REFERENCE = [0.493455784275402809122e-1, 0.496989460230171153861, 0.104174252488542151681e1,
             0.373911027265361256927, -0.770583684040972357970e-1, 0.744686658723778553466e-2,
             0.175568157537232222276e-1, 0.770341043779251976443, -0.473688659084893324729e-2,
             -0.110468033125734368808e-2]
END_TIME = 3.0

output = work_dir("car_axis_scene")
scene = example("mbd_mechanisms", "car_axis.scene")


def run(name, *overrides):
    sensors, run_manifest = mbd_only_checked(scene, os.path.join(output, name), overrides, timeout=300,
                                             label=name)
    if abs(sensors["time"][-1] - END_TIME) > 1e-9:
        fail(f"{name}: the last row is t = {sensors['time'][-1]}, not {END_TIME}")
    last = {key: column[-1] for key, column in sensors.items()}
    xb, yb = math.sqrt(1 - (0.1 * math.sin(10 * END_TIME)) ** 2), 0.1 * math.sin(10 * END_TIME)
    lambda_1 = -(last["phi1_force_x"] * xb + last["phi1_force_y"] * yb)
    dx, dy = last["xl"] - last["xr"], last["yl"] - last["yr"]
    lambda_2 = (last["axle_force_x"] * dx + last["axle_force_y"] * dy) / (2 * (dx * dx + dy * dy))
    computed = [last[key] for key in ("xl", "yl", "xr", "yr", "ul", "vl", "ur", "vr")] + [lambda_1, lambda_2]
    errors = [abs(c - r) / abs(r) for c, r in zip(computed, REFERENCE)]
    digits = [-math.log10(e) if e > 0 else 99.0 for e in errors]
    print(f"{name}: {run_manifest['model']['integrator']}; Newton {run_manifest['newton']}; significant digits "
          + " ".join(f"{d:.1f}" for d in digits), flush=True)
    return run_manifest, errors, digits


fixed, _, digits = run("fixed")
check(fixed["model"]["integrator"] == "Radau IIA, 3 stages" and min(digits) >= 6.0,
      f"fixed-step Radau IIA 3, h = 1e-4: at least 6 digits in every component (min {min(digits):.1f})")

ida, _, digits = run("ida", 'SolverOptions.Timeint.method="ida"', "SolverOptions.Timeint.step_size=0.01",
                     "SolverOptions.ErrorControl.relative_tolerance=1e-10",
                     "SolverOptions.ErrorControl.absolute_tolerance=1e-12")
check(ida["model"]["integrator"].startswith("SUNDIALS IDA") and min(digits) >= 6.0,
      f"IDA chosen in the scene, rtol 1e-10: at least 6 digits in every component (min {min(digits):.1f})")
check(ida["steps"] == 300 and ida["newton"]["steps"] > 0, f"IDA: 300 output steps, {ida['newton']['steps']} IDA steps")

adaptive, errors, _ = run("adaptive", 'SolverOptions.Timeint.method="adaptive"', "SolverOptions.Timeint.step_size=0.01",
                          "SolverOptions.ErrorControl.relative_tolerance=1e-6",
                          "SolverOptions.ErrorControl.absolute_tolerance=1e-8")
worst = max(errors[:8])
check(adaptive["model"]["integrator"].startswith("adaptive Radau IIA") and worst < 1e-6,
      f"adaptive Radau IIA chosen in the scene, rtol 1e-6: positions and velocities to {worst:.1e} (< 1e-6)")
# A coupled run keeps the fixed coupled step: --check of the scene (not --mbd-only) says so.
result = subprocess.run([binary("fsi-server"), scene, "--check", "--set", 'SolverOptions.Timeint.method="ida"'],
                        env=ENV, capture_output=True, text=True, timeout=60)
warning = [line for line in result.stdout.splitlines() if "(integration_method)" in line]
# It points at where the method was chosen: here the --set.
check(result.returncode == 0 and len(warning) == 1 and 'SolverOptions.Timeint.method="ida": warning' in warning[0] and
      "coupled run integrates with Radau IIA, 3 stages" in warning[0],
      f"--check of a coupled run warns that it keeps the fixed step: {warning}")
result = subprocess.run([binary("fsi-server"), scene, "--check", "--mbd-only", "--set",
                         'SolverOptions.Timeint.method="ida"'], env=ENV, capture_output=True, text=True, timeout=60)
check("(integration_method)" not in result.stdout, "--check --mbd-only does not warn: IDA runs there")
cleanup(output)
print("car axis scene: 6 passed, 0 failed")
