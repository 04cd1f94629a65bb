#!/usr/bin/python3
"""One run.json shape for every run mode, read by one reader (run_manifest.py): a short coupled
run of the coarse static tank, the same scene --mbd-only, a 3D --mbd-only run (its gravity has
three components: [0, 0, -9.81]) and an --mbd-only run that fails after many steps (its Newton
work is recorded, not zero). fsi-plot reads both runs, examples/static_tank/analyze.py the
coupled one."""
import os
import shutil
import subprocess

from fsi_test import ENV, binary, check, cleanup, example, fail, run_pair, work_dir
from run_manifest import read_run_manifest

output = work_dir("run_manifest")
tank = example("static_tank", "static_tank_coarse.scene")


def mbd_only(scene, run_dir, *overrides, expect=0):
    command = [binary("fsi-server"), scene, "--mbd-only", "--output", run_dir]
    for item in overrides:
        command += ["--set", item]
    result = subprocess.run(command, env=ENV, capture_output=True, text=True, timeout=120)
    if result.returncode != expect:
        fail(f"{' '.join(command)} exited {result.returncode}, not {expect}:\n{result.stderr[-3000:]}")
    return read_run_manifest(run_dir)


coupled_dir = os.path.join(output, "coupled")
server, client = run_pair(tank, coupled_dir, 1, ["Resolution.equilibration_steps=200",
                                                 "Resolution.end_time=100*1e-5",
                                                 "Resolution.snapshot_every_steps=50"], timeout=300)
check(server == 0 and client == 0, f"the short coupled run completes (server {server}, client {client})")
coupled = read_run_manifest(coupled_dir)
check(coupled["mode"] == "coupled" and coupled["steps"] == 100, "the reader reads the coupled run.json")
check(coupled["client"]["mpi_ranks"] == 1 and coupled["fluid"]["particle_count"] > 0,
      f"coupled: client and fluid recorded ({coupled['fluid']['particle_count']} particles)")

tank_dir = os.path.join(output, "mbd_only")
alone = mbd_only(tank, tank_dir, "Resolution.end_time=100*1e-5")
check(alone["mode"] == "mbd-only" and alone["steps"] == 100, "the same reader reads the --mbd-only run.json")
check(alone["fluid"] is None and alone["client"] is None and alone["timings_seconds"]["liggghts"] is None,
      "--mbd-only: fluid, client and fluid timings are null, not missing")
check([body["name"] for body in alone["model"]["bodies"]] == [body["name"] for body in coupled["model"]["bodies"]],
      "both modes list the same bodies by name")
check(alone["model"]["gravity"] == [0, -9.81], f"2D gravity: {alone['model']['gravity']}")

spatial = mbd_only(example("hydrostatic_box_3d", "hydrostatic_box_3d_held.scene"),
                   os.path.join(output, "spatial"), "SolverOptions.end_time=20*2.5e-5")
check(spatial["dimension"] == 3 and spatial["model"]["gravity"] == [0, 0, -9.81],
      f"3D --mbd-only records its gravity: {spatial['model']['gravity']}")

# A spring law that turns NaN after about 0.064 s (test_mbd_mechanisms.py): the run fails after
# thousands of steps and must say how much Newton work they took.
bad_dir = os.path.join(output, "bad")
os.makedirs(bad_dir)
for name in ("mbd_mechanisms.scene", "mbd_mechanisms.in"):
    shutil.copy(example("mbd_mechanisms", name), bad_dir)
with open(example("mbd_mechanisms", "mbd_mechanisms.scene")) as handle:
    text = handle.read()
with open(os.path.join(bad_dir, "nan.scene"), "w") as handle:
    handle.write(text + 'NonlinearSpringDamper { name = "brittle"; body_a = "valve"; point_b = [4, 1];'
                        ' tension = "sqrt(0.02 - elongation)" }\n')
failed = mbd_only(os.path.join(bad_dir, "nan.scene"), os.path.join(bad_dir, "run"), expect=1)
check(failed["status"] == "failed" and failed["steps"] > 100, f"the NaN spring fails after {failed['steps']} steps")
check(failed["newton"]["steps"] >= failed["steps"] and failed["newton"]["iterations"] >= failed["steps"],
      f"the failed run records its Newton work: {failed['newton']}")

# (The static tank's declared figure needs the fluid's N m g: fsi-plot refuses it for an
# --mbd-only run of that scene with what/where/how; the 3D --mbd-only run declares no figure.)
for run_dir, mode in ((coupled_dir, "coupled"), (os.path.join(output, "spatial"), "3D --mbd-only")):
    plot = subprocess.run(["/usr/bin/python3", binary("fsi-plot"), run_dir, "--output", os.path.join(run_dir, "plots")],
                          capture_output=True, text=True, timeout=300)
    check(plot.returncode == 0 and os.path.exists(os.path.join(run_dir, "plots", "sensors.png")),
          f"fsi-plot reads the {mode} run (status {plot.returncode}{': ' + plot.stderr[-500:] if plot.returncode else ''})")

analysis = subprocess.run(["/usr/bin/python3", example("static_tank", "analyze.py"), coupled_dir],
                          capture_output=True, text=True, timeout=60)
check("Traceback" not in analysis.stderr, f"examples/static_tank/analyze.py reads the coupled run.json "
      f"(status {analysis.returncode})")
cleanup(output)
print("run manifest: 8 passed, 0 failed")
