#!/usr/bin/python3
"""The energy audit stops the added-mass instability (issue 15; docs/theory.md, "The energy
audit"; docs/user-guide.md, "When a run stops: the health checks"). The floating box of
examples/floating_box made light (100 kg/m, a tenth of the water it displaces at its draft of
0.1 m, where it starts) and coupled with k = 20 fluid steps per structure step: the held force
lags the box by 20 fluid steps, its heave grows, and the coupling creates energy. Checked: the
audit warns, then stops the run when the created energy has grown three times over
(FluidHealth.max_coupling_energy_growth, default 3) with the named diagnosis and remedy, a
non-zero exit status, run.json "failed" with the check 'coupling_energy' and both steps, no NaN
in sensors.csv, never "completed" in the log, and before any other health check fires.
Measured (2026-12-03, 1 rank): warning at step 3 600 (7.61 J, 10.6 % of the energy moved through
the interface), stop at step 5 360 (23.2 J); the same run with the check off goes on until a
particle breaks through the box's wall at step 9 760 (wall_distance); with k = 1 the box heaves
quietly (0.13 % of the traffic at most). The healthy coupled runs of the suite run with this check on."""
import os
import subprocess

from fsi_test import ENV, binary, check, cleanup, example, fail, manifest, read, work_dir

output = work_dir("coupling_energy")
run_dir = os.path.join(output, "light_box_k20")
LIGHT_BOX = ["Geometry.box_mass=100", "Geometry.initial_draft=0.1", "SolverOptions.Timeint.substeps=20",
             "Resolution.end_time=3.2", "Output.snapshot_every_steps=0"]
command = [binary("fsi-run"), example("floating_box", "floating_box.scene"), "--np", "1", "--output", run_dir]
for item in LIGHT_BOX:
    command += ["--set", item]
result = subprocess.run(command, env=ENV, capture_output=True, text=True, timeout=600)
log = read(run_dir, "fsi-server.log")
if result.returncode == 0:
    print(log[-3000:])
    fail("the unstable light box ran to its end with exit status 0")
run_json = manifest(run_dir)
audit = run_json["energy_audit"]
reason = run_json["reason"] or ""
print(reason[:1200])
check(run_json["status"] == "failed", "run.json says failed")
check(run_json["health"]["failed_check"] == "coupling_energy",
      f"the check that stopped it is coupling_energy ({run_json['health']['failed_check']})")
warned, stopped = audit["injection_warning_step"], audit["stop_step"]
check(warned is not None and stopped is not None and stopped > warned,
      f"the audit warned at step {warned} and stopped the run later, at step {stopped}")
check(audit["coupling_energy"] > 0.0 and audit["max_coupling_fraction"] > 0.1,
      f"the coupling created {audit['coupling_energy']:.3g} J, {100 * audit['max_coupling_fraction']:.1f} % "
      "of the traffic at most")
for needle in ("health check 'coupling_energy' failed (energy audit)", "the coupling keeps creating energy",
               f"since the warning at step {warned}", "FluidHealth.max_coupling_energy_growth = 3",
               "added-mass instability", "lower SolverOptions.Timeint.substeps from 20 to at most 5"):
    check(needle in reason, f"the diagnosis says '{needle}'")
check("energy audit: the coupling has created energy" in log, "the warning came first, in the log")
check("run completed" not in log, "the log never says completed")
with open(os.path.join(run_dir, "sensors.csv")) as handle:
    check("nan" not in handle.read().lower(), f"no NaN in sensors.csv ({run_json['steps']} steps)")
cleanup(output)
print("PASS")
