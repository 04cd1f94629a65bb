#!/usr/bin/python3
"""The README's two-host commands, run as written on two "hosts": two network namespaces joined by
a veth pair (iproute2), so the connection crosses a real network interface instead of loopback.

The commands are read from the fenced block after the README's marker comment (the user guide's
"Server and client on two hosts" block must be the same). Each comment line of the block says
where the commands below it run: "# once" and "# host A" in the server's namespace, "# host B" in
the client's. Only these placeholders are replaced, and each must appear in the block:
  hostA                                   the server namespace's address
  examples/static_tank/static_tank.scene  the coarse static tank shortened to 200 + 200 steps (a
                                          copy of the example with two values of its coarse scene
                                          changed)
`~` is the test's own folder (HOME) and the programs come from the build (PATH); the namespaces
share the file system, so the token made "once" is already on both hosts. The client must connect
from the other namespace's address, authenticate with the token, and its sensors must equal those
of the same run over loopback to 1e-12. Skips (exit 77) with a message only where the kernel or
the user may not create namespaces. The namespaces are deleted even when the test fails."""
import os
import re
import shutil
import subprocess
import sys

from fsi_test import (BIN, ENV, check, cleanup, example, fail, kill_group, load_sensors, manifest, start_client,
                      start_server, wait, work_dir)

ROOT = os.path.abspath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
MARKER = "<!-- two-host commands: tests/integration/test_two_hosts.py runs this block as written -->"
tag = str(os.getpid() % 100000)
ns_server, ns_client = f"fsi_srv_{tag}", f"fsi_cli_{tag}"
veth_server, veth_client = f"fsv{tag}", f"fcv{tag}"
subnet = f"10.251.{os.getpid() % 250}"
server_address, client_address = f"{subnet}.1", f"{subnet}.2"
# Which namespace runs the commands after a comment that starts so.
HOSTS = {"# once": ns_server, "# host A": ns_server, "# host B": ns_client}


def fenced_block(text, after, source):
    """The lines of the first ```sh block after `after`, continuation lines joined."""
    start = text.find(after)
    if start < 0:
        fail(f"{source} has no '{after}'")
    match = re.compile(r"```sh\n(.*?)```", re.S).search(text, start)
    if match is None:
        fail(f"{source}: no ```sh block after '{after}'")
    return match.group(1).replace("\\\n", " ").splitlines()


def readme_steps(substitutions):
    """(namespace, command, comment) for each command of the README block, placeholders replaced."""
    readme = fenced_block(open(os.path.join(ROOT, "README.md")).read(), MARKER, "README.md")
    guide = fenced_block(open(os.path.join(ROOT, "docs", "user-guide.md")).read(),
                         "## Server and client on two hosts", "docs/user-guide.md")
    check(readme == guide, "the README's two-host commands are the user guide's")
    text = "\n".join(readme)
    for placeholder in substitutions:
        if placeholder not in text:
            fail(f"the README's two-host block no longer contains '{placeholder}'; update this test's "
                 f"placeholders to what the README says")
    steps, namespace, comment = [], None, None
    for line in readme:
        line = " ".join(line.split())
        if not line:
            continue
        if line.startswith("#"):
            namespace = next((ns for prefix, ns in HOSTS.items() if line.startswith(prefix)), None)
            if namespace is None:
                fail(f"README two-host block: '{line}' does not say where to run (one of {list(HOSTS)})")
            comment = line
            continue
        if namespace is None:
            fail(f"README two-host block: '{line}' comes before any comment saying where to run it")
        for placeholder, value in substitutions.items():
            line = line.replace(placeholder, value)
        steps.append((namespace, line, comment))
    return steps


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

    # 200 equilibration and 200 coupled steps of the coarse tank instead of the full example: a copy
    # of the example's folder with these two values of its coarse scene changed.
    tank = os.path.join(output, "static_tank")
    shutil.copytree(example("static_tank"), tank)
    scene = os.path.join(tank, "static_tank_coarse.scene")
    text = open(scene).read()
    for key, value in (("end_time", "0.002"), ("equilibration_steps", "200")):
        text, count = re.subn(rf"^(\s*{key}\s*=\s*)\S+", rf"\g<1>{value}", text, flags=re.M)
        check(count == 1, f"{scene} sets {key} once")
    with open(scene, "w") as handle:
        handle.write(text)
    substitutions = {"hostA": server_address, "examples/static_tank/static_tank.scene": scene}
    steps = readme_steps(substitutions)
    # The reference runs as many ranks as the README's client.
    ranks = re.search(r"mpirun -np (\d+) ", "\n".join(command for _, command, _ in steps))
    check(ranks is not None, "the README starts the client with mpirun -np N")
    ranks = int(ranks.group(1))

    # The reference: the same scene and ranks over loopback.
    loopback = os.path.join(output, "loopback")
    server, port = start_server(scene, loopback)
    client = start_client(port, ranks, loopback)
    processes += [server, client]
    check(wait(server, 600) == 0 and wait(client, 30) == 0, "the loopback run completes")

    # The README's commands, each in its namespace from the folder `hosts`, whose out/tank receives
    # the results. "# once" commands run to completion; the server and the client run together.
    hosts = os.path.join(output, "hosts")
    os.makedirs(hosts)
    env = dict(ENV, HOME=hosts, PATH=BIN + os.pathsep + ENV.get("PATH", ""))
    started = []
    for number, (namespace, command, comment) in enumerate(steps):
        log_path = os.path.join(hosts, f"step{number}.log")
        print(f"[{namespace}] {command}", flush=True)
        process = subprocess.Popen(["ip", "netns", "exec", namespace, "bash", "-c", command], cwd=hosts, env=env,
                                   stdout=open(log_path, "w"), stderr=subprocess.STDOUT, start_new_session=True)
        processes.append(process)
        if comment.startswith("# once"):
            status = wait(process, 60)
            if status != 0:
                fail(f"'{command}' ended with status {status}:\n{open(log_path).read()[-2000:]}")
        else:
            started.append((command, process, log_path))
    check([ns for ns, _, c in steps if not c.startswith("# once")] == [ns_server, ns_client],
          "the block starts one command on host A, then one on host B")
    for command, process, log_path in started:
        status = wait(process, 600)
        if status != 0:
            fail(f"'{command}' ended with status {status}\n" +
                 "\n".join(open(path).read()[-3000:] for _, _, path in started))
    token = os.path.join(hosts, ".fsi.token")
    check(os.stat(token).st_mode & 0o077 == 0 and len(open(token).read().strip()) == 64,
          "the token file holds 64 hex digits that only its owner can read")
    remote = os.path.join(hosts, "out", "tank")
    log = open(started[0][2]).read()
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
