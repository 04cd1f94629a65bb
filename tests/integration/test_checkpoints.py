#!/usr/bin/python3
"""Coupled checkpoints and resume (issue 16) on the coarse elastic plate, a flexible ANCF plate
moving in LIGGGHTS' SPH water, 200 steps with a checkpoint every 40 (and once on the coarse
static tank, whose piston is prescribed):

- bitwise continuation: a run killed mid-way and resumed (`fsi-run --resume DIR`, on 1 rank
  without the scene and its --set, which come from the run's run.json) ends with the
  sensors.csv, energy.csv and particle snapshot of the run that never stopped, byte for byte,
  on 1 and on 2 ranks; the server killed (-9) in one case, the client in the other;
- a server with --reconnect-timeout outlives its client (kill -9): it goes back to the newest
  checkpoint and the client started again with the same command line continues byte for byte;
- a checkpoint whose writing is killed (-9 in the middle of it) is never used: the resume takes
  the one before and still ends byte for byte like the whole run;
- a resume on 1 rank from the checkpoint of a 2-rank run agrees with the 2-rank run to 1e-10 of
  each sensor's scale over the 120 steps after it (the summation order only);
- a checkpoint does not change the run: the whole run with checkpoints agrees with one without
  to 1e-10 of each sensor's scale and of the largest particle speed (the summation order only);
- a resume of a folder without a complete checkpoint is refused, naming the folder, and leaves
  its files as they were."""
import hashlib
import json
import os
import signal
import subprocess
import time

from fsi_test import ENV, binary, check, cleanup, example, fail, kill_group, load_sensors, read, work_dir

scene = example("elastic_plate", "elastic_plate_coarse.scene")
overrides = ["Resolution.equilibration_steps=500", "Resolution.end_time=200*Resolution.time_step",
             "Output.checkpoint_every_steps=40", "Output.snapshot_every_steps=100"]
COMPARED = ["sensors.csv", "energy.csv", os.path.join("snapshots", "particles_000000200.csv")]
work = work_dir("checkpoints")


def fsi_run(run_dir, ranks, resume=False, env_extra=None, run_scene=None, run_overrides=None,
            bare=False):
    """fsi-run of the scene with its --set; `bare`: `fsi-run --np N --resume DIR` alone (the
    scene and its --set from the run's run.json)."""
    command = [binary("fsi-run")] + ([] if bare else [run_scene or scene]) + \
        ["--np", str(ranks), "--resume" if resume else "--output", run_dir]
    for item in [] if bare else run_overrides or overrides:
        command += ["--set", item]
    env = dict(ENV)
    env.update(env_extra or {})
    log = open(run_dir + (".resume" if resume else "") + ".log", "w")
    return subprocess.Popen(command, stdout=log, stderr=subprocess.STDOUT, env=env,
                            start_new_session=True)


def finish(process, what, timeout=300):
    try:
        status = process.wait(timeout=timeout)
    except subprocess.TimeoutExpired:
        kill_group(process)
        fail(f"{what} did not end within {timeout} s")
    return status


def wait_for(path, process, what, timeout=120):
    deadline = time.time() + timeout
    while not os.path.exists(path):
        if process.poll() is not None:
            fail(f"{what}: the run ended ({process.returncode}) before {path} appeared")
        if time.time() > deadline:
            kill_group(process)
            fail(f"{what}: {path} did not appear within {timeout} s")
        time.sleep(0.05)


def pid_of(pattern):
    found = subprocess.run(["pgrep", "-f", pattern], capture_output=True, text=True).stdout.split()
    return int(found[0]) if found else None


def kill_program(program, run_dir):
    """kill -9 of this run's fsi-server, or of its fsi-client rank 0 (not mpirun)."""
    pid = pid_of(f"^{binary(program)} .*{run_dir}")
    check(pid is not None, f"{program} of {os.path.basename(run_dir)} found to kill")
    os.kill(pid, signal.SIGKILL)


def check_logged(condition, message, log):
    """check(), with the end of the run's log when it fails."""
    if not condition:
        fail(f"{message}\n{log[-3000:]}")
    check(True, message)


def same_files(a, b):
    return {name: open(os.path.join(a, name), "rb").read() == open(os.path.join(b, name), "rb").read()
            for name in COMPARED}


def folder_hashes(folder):
    hashes = {}
    for root, _, files in os.walk(folder):
        for name in files:
            path = os.path.join(root, name)
            with open(path, "rb") as handle:
                hashes[os.path.relpath(path, folder)] = hashlib.sha256(handle.read()).hexdigest()
    return hashes


whole = {}
for ranks in (1, 2):
    run_dir = os.path.join(work, f"whole{ranks}")
    status = finish(fsi_run(run_dir, ranks), f"the whole run on {ranks} rank(s)")
    check_logged(status == 0, f"the whole run on {ranks} rank(s) completes ({status})",
                 read(work, f"whole{ranks}.log"))
    whole[ranks] = run_dir
    check(sorted(os.listdir(os.path.join(run_dir, "checkpoints"))) == ["step-000000120", "step-000000160"],
          f"{ranks} rank(s): the newest two checkpoints are kept ({os.listdir(os.path.join(run_dir, 'checkpoints'))})")

# A checkpoint is also a restart point of the running programs (the client restores itself from
# its bytes and carries the last step's forces and density rates through the set-up): the run
# must not feel it beyond the summation order.
plain_dir = os.path.join(work, "plain")
plain = subprocess.Popen([binary("fsi-run"), scene, "--np", "1", "--output", plain_dir,
                          *sum((["--set", item] for item in overrides), []),
                          "--set", "Output.checkpoint_every_steps=0", "--set", "Output.checkpoint_every_seconds=0"],
                         stdout=open(plain_dir + ".log", "w"), stderr=subprocess.STDOUT, env=ENV,
                         start_new_session=True)
check_logged(finish(plain, "the run without checkpoints") == 0, "the run without checkpoints completes",
             read(work, "plain.log"))
check(not os.path.exists(os.path.join(plain_dir, "checkpoints")), "the run without checkpoints wrote none")
with_them, without = load_sensors(whole[1]), load_sensors(plain_dir)
worst = max(max(abs(a - b) for a, b in zip(with_them[name], without[name])) / (max(abs(v) for v in without[name]) or 1.0)
            for name in without)


def particles(run_dir):
    with open(os.path.join(run_dir, "snapshots", "particles_000000200.csv")) as handle:
        rows = [line.strip().split(",") for line in handle if not line.startswith("#")][1:]
    return {int(row[0]): [float(value) for value in row[1:]] for row in rows}


a, b = particles(whole[1]), particles(plain_dir)
speed = max(max(abs(values[2]), abs(values[3])) for values in b.values())
moved = max(max(abs(a[key][2] - b[key][2]), abs(a[key][3] - b[key][3])) for key in b) / speed
check(worst <= 1e-10 and moved <= 1e-10,
      f"checkpoints do not change the run: sensors within {worst:.1e} of their scale, particle velocities "
      f"within {moved:.1e} of the largest speed (<= 1e-10)")

# Killed mid-way (step 100 takes 20 s by the client's test hook, the checkpoint of step 80 is
# written by then): the server on 1 rank, the client on 2 ranks; then resumed.
for ranks, victim in ((1, "fsi-server"), (2, "fsi-client")):
    run_dir = os.path.join(work, f"killed{ranks}")
    first = fsi_run(run_dir, ranks, env_extra={"FSI_TEST_SLOW_STEP": "100:20"})
    wait_for(os.path.join(run_dir, "checkpoints", "step-000000080"), first, f"{ranks} rank(s)")
    time.sleep(0.5)
    killed_at = time.time()
    kill_program(victim, run_dir)
    status = finish(first, "the killed run", timeout=60)
    ended = time.time() - killed_at
    # A client asleep in the test hook cannot notice a dead server before fsi-run ends it after
    # its 10-s grace; a dead client is noticed at once.
    check(status != 0 and ended < 25,
          f"{ranks} rank(s): kill -9 of the {victim} ends the run non-zero ({status}) in {ended:.1f} s (< 25 s)")
    # On 1 rank as a user would type it: `fsi-run --np 1 --resume DIR`, nothing else.
    status = finish(fsi_run(run_dir, ranks, resume=True, bare=ranks == 1), "the resumed run")
    log = read(work, f"killed{ranks}.resume.log")
    check_logged(status == 0, f"{ranks} rank(s): the resumed run completes ({status})", log)
    check("resuming from" in log and "step-000000080" in log, f"{ranks} rank(s): it resumed from step 80")
    for name, same in same_files(whole[ranks], run_dir).items():
        check(same, f"{ranks} rank(s), {victim} killed at step 100 and resumed: {name} equals the whole run's byte for byte")
    with open(os.path.join(run_dir, "run.json")) as handle:
        manifest = json.load(handle)
    check(manifest["status"] == "completed" and manifest["steps"] == 200 and len(manifest["resumes"]) == 1
          and manifest["resumes"][0]["step"] == 80,
          f"{ranks} rank(s): run.json records the completed run and its resume from step 80 "
          f"({manifest['status']}, {manifest['steps']}, {manifest['resumes']})")

# --reconnect-timeout: the client killed at step 100 (-9), the server waits, goes back to the
# checkpoint of step 80, and the client started again with the same command line finishes the run.
run_dir = os.path.join(work, "reconnected")
os.makedirs(run_dir)
port_file = os.path.join(work, "reconnected.port")
command = [binary("fsi-server"), scene, "--output", run_dir, "--port", "0", "--port-file", port_file,
           "--reconnect-timeout", "60"]
for item in overrides:
    command += ["--set", item]
server = subprocess.Popen(command, stdout=open(run_dir + ".server.log", "w"), stderr=subprocess.STDOUT,
                          env=ENV, start_new_session=True)
wait_for(port_file, server, "the server's port")
time.sleep(0.2)
with open(port_file) as handle:
    port = handle.read().strip()
client_command = ["mpirun", "--oversubscribe", "-np", "1"] + (["--allow-run-as-root"] if os.geteuid() == 0 else []) + \
    [binary("fsi-client"), "--server", f"127.0.0.1:{port}", "--log-file", os.path.join(run_dir, "fsi-client.log")]
first = subprocess.Popen(client_command, stdout=open(run_dir + ".client1.log", "w"), stderr=subprocess.STDOUT,
                         env=dict(ENV, FSI_TEST_SLOW_STEP="100:20"), start_new_session=True)
wait_for(os.path.join(run_dir, "checkpoints", "step-000000080"), server, "reconnect")
time.sleep(0.5)
kill_program("fsi-client", run_dir)
finish(first, "the killed client", timeout=60)
again = subprocess.Popen(client_command, stdout=open(run_dir + ".client2.log", "w"), stderr=subprocess.STDOUT,
                         env=ENV, start_new_session=True)
status = finish(server, "the server waiting for its client again")
client_status = finish(again, "the client started again", timeout=60)
log = read(work, "reconnected.server.log")
check_logged(status == 0 and client_status == 0 and "the fluid side is gone" in log,
             f"the server outlives its client and completes with the one started again ({status}, {client_status})", log)
for name, same in same_files(whole[1], run_dir).items():
    check(same, f"client killed and started again (--reconnect-timeout): {name} equals the whole run's byte for byte")

# Killed while writing the checkpoint of step 120 (the server waits 20 s between its files by its
# test hook): that checkpoint stays partial and is passed over; the resume takes step 80's.
run_dir = os.path.join(work, "killed_writing")
first = fsi_run(run_dir, 1, env_extra={"FSI_TEST_SLOW_CHECKPOINT": "120:20"})
partial = os.path.join(run_dir, "checkpoints", "step-000000120.partial", "server.state")
wait_for(partial, first, "the checkpoint of step 120")
kill_program("fsi-server", run_dir)
finish(first, "the run killed while writing a checkpoint", timeout=60)
check(not os.path.exists(os.path.join(run_dir, "checkpoints", "step-000000120")),
      "the checkpoint killed while being written is not complete")
status = finish(fsi_run(run_dir, 1, resume=True), "the resume after a kill during a checkpoint")
log = read(work, "killed_writing.resume.log")
check_logged(status == 0 and "step-000000120.partial: unfinished" in log and "step-000000080" in log,
             f"the resume passes over the unfinished checkpoint and takes step 80's ({status})", log)
for name, same in same_files(whole[1], run_dir).items():
    check(same, f"killed while writing a checkpoint, resumed from the one before: {name} equals the whole run's")

# A resume on 1 rank from a 2-rank run's checkpoint.
run_dir = os.path.join(work, "ranks_changed")
first = fsi_run(run_dir, 2, env_extra={"FSI_TEST_SLOW_STEP": "100:20"})
wait_for(os.path.join(run_dir, "checkpoints", "step-000000080"), first, "2 -> 1 ranks")
time.sleep(0.5)
kill_program("fsi-server", run_dir)
finish(first, "the 2-rank run", timeout=60)
status = finish(fsi_run(run_dir, 1, resume=True), "the resume on 1 rank")
check_logged(status == 0, f"the resume on 1 rank of a 2-rank run completes ({status})",
             read(work, "ranks_changed.resume.log"))
one, two = load_sensors(run_dir), load_sensors(whole[2])
worst = 0.0
for name in two:
    scale = max(abs(v) for v in two[name]) or 1.0
    worst = max(worst, max(abs(a - b) for a, b in zip(one[name], two[name])) / scale)
check(len(one["time"]) == len(two["time"]) and worst <= 1e-10,
      f"resumed on 1 rank from a 2-rank checkpoint: {len(one['time'])} rows, the sensors differ from the "
      f"2-rank run by {worst:.1e} of their scale (<= 1e-10)")

# The static tank (its piston prescribed, the water at rest), 1 rank: killed at step 150 after the
# checkpoint of step 100, resumed, byte for byte.
tank = example("static_tank", "static_tank_coarse.scene")
tank_set = ["Resolution.equilibration_steps=500", "Resolution.end_time=300*Resolution.time_step",
            "Resolution.snapshot_every_steps=300", "Output.checkpoint_every_steps=100"]
tank_whole = os.path.join(work, "tank_whole")
status = finish(fsi_run(tank_whole, 1, run_scene=tank, run_overrides=tank_set), "the static tank's whole run")
check_logged(status == 0, f"the static tank's whole run completes ({status})", read(work, "tank_whole.log"))
run_dir = os.path.join(work, "tank_killed")
first = fsi_run(run_dir, 1, env_extra={"FSI_TEST_SLOW_STEP": "150:20"}, run_scene=tank, run_overrides=tank_set)
wait_for(os.path.join(run_dir, "checkpoints", "step-000000100"), first, "the static tank")
time.sleep(0.5)
kill_program("fsi-server", run_dir)
finish(first, "the killed static tank", timeout=60)
status = finish(fsi_run(run_dir, 1, resume=True, run_scene=tank, run_overrides=tank_set), "the resumed static tank")
check_logged(status == 0, f"the static tank resumes and completes ({status})", read(work, "tank_killed.resume.log"))
for name in ("sensors.csv", "energy.csv", os.path.join("snapshots", "particles_000000300.csv")):
    with open(os.path.join(run_dir, name), "rb") as a, open(os.path.join(tank_whole, name), "rb") as b:
        check(a.read() == b.read(), f"static tank killed at step 150 and resumed: {name} equals the whole run's byte for byte")

# A folder without a complete checkpoint: refused by name, nothing changed.
run_dir = os.path.join(work, "no_checkpoint")
first = fsi_run(run_dir, 1, env_extra={"FSI_TEST_SLOW_STEP": "20:20"})
wait_for(os.path.join(run_dir, "sensors.csv"), first, "a run without checkpoints")
time.sleep(1.0)
kill_program("fsi-server", run_dir)
finish(first, "the run killed before its first checkpoint", timeout=60)
before = folder_hashes(run_dir)
status = finish(fsi_run(run_dir, 1, resume=True), "the refused resume", timeout=120)
log = read(work, "no_checkpoint.resume.log")
check_logged(status != 0 and "no complete checkpoint in" in log and os.path.join(run_dir, "checkpoints") in log
             and "the run in" in log and "is as it was" in log,
             f"a resume without a checkpoint is refused, naming the folder and that nothing changed ({status})", log)
after = folder_hashes(run_dir)
# Only the logs grow (a resume appends to them) and the launcher's port file is rewritten.
changed = sorted(name for name in set(before) | set(after)
                 if before.get(name) != after.get(name) and not name.endswith(".log") and name != "server.port")
check(not changed, f"the refused resume changed no result file ({changed})")
cleanup(work)
