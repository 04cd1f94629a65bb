#!/usr/bin/python3
"""Files that cannot be written (issue 16 item 5): an output folder on a read-only file system,
and a disk that fills up during the run (a small tmpfs), end the run with a message naming the
file, the system's reason and the fix, a non-zero exit of both programs within seconds, and no
half-written file: run.json parses, sensors.csv holds whole rows, every snapshot is complete,
every .pvd index is valid and names only files that exist, no temporary file is left. With
checkpoints: a disk that fills up after the first checkpoint ends the run clearly, that
checkpoint stays intact, and once there is room again `fsi-run --resume` ends the run byte for
byte like one that never stopped. Needs root to mount the tmpfs; exits 77 (skipped) otherwise."""
import glob
import json
import os
import subprocess
import sys
import time
import xml.etree.ElementTree as ElementTree

from fsi_test import ENV, binary, check, cleanup, example, fail, work_dir

SCENE = example("static_tank", "static_tank_coarse.scene")
SHORT = ["--set", "Resolution.equilibration_steps=100", "--set", "Resolution.snapshot_every_steps=50",
         "--set", "Resolution.end_time=400*Resolution.time_step"]
output = work_dir("output_faults")
mounts = []


def mount(name, options):
    path = os.path.join(output, name)
    os.makedirs(path)
    result = subprocess.run(["mount", "-t", "tmpfs", "-o", options, "tmpfs", path], capture_output=True, text=True)
    if result.returncode != 0:
        print(f"SKIP: cannot mount a tmpfs here ({result.stderr.strip()}); run as root", flush=True)
        cleanup(output)
        sys.exit(77)
    mounts.append(path)
    return path


def fsi_run(run_dir):
    started = time.time()
    result = subprocess.run([binary("fsi-run"), SCENE, "--np", "2", "--output", run_dir, *SHORT],
                            capture_output=True, text=True, timeout=300, env=ENV)
    return result, time.time() - started


try:
    # 1. A read-only folder: refused before the client starts, naming the file and the fix.
    read_only = mount("read_only", "ro,size=64k")
    result, seconds = fsi_run(read_only)
    ok = (result.returncode != 0 and "fsi-server.log: Read-only file system" in result.stderr
          and "writable" in result.stderr and seconds < 30)
    check(ok, f"read-only --output: fsi-run exits {result.returncode} after {seconds:.1f} s naming the file "
              f"and the fix" + ("" if ok else f":\n{result.stderr[-3000:]}"))

    # 2. The disk fills up during the run: each snapshot (CSV and VTK) takes about 0.42 MB, so a
    # 1.2 MB disk is full at the third.
    full = mount("full", "size=1200k")
    run_dir = os.path.join(full, "run")
    result, seconds = fsi_run(run_dir)
    text = result.stderr
    named = [line for line in text.splitlines() if "No space left on device" in line and run_dir in line]
    ok = result.returncode != 0 and named and "free space on the disk" in text
    check(ok, f"full disk: fsi-run exits {result.returncode}, naming the file and the fix: "
              f"{named[0].strip()[:200] if named else text[-3000:]}")
    client = [line for line in text.splitlines() if line.startswith("fsi-run: fsi-server exited with status")]
    ok = client and "(fsi-client: 0)" not in client[0] and "still running" not in text and seconds < 60
    check(ok, f"full disk: both programs end non-zero, the run in {seconds:.1f} s: {client[0] if client else text[-2000:]}")

    # Nothing half-written.
    with open(os.path.join(run_dir, "run.json")) as handle:
        manifest = json.load(handle)
    check(manifest["status"] in ("started", "failed"), f"run.json is whole JSON (status {manifest['status']!r})")
    with open(os.path.join(run_dir, "sensors.csv")) as handle:
        sensors = handle.read()
    lines = [line for line in sensors.split("\n")[:-1] if not line.startswith("#")]
    width = len(lines[0].split(","))
    check(sensors.endswith("\n") and all(len(line.split(",")) == width for line in lines[1:]) and len(lines) > 1,
          f"sensors.csv holds {len(lines) - 1} whole rows of {width} fields")
    snapshots = sorted(glob.glob(os.path.join(run_dir, "snapshots", "particles_*.csv")))
    sizes = set()
    for path in snapshots:
        with open(path) as handle:
            content = handle.read()
        if not content.endswith("\n"):
            fail(f"{path} is cut off")
        sizes.add(content.count("\n"))
    check(snapshots and len(sizes) == 1, f"{len(snapshots)} snapshot(s), each complete ({sizes} lines)")
    for index in glob.glob(os.path.join(run_dir, "vtk", "*.pvd")):
        files = [entry.get("file") for entry in ElementTree.parse(index).getroot().iter("DataSet")]
        missing = [name for name in files if not os.path.exists(os.path.join(run_dir, "vtk", name))]
        if missing:
            fail(f"{index} names files that do not exist: {missing}")
    check(True, "every .pvd index parses and names only files that exist")
    pieces = glob.glob(os.path.join(run_dir, "vtk", "*.vt[up]"))
    for path in pieces:
        with open(path, "rb") as handle:
            if not handle.read().endswith(b"</VTKFile>\n"):
                fail(f"{path} is cut off")
    check(pieces, f"{len(pieces)} VTK files, each complete")
    leftovers = [path for path in glob.glob(os.path.join(run_dir, "**", "*.tmp"), recursive=True)]
    check(not leftovers, f"no temporary file is left ({leftovers})")

    # 3. Checkpoints on a disk that fills up after the first one (the client's test hook holds
    # step 60 for 20 s; the test fills the disk meanwhile), then room again and a resume.
    plate = example("elastic_plate", "elastic_plate_coarse.scene")
    plate_set = []
    for item in ("Resolution.equilibration_steps=500", "Resolution.end_time=160*Resolution.time_step",
                 "Output.checkpoint_every_steps=40", "Output.snapshot_every_steps=160"):
        plate_set += ["--set", item]

    def plate_run(run_dir, how="--output", env=None):
        return subprocess.Popen([binary("fsi-run"), plate, "--np", "1", how, run_dir, *plate_set],
                                stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                                env=env or ENV, start_new_session=True)

    whole_dir = os.path.join(output, "whole")
    whole = plate_run(whole_dir)
    whole_text, _ = whole.communicate(timeout=300)
    check(whole.returncode == 0, "the plate's whole run completes" + ("" if whole.returncode == 0 else whole_text[-3000:]))
    disk = mount("checkpoints", "size=8m")
    run_dir = os.path.join(disk, "run")
    first = plate_run(run_dir, env=dict(ENV, FSI_TEST_SLOW_STEP="60:20"))
    deadline = time.time() + 120
    while not os.path.isdir(os.path.join(run_dir, "checkpoints", "step-000000040")):
        if time.time() > deadline or first.poll() is not None:
            fail("the checkpoint of step 40 did not appear")
        time.sleep(0.05)
    # All but 48 kB: the sensor rows still fit, the checkpoint of step 80 (0.16 MB) does not.
    filler = os.path.join(disk, "filler")
    free = os.statvfs(disk).f_bavail * os.statvfs(disk).f_frsize
    with open(filler, "wb") as handle:
        handle.write(b"\0" * max(0, free - 48 * 1024))
    text, _ = first.communicate(timeout=120)
    named = [line for line in text.splitlines() if "No space left on device" in line]
    ok = (first.returncode != 0 and named and "checkpoint of step 80" in text and "free space on the disk" in text
          and "the checkpoint of step 40 is intact" in text)
    check(ok, f"checkpoints on a full disk: the run ends ({first.returncode}) naming the checkpoint, the file, the fix "
              f"and the intact checkpoint: {named[0].strip()[:300] if ok else text[-3000:]}")
    kept = sorted(os.listdir(os.path.join(run_dir, "checkpoints")))
    check(kept == ["step-000000040"], f"the checkpoint of step 40 is kept whole, the failed one removed ({kept})")
    os.remove(filler)
    again = plate_run(run_dir, how="--resume")
    text, _ = again.communicate(timeout=300)
    check(again.returncode == 0 and "resuming from" in text,
          f"with room again, --resume completes the run ({again.returncode})" + ("" if again.returncode == 0 else text[-3000:]))
    for name in ("sensors.csv", "energy.csv", os.path.join("snapshots", "particles_000000160.csv")):
        with open(os.path.join(run_dir, name), "rb") as a, open(os.path.join(whole_dir, name), "rb") as b:
            check(a.read() == b.read(), f"resumed after a full disk: {name} equals the whole run's byte for byte")
finally:
    for path in mounts:
        subprocess.run(["umount", path], check=False)
cleanup(output)
