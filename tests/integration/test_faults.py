#!/usr/bin/python3
"""Faults end both sides cleanly: a killed client ends the server within 10 s with a clear
message and non-zero status, and the other way round; a peer of another protocol major version
is refused with a message naming both versions, by the server and by the client."""
import json
import os
import signal
import subprocess
import time

from fsi_test import (ENV, binary, check, cleanup, example, fail, kill_group, read, sensor_rows, start_client,
                      start_server, wait, wait_for_exit, work_dir)

scene = example("static_tank", "static_tank_coarse.scene")
long_run = ["Resolution.end_time=10", "Resolution.equilibration_steps=100"]
output = work_dir("faults")


ports = {}


def signal_client_ranks(run_dir, sig):
    """mpirun starts the ranks outside its process group: signal the fsi-client processes."""
    subprocess.run(["pkill", f"-{int(sig)}", "-f", f"fsi-client --server 127.0.0.1:{ports[run_dir]}( |$)"],
                   check=False)


def start_running_pair(name, server_extra=(), client_extra=()):
    run_dir = os.path.join(output, name)
    server, port = start_server(scene, run_dir, long_run, server_extra)
    ports[run_dir] = port
    client = start_client(port, 2, run_dir, client_extra)
    deadline = time.time() + 300
    while len(sensor_rows(run_dir)) < 200:
        if time.time() > deadline or server.poll() is not None or client.poll() is not None:
            fail(f"{name}: the coupled run did not start:\n{read(run_dir, 'server.stderr')}\n{read(run_dir, 'client.stderr')}")
        time.sleep(0.2)
    return run_dir, server, client


def fault_case(name, fault, survivor, seconds, what_happened, server_extra=(), client_extra=()):
    """Starts a coupled run `name`, strikes it with `fault(run_dir, server, client)` and waits up to
    `seconds` for the `survivor` ("server" or "client") to end; afterwards nothing of the pair is
    left running, stopped or not. Returns (run_dir, the survivor's status, the seconds it took to
    end, its log)."""
    run_dir, server, client = start_running_pair(name, server_extra, client_extra)
    fault(run_dir, server, client)
    try:
        status, elapsed = wait_for_exit(server if survivor == "server" else client, seconds,
                                        f"fsi-{survivor} still runs {seconds} s after {what_happened}")
    finally:
        signal_client_ranks(run_dir, signal.SIGKILL)
        kill_group(client, signal.SIGKILL)
        kill_group(server, signal.SIGKILL)
    return run_dir, status, elapsed, read(run_dir, f"{survivor}.stderr")


# 1. The client dies mid-run.
run_dir, status, elapsed, log = fault_case("kill_client", lambda run_dir, server, client: kill_group(client),
                                           "server", 10, "the client was killed")
check(status > 0, f"server exits non-zero without crashing ({status}) {elapsed:.2f} s after the client was killed")
check("connection closed by peer" in log, "server says the connection was closed by the client")
check('"status": "failed"' in read(run_dir, "run.json"), "run.json records the failure")
manifest = json.loads(read(run_dir, "run.json"))
check("connection" in manifest.get("reason", ""), f"run.json says why: {manifest.get('reason', '')[:120]}")
# The sensors written before the crash stay readable: a header, then complete numeric rows with
# strictly increasing times (flushed every second, so at most the last second can be missing).
text = read(run_dir, "sensors.csv")
lines = [line for line in text.splitlines() if line and not line.startswith("#")]
header = lines[0].split(",")
rows = []
for number, line in enumerate(lines[1:], start=2):
    fields = line.split(",")
    if len(fields) != len(header):
        fail(f"sensors.csv line {number} after the crash has {len(fields)} fields, the header {len(header)}")
    rows.append([float(field) for field in fields])
times = [row[0] for row in rows]
check(len(rows) >= 200 and all(b > a for a, b in zip(times, times[1:])),
      f"sensors.csv after kill -9 of the client: {len(rows)} complete rows up to t = {times[-1]:.5f} s")

# 2. The server dies mid-run.
run_dir, status, elapsed, log = fault_case("kill_server", lambda run_dir, server, client: kill_group(server),
                                           "client", 10, "the server was killed")
check(status > 0, f"client exits non-zero without crashing ({status}) {elapsed:.2f} s after the server was killed")
check("connection closed by peer" in log, "client says the connection was closed by the server")

# 2b. A hung client (stopped with SIGSTOP: alive, socket open, silent) ends the server after its
# --peer-timeout, and a hung server ends the client after the client's --peer-timeout.
run_dir, status, elapsed, log = fault_case(
    "hang_client", lambda run_dir, server, client: signal_client_ranks(run_dir, signal.SIGSTOP),
    "server", 15, "the client stopped answering (--peer-timeout 3)", server_extra=["--peer-timeout", "3"])
check(status > 0 and elapsed < 10, f"server exits non-zero ({status}) {elapsed:.2f} s after the client hung (timeout 3 s)")
check("timed out" in log, "the server says it timed out waiting for the client")

run_dir, status, elapsed, log = fault_case(
    "hang_server", lambda run_dir, server, client: kill_group(server, signal.SIGSTOP),
    "client", 15, "the server stopped answering (--peer-timeout 3)", client_extra=["--peer-timeout", "3"])
check(status > 0 and elapsed < 10, f"client exits non-zero ({status}) {elapsed:.2f} s after the server hung (timeout 3 s)")
check("timed out" in log, "the client says it timed out waiting for the server")

# 3. A client speaking protocol 2.0 is refused by the server.
run_dir = os.path.join(output, "client_version")
server, port = start_server(scene, run_dir)
fake = subprocess.run([binary("fake_peer"), "client", "127.0.0.1", str(port), "2"], capture_output=True,
                      text=True, timeout=30, env=ENV)
status = wait(server, 10)
log = read(run_dir, "server.stderr")
check(fake.returncode == 1 and "server refused" in fake.stdout, f"fake client refused: {fake.stdout.strip()}")
check("protocol 2.0" in fake.stdout and "this fsi-server speaks 1." in fake.stdout, "the refusal names both versions")
check(status is not None and status > 0, f"server exits non-zero without crashing ({status})")
check("protocol 2.0" in log and "this fsi-server speaks 1." in log, "the server's message names both versions")

# 4. A server speaking protocol 2.0 is refused by the client.
run_dir = os.path.join(output, "server_version")
os.makedirs(run_dir)
port_file = os.path.join(run_dir, "port")
fake_server = subprocess.Popen([binary("fake_peer"), "server", port_file, "2"], stdout=subprocess.PIPE,
                               stderr=subprocess.STDOUT, text=True, env=ENV)
deadline = time.time() + 20
while not os.path.exists(port_file) and time.time() < deadline:
    time.sleep(0.05)
port = int(open(port_file).read())
client = start_client(port, 1, run_dir)
status, _ = wait_for_exit(client, 10, "fsi-client still runs 10 s after meeting a protocol 2.0 server")
log = read(run_dir, "client.stderr")
check(status > 0, f"client exits non-zero without crashing ({status})")
check("protocol 2.0" in log and "this side speaks 1." in log, "the client's message names both versions")
fake_server.wait(timeout=30)
cleanup(output)
