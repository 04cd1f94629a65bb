#!/usr/bin/python3
"""Every error reaches the user from any rank (issue 16 item 4), through fsi-run with 2 client
ranks: a LIGGGHTS error raised on rank 1 only (fix wall/region finds particles that only rank 1
owns outside its region: Error::one) and one raised on every rank (an unknown pair style:
Error::all) end both programs non-zero within 10 s of the error, the server's log names LIGGGHTS'
message and the script line, and nothing alarming from mpirun follows (no MPI_ABORT notice, no
ORTE "unpack would read past end of buffer"). A rank that crashes mid-run (SIGSEGV) says so, and
both sides end with a message on the server's side. fix fsi/sph's close-approach warning for a particle that
rank 1 owns is printed. FSI_RANK_ERROR_REPEATS (default 3) repeats the two error cases; the
20-fold run under load is recorded in docs/testing.md."""
import os
import re
import signal
import subprocess
import threading
import time

from fsi_test import ENV, binary, check, cleanup, example, fail, read, sensor_rows, work_dir

SCENE = example("static_tank", "static_tank_coarse.scene")
SHORT = ["--set", "Resolution.equilibration_steps=100", "--set", "Resolution.snapshot_every_steps=0"]
REPEATS = int(os.environ.get("FSI_RANK_ERROR_REPEATS", "3"))
ALARMING = ("MPI_ABORT", "unpack would read past end of buffer", "mpirun detected", "mpirun noticed",
            "Primary job")
output = work_dir("rank_errors")
with open(example("static_tank", "static_tank.in1")) as handle:
    SCRIPT1 = handle.read()
with open(example("static_tank", "static_tank.in2")) as handle:
    SCRIPT2 = handle.read()


def script(name, text):
    path = os.path.join(output, name)
    with open(path, "w") as handle:
        handle.write(text)
    return path


# fsi-client splits the fluid along x at its median (about 0.024 m; docs/user-guide.md "Ranks and
# balance"); the fluid reaches x = 0.0484 m.
RANK1_ONLY = script("rank1_only.in2", SCRIPT2 + """
# Only particles right of x = 0.045 m lie outside this region; only rank 1 owns them.
region      keep block -0.005 0.045 ${ymin} ${ymax} -${zhalf} ${zhalf} units box
fix         stay all wall/region keep harmonic 1.0 1.0 0.0001
""")
EVERY_RANK = script("every_rank.in1", SCRIPT1.replace("sph/artVisc/tensCorr spiky2d", "sph/nonsense spiky2d"))
NEAR_WALL = script("near_wall.in2", SCRIPT2 + """
# The rightmost column moved to 0.6 mm (0.19 r0) from the right wall, which only rank 1 owns.
region      near_right_wall block 0.047 0.06 INF INF INF INF units box
set         region near_right_wall x 0.0494
""")


def fsi_run(name, *extra, strike=None):
    """fsi-run with 2 ranks; returns (exit status, its stderr, seconds from the first LIGGGHTS ERROR
    line (or the strike) to fsi-run's end, the run folder). strike(run_dir) is called once the
    coupled steps run."""
    run_dir = os.path.join(output, name)
    command = [binary("fsi-run"), SCENE, "--np", "2", "--output", run_dir, *SHORT, *extra]
    process = subprocess.Popen(command, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True,
                               env=ENV, start_new_session=True)
    lines, marks = [], {}

    def collect():
        for line in process.stderr:
            lines.append(line)
            if "ERROR" in line and "error" not in marks:
                marks["error"] = time.time()
    reader = threading.Thread(target=collect)
    reader.start()
    if strike:
        deadline = time.time() + 120
        while len(sensor_rows(run_dir)) < 10 and process.poll() is None and time.time() < deadline:
            time.sleep(0.1)
        strike(run_dir)
        marks["error"] = time.time()
    try:
        status = process.wait(timeout=180)
    except subprocess.TimeoutExpired:
        os.killpg(process.pid, signal.SIGKILL)
        fail(f"{name}: fsi-run still runs after 180 s:\n{''.join(lines)[-3000:]}")
    ended = time.time()
    reader.join()
    return status, "".join(lines), ended - marks.get("error", ended), run_dir


def ends_cleanly(name, status, text, seconds, run_dir, needles):
    log = read(run_dir, "fsi-server.log")
    client = re.search(r"fsi-run: fsi-server exited with status (\d+) \(fsi-client: (\d+)\)", text)
    both = status != 0 and client is not None and int(client.group(2)) != 0
    check(both and seconds < 10 and "still running" not in text,
          f"{name}: fsi-server ({status}) and fsi-client ({client.group(2) if client else '?'}) exit non-zero "
          f"{seconds:.2f} s after the error" + ("" if both and seconds < 10 else f":\n{text[-3000:]}"))
    missing = [needle for needle in needles if needle not in log]
    check(not missing, f"{name}: the server's log names {needles}" + (f"; missing {missing}:\n{log[-3000:]}" if missing else ""))
    alarming = [word for word in ALARMING if word in text]
    check(not alarming, f"{name}: nothing alarming follows" + (f": {alarming} in:\n{text[-3000:]}" if alarming else ""))


for repetition in range(1, REPEATS + 1):
    status, text, seconds, run_dir = fsi_run(f"rank1_{repetition}", "--set", f'LIGGGHTS.script2="{RANK1_ONLY}"')
    ends_cleanly(f"rank 1 only ({repetition}/{REPEATS})", status, text, seconds, run_dir,
                 ["ERROR on proc 1: Particle on or inside surface of region used in fix wall/region",
                  "rank1_only.in2:", "on rank 1 of 2"])
    status, text, seconds, run_dir = fsi_run(f"every_{repetition}", "--set", f'LIGGGHTS.script1="{EVERY_RANK}"')
    ends_cleanly(f"every rank ({repetition}/{REPEATS})", status, text, seconds, run_dir,
                 ["ERROR: Invalid pair style", "every_rank.in1:33"])


def kill_rank1(run_dir):
    """SIGSEGV to rank 1 of this run's fsi-client (found by its --log-file): a crash."""
    found = subprocess.run(["pgrep", "-f", f"fsi-client --server .* --log-file {run_dir}/fsi-client.log"],
                           capture_output=True, text=True).stdout.split()
    for pid in found:
        try:
            with open(f"/proc/{pid}/environ", "rb") as handle:
                environment = handle.read().split(b"\0")
        except OSError:
            continue
        if b"OMPI_COMM_WORLD_RANK=1" in environment:
            os.kill(int(pid), signal.SIGSEGV)
            return
    fail(f"rank 1 of the client writing {run_dir}/fsi-client.log not found among {found}")


status, text, seconds, run_dir = fsi_run("crash", "--set", "Resolution.end_time=10", strike=kill_rank1)
ends_cleanly("rank 1 crashed mid-run", status, text, seconds, run_dir,
             ["the MPI job was ended from outside", "another rank crashed or was killed"])
check("fsi-client rank 1 of 2: crashed with signal 11" in text, "the crashed rank says so on stderr")

status, text, seconds, run_dir = fsi_run("near_wall", "--set", f'LIGGGHTS.script2="{NEAR_WALL}"',
                                         "--set", "Resolution.end_time=10*Resolution.time_step")
warned = [line for line in text.splitlines() if "fix fsi/sph: a particle is" in line]
check(status == 0 and any("rank 1]" in line for line in warned) and not any("rank 0]" in line for line in warned),
      f"fix fsi/sph's close-approach warning of rank 1 is printed: {warned[:1]}" + ("" if warned else text[-2000:]))
cleanup(output)
