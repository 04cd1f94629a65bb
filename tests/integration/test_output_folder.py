#!/usr/bin/python3
"""Results are never overwritten by accident (issue 16 item 6): a second run into a folder that
holds an earlier run's results is refused by fsi-run and by fsi-server, naming the earlier run
(scene, start date, status, steps), and nothing in the folder changes (every file's SHA-256, and
the file list, before and after); --overwrite replaces that run's files and keeps the user's own;
the remains of a run that failed before its first step are replaced without --overwrite."""
import hashlib
import json
import os
import subprocess

from fsi_test import ENV, binary, check, cleanup, example, fail, work_dir

SCENE = example("static_tank", "static_tank_coarse.scene")
SHORT = ["--set", "Resolution.equilibration_steps=100", "--set", "Resolution.snapshot_every_steps=50"]
output = work_dir("output_folder")
run_dir = os.path.join(output, "tank")


def fsi_run(steps, *extra):
    return subprocess.run([binary("fsi-run"), SCENE, "--np", "1", "--output", run_dir, *SHORT,
                           "--set", f"Resolution.end_time={steps}*Resolution.time_step", *extra],
                          capture_output=True, text=True, timeout=300, env=ENV)


def hashes(folder):
    """Every file under the folder (relative path) with the SHA-256 of its content."""
    found = {}
    for root, _, files in os.walk(folder):
        for name in files:
            path = os.path.join(root, name)
            with open(path, "rb") as handle:
                found[os.path.relpath(path, folder)] = hashlib.sha256(handle.read()).hexdigest()
    return found


first = fsi_run(100)
if first.returncode != 0:
    fail(f"the first run exits {first.returncode}:\n{first.stderr[-3000:]}")
with open(os.path.join(run_dir, "run.json")) as handle:
    manifest = json.load(handle)
started = manifest["started_utc"]
check(manifest["status"] == "completed" and manifest["steps"] == 100 and started.endswith("Z"),
      f"the first run: completed, 100 steps, started {started}")
with open(os.path.join(run_dir, "notes.txt"), "w") as handle:
    handle.write("my own notes on this run\n")
before = hashes(run_dir)
check(len(before) >= 10, f"the folder holds {len(before)} files")
earlier_named = ["static_tank_coarse.scene", "started " + started[:10] + " " + started[11:19] + " UTC",
                 "status completed", "100 steps", "--overwrite"]

second = fsi_run(60)
missing = [text for text in earlier_named if text not in second.stderr]
check(second.returncode == 2 and not missing,
      f"fsi-run into the folder is refused (status {second.returncode}), naming the earlier run"
      + (f"; missing {missing} in:\n{second.stderr}" if missing else f":\n{second.stderr.strip()}"))
check(hashes(run_dir) == before, "fsi-run's refusal changed nothing in the folder (file list and SHA-256)")

server = subprocess.run([binary("fsi-server"), SCENE, "--output", run_dir, "--port", "0"],
                        capture_output=True, text=True, timeout=60, env=ENV)
missing = [text for text in earlier_named if text not in server.stderr]
check(server.returncode == 2 and not missing,
      f"fsi-server into the folder is refused (status {server.returncode}), naming the earlier run"
      + (f"; missing {missing} in:\n{server.stderr}" if missing else ""))
mbd_only = subprocess.run([binary("fsi-server"), SCENE, "--mbd-only", "--output", run_dir],
                          capture_output=True, text=True, timeout=60, env=ENV)
check(mbd_only.returncode == 2 and "status completed" in mbd_only.stderr,
      f"fsi-server --mbd-only into the folder is refused too ({mbd_only.returncode})")
check(hashes(run_dir) == before, "fsi-server's refusals changed nothing in the folder")

third = fsi_run(60, "--overwrite")
if third.returncode != 0:
    fail(f"fsi-run --overwrite exits {third.returncode}:\n{third.stderr[-3000:]}")
with open(os.path.join(run_dir, "run.json")) as handle:
    manifest = json.load(handle)
after = hashes(run_dir)
stale = [name for name in after if name.endswith(("_000000100.csv", "_000000100.vtu", "_000000100.vtp"))]
check(manifest["steps"] == 60 and manifest["status"] == "completed" and not stale,
      f"--overwrite replaced the run: 60 steps now, no file of step 100 left ({stale})")
check(after.get("notes.txt") == before["notes.txt"], "--overwrite kept the user's own file")
with open(os.path.join(run_dir, "vtk", "fluid.pvd")) as handle:
    index = handle.read()
check("_000000100" not in index and "_000000050" in index, "the .pvd index lists the new run's files only")

# A run that failed before its first step (here: no client connected within --accept-timeout)
# leaves nothing worth keeping: the next run replaces it without --overwrite.
failed_dir = os.path.join(output, "failed")
never = subprocess.run([binary("fsi-server"), SCENE, "--output", failed_dir, "--accept-timeout", "0.5"],
                       capture_output=True, text=True, timeout=60, env=ENV)
with open(os.path.join(failed_dir, "run.json")) as handle:
    failed = json.load(handle)
check(never.returncode != 0 and failed["status"] == "failed" and failed["steps"] == 0,
      "a run whose client never came: status failed, 0 steps")
again = subprocess.run([binary("fsi-server"), SCENE, "--output", failed_dir, "--accept-timeout", "0.5"],
                       capture_output=True, text=True, timeout=60, env=ENV)
check(again.returncode == 1 and "replaced the files of an earlier run" in again.stderr,
      f"its folder is reused without --overwrite, and the log says so ({again.returncode})")
cleanup(output)
