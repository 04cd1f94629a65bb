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
quietly (0.13 % of the traffic at most). The healthy coupled runs of the suite run with this check on.
Then the same light box, k = 20, with an AddedMass block: it runs, and the audit stays quiet."""
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

# The cure (docs/theory.md, "Artificial added mass"): the same light box, the same k = 20, with an
# AddedMass of six times its own mass (about the water's added mass in heave), for twice the time
# the unstable run lasted: it runs to its end, the audit never warns, the box stays near its draft.
added_dir = os.path.join(output, "light_box_k20_added_mass")
os.makedirs(added_dir, exist_ok=True)
wrapper = os.path.join(output, "light_box_added_mass.scene")
with open(wrapper, "w") as handle:
    handle.write('scene_language = 1\ninclude "' + example("floating_box", "floating_box.scene") + '"\n'
                 'AddedMass { body = "box"; ratio = 6 }\n')
command = [binary("fsi-run"), wrapper, "--np", "1", "--output", added_dir]
for item in LIGHT_BOX:
    command += ["--set", item.replace("Resolution.end_time=3.2", "Resolution.end_time=1.6")]
result = subprocess.run(command, env=ENV, capture_output=True, text=True, timeout=600)
log = read(added_dir, "fsi-server.log")
run_json = manifest(added_dir)
if result.returncode != 0:
    print(log[-3000:])
check(result.returncode == 0 and run_json["status"] == "completed",
      f"with AddedMass the light box runs to its end ({run_json['status']}, {run_json['steps']} steps)")
audit = run_json["energy_audit"]
check(audit["injection_warning_step"] is None and audit["max_coupling_fraction"] < 0.05,
      f"the audit never warns: the coupling made {100 * audit['max_coupling_fraction']:.2f} % of the traffic "
      "at most")
with open(os.path.join(added_dir, "sensors.csv")) as handle:
    rows = [line.split(",") for line in handle.read().splitlines()]
column = rows[0].index("box_y")
heave = [float(row[column]) for row in rows[1:]]
start = heave[0]
check(max(abs(y - start) for y in heave) < 0.02,
      f"the box stays within 2 cm of its start (largest {max(abs(y - start) for y in heave):.4f} m)")
cleanup(output)
print("PASS")
