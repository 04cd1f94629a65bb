#!/usr/bin/python3
"""Andrews' squeezing mechanism (examples/mbd_mechanisms/andrews_squeezer.scene; IVP Test Set,
problem "andrews"), run by fsi-server --mbd-only, against the test set's reference angles at
t = 0.03 s, with the largest relative error over the seven angles:
  fixed-step Radau IIA 3, h = 1e-4 s:          < 2e-6   (measured 5.2e-7, 2026-12-06)
  IDA at its default tolerances (1e-6, 1e-8):  < 1e-4   (measured 2.3e-5)
  IDA at rtol 1e-10, atol 1e-12:               < 1e-8   (measured 9.2e-10)
Before 2026-12-06 IDA failed at t = 0 at every tolerance tighter than atol 1e-5 (its first step's
error weights took h = 1: the corrector failed at ever smaller steps down to hmin); the two IDA
runs are that failure's test. The accuracy must follow the tolerance: the tight run at least 100
times closer than the default one."""
import os

from fsi_test import check, cleanup, example, fail, mbd_only_checked, work_dir

# IVP Test Set (F. Mazzia, F. Iavernaro, C. Magherini, "Test Set for IVP Solvers", problem
# "andrews", reference solution y(0.03), first 7 components): beta, Theta, gamma, Phi, delta, Omega,
# epsilon [rad].
REFERENCE = [0.1581077119629904e2, -0.1575637105984298e2, 0.4082224013073101e-1,
             -0.5347301163226948, 0.5244099658805304, 0.5347301163226948, 0.1048080741042263e1]
END_TIME = 0.03

output = work_dir("andrews_squeezer")
scene = example("mbd_mechanisms", "andrews_squeezer.scene")


def largest_error(name, *overrides):
    sensors, run = mbd_only_checked(scene, os.path.join(output, name), overrides, label=name)
    if abs(sensors["time"][-1] - END_TIME) > 1e-12:
        fail(f"{name}: the last row is t = {sensors['time'][-1]}, not {END_TIME}")
    k = {i: sensors[f"K{i}_angle"][-1] for i in range(1, 8)}
    angles = [k[1], k[2] - k[1], k[3], k[4] - k[5], k[5], k[6] - k[7], k[7]]
    error = max(abs(a - r) / abs(r) for a, r in zip(angles, REFERENCE))
    print(f"{name}: {run['model']['integrator']}; {run['newton']['steps']} integrator steps; largest "
          f"relative error of the 7 angles {error:.2e}", flush=True)
    return error


fixed = largest_error("fixed")
check(fixed < 2e-6, f"Radau IIA 3, h = 1e-4 s: largest relative error {fixed:.2e} < 2e-6")
ida = largest_error("ida_default", 'SolverOptions.Timeint.method="ida"')
check(ida < 1e-4, f"IDA at its default tolerances: largest relative error {ida:.2e} < 1e-4")
tight = largest_error("ida_tight", 'SolverOptions.Timeint.method="ida"',
                      "SolverOptions.ErrorControl.relative_tolerance=1e-10",
                      "SolverOptions.ErrorControl.absolute_tolerance=1e-12")
check(tight < 1e-8 and tight < 0.01 * ida,
      f"IDA at rtol 1e-10, atol 1e-12: {tight:.2e} < 1e-8, and 100 times below the default's {ida:.2e}")
cleanup(output)
