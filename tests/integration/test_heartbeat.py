#!/usr/bin/python3
"""Heartbeats (docs/protocol.md, "Waiting"): a client whose coupled step takes longer than the
server's --peer-timeout is not taken for dead, because it sends heartbeats while it computes; a
client that is stopped (SIGSTOP: alive, socket open, silent) in the same long step ends the
server within the timeout."""
import os
import signal
import subprocess
import time

from fsi_test import (ENV, check, cleanup, example, fail, kill_group, manifest, read, start_client,
                      start_server, wait, work_dir)

scene = example("static_tank", "static_tank_coarse.scene")
short_run = ["Resolution.end_time=0.0005", "Resolution.equilibration_steps=50"]  # 50 steps
output = work_dir("heartbeat")
timeout = 2.0


def start(name, slow_step):
    run_dir = os.path.join(output, name)
    server, port = start_server(scene, run_dir, short_run, ["--peer-timeout", str(timeout)])
    ENV["FSI_TEST_SLOW_STEP"] = slow_step  # the client's test hook: this step sleeps
    client = start_client(port, 2, run_dir)
    del ENV["FSI_TEST_SLOW_STEP"]
    return run_dir, server, port, client


# 1. Step 30 takes 5 s, more than twice the server's --peer-timeout of 2 s: the run completes.
run_dir, server, port, client = start("long_step", "30:5")
started = time.time()
status = wait(server, 120)
elapsed = time.time() - started
client_status = wait(client, 30)
for process in (server, client):
    if process.poll() is None:
        kill_group(process)
log = read(run_dir, "server.stderr")
if status != 0:
    fail(f"the run with a 5 s step failed ({status}):\n{log[-3000:]}")
check(status == 0 and client_status == 0, f"a 5 s step with --peer-timeout 2: both exit 0 after {elapsed:.1f} s")
check(elapsed > 5.0, "the slow step really took its 5 s")
check(manifest(run_dir)["steps"] == 50 and "timed out" not in log, "all 50 steps, no timeout")

# 2. The same long step, but the client is stopped in it: the server ends within the timeout.
run_dir, server, port, client = start("stopped_in_long_step", "30:60")
deadline = time.time() + 120
while "test hook: step 30 takes 60 s" not in read(run_dir, "client.stderr"):
    if time.time() > deadline or server.poll() is not None:
        kill_group(server)
        kill_group(client)
        fail(f"the run did not reach step 30:\n{read(run_dir, 'server.stderr')}")
    time.sleep(0.1)
time.sleep(1.5)  # inside the 60 s step now, heartbeats flowing
check(server.poll() is None, "the server still waits 1.5 s into the long step")
pattern = f"fsi-client --server 127.0.0.1:{port}( |$)"
subprocess.run(["pkill", "-STOP", "-f", pattern], check=False)
stopped = time.time()
status = wait(server, 20)
elapsed = time.time() - stopped
subprocess.run(["pkill", "-KILL", "-f", pattern], check=False)
kill_group(client)
log = read(run_dir, "server.stderr")
if status is None:
    kill_group(server)
    fail("fsi-server still runs 20 s after the client was stopped (--peer-timeout 2)")
# Silence starts at the last heartbeat, at most 1.25 intervals (0.625 s) before the stop.
check(status != 0 and elapsed < timeout + 1.5,
      f"server exits non-zero ({status}) {elapsed:.2f} s after the client was stopped (timeout {timeout} s)")
check("timed out after 2 s while waiting for Forces" in log, "the server says it timed out waiting for Forces")
cleanup(output)
