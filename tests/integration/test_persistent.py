#!/usr/bin/python3
"""fsi-client --persistent (thesis §5.4.2 "Finalize"): one client serves two consecutive
fsi-server runs on the same address; each run completes, the second run's sensors equal the
first's bit for bit (a fresh set-up, nothing left over from the first), and the client is still
waiting afterwards."""
import os
import signal
import socket
import subprocess
import time

from fsi_test import (ENV, binary, check, cleanup, example, fail, kill_group, manifest, read, sensor_rows, start_client,
                      wait, work_dir)

scene = example("static_tank", "static_tank_coarse.scene")
short_run = ["--set", "Resolution.end_time=0.0005", "--set", "Resolution.equilibration_steps=50"]
output = work_dir("persistent")

probe = socket.socket()
probe.bind(("127.0.0.1", 0))
port = probe.getsockname()[1]
probe.close()


def run_server(name):
    run_dir = os.path.join(output, name)
    os.makedirs(run_dir)
    log = open(os.path.join(run_dir, "server.stderr"), "w")
    server = subprocess.Popen([binary("fsi-server"), scene, "--output", run_dir, "--port", str(port)] + short_run,
                              stdout=log, stderr=subprocess.STDOUT, env=ENV, start_new_session=True)
    status = wait(server, 180)
    if status is None:
        kill_group(server)
        fail(f"{name}: fsi-server did not finish:\n{read(run_dir, 'server.stderr')}")
    return run_dir, status


client_dir = os.path.join(output, "client")
os.makedirs(client_dir)
client = start_client(port, 2, client_dir, ["--persistent"])
try:
    first, status = run_server("first")
    check(status == 0, f"first run: fsi-server exits 0 ({status})")
    deadline = time.time() + 30
    while "waiting for the next fsi-server" not in read(client_dir, "client.stderr") and time.time() < deadline:
        time.sleep(0.1)
    check(client.poll() is None and "run 1 done; waiting for the next fsi-server" in read(client_dir, "client.stderr"),
          "after the first run the client waits for the next server")
    time.sleep(1.0)  # the client retries meanwhile: nobody listens
    second, status = run_server("second")
    check(status == 0, f"second run, same client: fsi-server exits 0 ({status})")
    check(manifest(first)["steps"] == 50 and manifest(second)["steps"] == 50, "both runs did all 50 steps")
    check(len(sensor_rows(first)) > 0 and sensor_rows(first) == sensor_rows(second),
          f"the second run's {len(sensor_rows(second))} sensor rows equal the first's bit for bit")
    time.sleep(0.5)
    check(client.poll() is None and "run 2 done" in read(client_dir, "client.stderr"),
          "the client still waits after the second run")
finally:
    kill_group(client, signal.SIGTERM)
    if wait(client, 10) is None:
        kill_group(client)
cleanup(output)
