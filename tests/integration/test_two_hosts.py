#!/usr/bin/python3
"""Server and client on two "hosts": two network namespaces joined by a veth pair (iproute2), so
the connection crosses a real network interface instead of loopback. fsi-server listens in one
namespace on its veth address (with a token, as a non-loopback address requires), `mpirun -np 2
fsi-client` runs in the other; the sensors of the coarse static tank equal those of a loopback
run to 1e-12. Skips (exit 77) with a message only where the kernel or the user may not create
namespaces. The namespaces are deleted even when the test fails."""
import os
import shutil
import signal
import subprocess
import sys
import time

from fsi_test import (ENV, binary, check, cleanup, example, fail, kill_group, load_sensors, manifest, read,
                      start_client, start_server, wait, work_dir)

scene = example("static_tank", "static_tank_coarse.scene")
overrides = ["Resolution.end_time=0.002", "Resolution.equilibration_steps=200"]  # 200 coupled steps
tag = str(os.getpid() % 100000)
ns_server, ns_client = f"fsi_srv_{tag}", f"fsi_cli_{tag}"
veth_server, veth_client = f"fsv{tag}", f"fcv{tag}"
subnet = f"10.251.{os.getpid() % 250}"
server_address, client_address = f"{subnet}.1", f"{subnet}.2"


def ip(*arguments, check_status=True):
    result = subprocess.run(["ip"] + list(arguments), capture_output=True, text=True)
    if check_status and result.returncode != 0:
        raise RuntimeError(f"ip {' '.join(arguments)}: {result.stderr.strip()}")
    return result


def skip(message):
    print(f"SKIP: {message}", flush=True)
    sys.exit(77)


if shutil.which("ip") is None:
    fail("iproute2 ('ip') is not installed; scripts/install-deps installs it")
probe = ip("netns", "add", ns_server, check_status=False)
if probe.returncode != 0:
    skip(f"this kernel or user may not create network namespaces: {probe.stderr.strip()}")

output = work_dir("two_hosts")
processes = []
try:
    ip("netns", "add", ns_client)
    ip("link", "add", veth_server, "type", "veth", "peer", "name", veth_client)
    ip("link", "set", veth_server, "netns", ns_server)
    ip("link", "set", veth_client, "netns", ns_client)
    for namespace, device, address in ((ns_server, veth_server, server_address),
                                       (ns_client, veth_client, client_address)):
        ip("-n", namespace, "addr", "add", f"{address}/24", "dev", device)
        ip("-n", namespace, "link", "set", device, "up")
        ip("-n", namespace, "link", "set", "lo", "up")
    token = os.path.join(output, "token")
    with open(token, "w") as handle:
        handle.write("8d969eef6ecad3c29a3a629280e686cf0c3f5d5a86aff3ca12020c923adc6c92\n")
    os.chmod(token, 0o600)

    # The reference: the same run over loopback.
    loopback = os.path.join(output, "loopback")
    server, port = start_server(scene, loopback, overrides)
    client = start_client(port, 2, loopback)
    processes += [server, client]
    check(wait(server, 600) == 0 and wait(client, 30) == 0, "the loopback run completes")

    # The two-host run.
    remote = os.path.join(output, "two_hosts")
    os.makedirs(remote)
    port_file = os.path.join(remote, "port")
    command = ["ip", "netns", "exec", ns_server, binary("fsi-server"), scene, "--output", remote, "--listen",
               server_address, "--port", "0", "--port-file", port_file, "--token-file", token]
    for item in overrides:
        command += ["--set", item]
    server = subprocess.Popen(command, stdout=open(os.path.join(remote, "server.stderr"), "w"),
                              stderr=subprocess.STDOUT, env=ENV, start_new_session=True)
    processes.append(server)
    deadline = time.time() + 60
    while not (os.path.exists(port_file) and open(port_file).read().strip()):
        if server.poll() is not None or time.time() > deadline:
            fail(f"fsi-server in {ns_server} did not listen:\n{read(remote, 'server.stderr')}")
        time.sleep(0.05)
    port = int(open(port_file).read())
    mpirun = ["mpirun", "--oversubscribe", "-np", "2"] + (["--allow-run-as-root"] if os.geteuid() == 0 else [])
    client = subprocess.Popen(["ip", "netns", "exec", ns_client] + mpirun +
                              [binary("fsi-client"), "--server", f"{server_address}:{port}", "--token-file", token],
                              stdout=open(os.path.join(remote, "client.stderr"), "w"), stderr=subprocess.STDOUT,
                              env=ENV, start_new_session=True)
    processes.append(client)
    server_status = wait(server, 600)
    client_status = wait(client, 30)
    if server_status != 0 or client_status != 0:
        fail(f"two-host run: server {server_status}, client {client_status}\n{read(remote, 'server.stderr')[-3000:]}\n"
             f"{read(remote, 'client.stderr')[-3000:]}")
    log = read(remote, "server.stderr")
    check(f"connected from {client_address}:" in log,
          f"the client connected from the other namespace's address {client_address}")
    check(manifest(remote)["protocol"]["authenticated"] is True, "authenticated with the token")
    reference, measured = load_sensors(loopback), load_sensors(remote)
    check(list(reference) == list(measured) and len(reference["time"]) == len(measured["time"]) > 0,
          f"same sensors and rows ({len(measured['time'])} rows of {len(measured)} columns)")
    worst = 0.0
    for name in reference:
        for a, b in zip(reference[name], measured[name]):
            worst = max(worst, abs(a - b) / max(1.0, abs(a)))
    check(worst <= 1e-12, f"sensors of the two-host run equal the loopback run's: max difference {worst:.3e} <= 1e-12")
finally:
    for process in processes:
        if process.poll() is None:
            kill_group(process)
    for namespace in (ns_server, ns_client):
        ip("netns", "del", namespace, check_status=False)
    left = ip("netns", "list", check_status=False).stdout
    if ns_server in left or ns_client in left:
        print(f"warning: could not delete the namespaces {ns_server}, {ns_client}", flush=True)
cleanup(output)
