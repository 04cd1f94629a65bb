#!/usr/bin/python3
"""Bad input gets a clear error before anything runs, or ends the run cleanly: a scene error
names file:line:column, an override error suggests the right key, a bad `fix fsi/sph` line and a
LIGGGHTS error in a script reach the server with script name and line."""
import os
import subprocess

from fsi_test import ENV, binary, check, cleanup, example, manifest, read, run_pair, work_dir

scene = example("static_tank", "static_tank_coarse.scene")
output = work_dir("bad_input")


def server(*arguments):
    return subprocess.run([binary("fsi-server"), *arguments], capture_output=True, text=True, env=ENV, timeout=60)


ok = server(scene, "--check")
check(ok.returncode == 0 and "particles" in ok.stdout, "--check accepts the example and summarises it")

# Physics warnings (thesis §6.2 rules of thumb) are listed, all of them, and do not fail --check.
physics = server(scene, "--check", "--set", "Resolution.time_step=3e-5", "--set", "LIGGGHTS_SPH_parameters.cAB=7",
                 "--set", "LIGGGHTS_SPH_parameters.particlespacing=smoothinglength",
                 "--set", "LIGGGHTS_SPH_parameters.SPH_wall_visc=10000", "--set", "FluidRegion.lower=[0.0005, 0.0041]",
                 "--set", "LIGGGHTS_SPH_parameters.gravity=9.8")
listed = [name for name in ("acoustic_time_step", "contact_time_step", "speed_of_sound", "wall_repulsion",
                            "kernel_neighbours", "wall_viscosity", "fluid_overlap", "gravity", "viscosity_match")
          if f"warning ({name})" in physics.stdout]
check(physics.returncode == 0 and len(listed) == 9 and "9 warning(s)" in physics.stdout,
      f"--check lists all 9 physics warnings and exits 0 ({physics.returncode}, {listed})")

bad_scene = os.path.join(output, "bad.scene")
with open(bad_scene, "w") as handle:
    handle.write('scene_language = 1\ninclude "%s"\nOutput.sensor_every_step = 2\n' % example("static_tank", "static_tank_coarse.scene"))
result = server(bad_scene, "--check")
check(result.returncode == 2, f"unknown key: exit status 2 ({result.returncode})")
check("bad.scene:3:1" in result.stderr and "did you mean 'sensor_every_steps'" in result.stderr,
      "unknown key: file:line:column and a suggestion")

# Five different mistakes in one file: --check reports all of them, each at its line:column.
with open(os.path.join(output, "ok.in1"), "w") as handle:
    handle.write("# script 1\n")
five_scene = os.path.join(output, "five.scene")
with open(five_scene, "w") as handle:
    handle.write("""scene_language = 1
SolverOptions { end_time = 1; Timeint { step_size = 1e-5; stages = 4 } }
Output { snapshot_every_step = 10 }
Geometry { a = b; b = a + 1 }
RigidBody2D { name = "lid"; mass = Geometry.c; inertia = [1]; Mesh { points = [[0, 1], [1, 1]] } }
LIGGGHTS { script1 = "ok.in1"; script2 = "nowhere.in2" }
Coupling { refinement_resolution = 0.002 }
""")
result = server(five_scene, "--check")
expected = {"2:59": "'SolverOptions.Timeint.stages' = 4 is out of range",  # value out of range
            "3:10": "did you mean 'snapshot_every_steps'?",               # unknown key
            "4:16": "a cycle Geometry.a -> Geometry.b -> Geometry.a",     # cycle
            "5:36": "has no parameter 'c'",                                # undefined reference
            "5:48": "must be a number, not a vector",                      # wrong type
            "6:32": "nowhere.in2' cannot be read"}                         # missing script
found = {where: any(f"five.scene:{where}:" in line and what in line for line in result.stderr.splitlines())
         for where, what in expected.items()}
check(result.returncode == 2 and all(found.values()) and "6 problem(s)" in result.stderr,
      f"--check reports six different mistakes at once, each at its line:column ({found})\n{result.stderr}")

result = server(scene, "--check", "--set", "Geometry.widht=0.06")
check(result.returncode == 2 and "did you mean 'Geometry.width'" in result.stderr, "bad --set suggests the key")

result = server(scene, "--check", "--set", "SolverOptions.Timeint.step_size=-1")
check(result.returncode == 2 and "out of range" in result.stderr, "a negative step size is out of range")

def run_with_script(name, script_number, text, ranks, overrides=()):
    """A coupled run of the coarse tank whose LIGGGHTS script `script_number` is `text`, written as
    NAME.in1 or NAME.in2; returns both exit statuses, the server's log, and both logs' tails to show
    on failure (a flake of the bad-fix case was seen once in ~12 runs on 2026-11-22 and could not be
    reproduced; the logs say which side misbehaved)."""
    script_path = os.path.join(output, f"{name}.in{script_number}")
    with open(script_path, "w") as handle:
        handle.write(text)
    run_dir = os.path.join(output, name)
    status, client = run_pair(scene, run_dir, ranks,
                              [f'LIGGGHTS.script{script_number}="{script_path}"', *overrides], timeout=120)
    log = read(run_dir, "server.stderr")
    logs = f"\n--- server ---\n{log[-3000:]}\n--- client ---\n{read(run_dir, 'client.stderr')[-3000:]}"
    return status, client, log, logs


with open(example("static_tank", "static_tank.in1")) as handle:
    script = handle.read()
status, client, log, logs = run_with_script(
    "bad_fix", 1, script.replace("cutoff ${SPH_wall_cutoff}", "cutof ${SPH_wall_cutoff}"), 1)
check(status == 1 and client > 0, f"bad fix keyword: server {status}, client {client} (both non-zero)" +
      ("" if status == 1 and client > 0 else logs))
check("unknown keyword 'cutof'" in log and "bad_fix.in1:" in log,
      "bad fix keyword: reported with script and line" + ("" if "bad_fix.in1:" in log else logs))

status, client, log, logs = run_with_script(
    "bad_pair", 1, script.replace("sph/artVisc/tensCorr spiky2d", "sph/nonsense spiky2d"), 2)
check(status == 1 and client > 0, f"LIGGGHTS error: server {status}, client {client} (both non-zero)" +
      ("" if status == 1 and client > 0 else logs))
ok = "Invalid pair style" in log and "bad_pair.in1:" in log
check(ok, "LIGGGHTS' own error message and the script line reach the server" + ("" if ok else logs))
# The client runs text that arrives over the network: `shell` is refused (issue 5, safe commands).
marker = os.path.join(output, "shell_ran")
status, client, log, logs = run_with_script("bad_shell", 1, script + f"\nshell touch {marker}\n", 1)
ok = status == 1 and client > 0 and "command refused: 'shell'" in log and "bad_shell.in1:" in log
check(ok, "a 'shell' command is refused with script and line, both sides non-zero" + ("" if ok else logs))
check(not os.path.exists(marker), "the refused shell command did not run")

# A script that leaves LIGGGHTS without particles: the run fails and says so, instead of
# "completing" with a fluid that weighs nothing.
with open(example("static_tank", "static_tank.in2")) as handle:
    script2 = handle.read()
status, client, log, logs = run_with_script("no_fluid", 2, script2 + "\ndelete_atoms group all\n", 2,
                                            ["Resolution.equilibration_steps=20"])
ok = status == 1 and client > 0 and "LIGGGHTS holds no particle after the set-up" in log
check(ok, "no particle left after the set-up: both sides non-zero, the server says so" + ("" if ok else logs))
check(manifest(os.path.join(output, "no_fluid"))["status"] == "failed", "run.json says failed")
cleanup(output)
