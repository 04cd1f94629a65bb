#!/usr/bin/python3
"""--token-file (docs/protocol.md, "Authentication"): with the same token both programs run; a
client with a wrong or no token is refused by the server before any set-up data is sent; a
server without the token (none, or an impostor with another one) is refused by the client; a
server will not listen beyond loopback without a token unless told so; token files others can
read are refused. Every refusal: a clear message and a non-zero exit."""
import os
import subprocess
import time

from fsi_test import (ENV, binary, check, cleanup, example, fail, kill_group, manifest, read, start_client,
                      start_server, wait, work_dir)

scene = example("static_tank", "static_tank_coarse.scene")
short_run = ["Resolution.end_time=0.0005", "Resolution.equilibration_steps=50"]
output = work_dir("authentication")


def token(name, text):
    path = os.path.join(output, name)
    with open(path, "w") as handle:
        handle.write(text + "\n")
    os.chmod(path, 0o600)
    return path


token_a = token("a.token", "9f86d081884c7d659a2feaa0c55ad015a3bf4f1b2b0b822cd15d6c15b0f00a08")
token_b = token("b.token", "60303ae22b998861bce3b28f33eec1be758a213c86c93c076dbe9f558c11c752")


def finish(run_dir, server, client, timeout=120):
    server_status = wait(server, timeout)
    client_status = wait(client, 30)
    for process in (server, client):
        if process.poll() is None:
            kill_group(process)
    if server_status is None or client_status is None:
        fail(f"{run_dir}: a side still runs (server {server_status}, client {client_status}):\n"
             f"{read(run_dir, 'server.stderr')}\n{read(run_dir, 'client.stderr')}")
    return server_status, client_status, read(run_dir, "server.stderr"), read(run_dir, "client.stderr")


# 1. The same token on both sides: the run completes and run.json says it was authenticated.
run_dir = os.path.join(output, "same_token")
server, port = start_server(scene, run_dir, short_run, ["--token-file", token_a])
client = start_client(port, 2, run_dir, ["--token-file", token_a])
s, c, server_log, client_log = finish(run_dir, server, client)
check(s == 0 and c == 0, f"same token: server and client exit 0 ({s}, {c})")
check(manifest(run_dir)["protocol"]["authenticated"] is True, "run.json: protocol.authenticated = true")
check("server authenticated" in client_log, "the client says the server was authenticated")

# 2. The client holds another token: the server refuses it before any set-up data.
run_dir = os.path.join(output, "wrong_client_token")
server, port = start_server(scene, run_dir, short_run, ["--token-file", token_a])
client = start_client(port, 2, run_dir, ["--token-file", token_b])
s, c, server_log, client_log = finish(run_dir, server, client)
check(s != 0 and c != 0, f"wrong client token: both exit non-zero (server {s}, client {c})")
check("authentication failed, its token differs" in server_log, "the server says the client's token differs")
check("sent set-up" not in server_log, "the server sent no set-up data")
check("[AuthenticationFailed]" in client_log and "token differs" in client_log,
      "the client reports the server's refusal")
check(manifest(run_dir)["status"] == "failed", "run.json records the failure")

# 2b. What a client with the wrong token receives, frame by frame: the Error and nothing else.
run_dir = os.path.join(output, "wrong_token_frames")
server, port = start_server(scene, run_dir, short_run, ["--token-file", token_a])
fake = subprocess.run([binary("fake_peer"), "client-token", "127.0.0.1", str(port), token_b],
                      capture_output=True, text=True, timeout=60, env=ENV)
status = wait(server, 30)
if status is None:
    kill_group(server)
    fail("fsi-server still runs after refusing a client")
check(fake.returncode == 1 and "[AuthenticationFailed]" in fake.stdout,
      f"fake client with a wrong token refused: {fake.stdout.strip().splitlines()[0]}")
check("then received" not in fake.stdout and "connection closed by peer" in fake.stdout,
      "after the Error the server sent nothing, then closed")
check(status != 0, f"the server exits non-zero ({status})")

# 3. The client has no token: refused by a server that requires one.
run_dir = os.path.join(output, "client_without_token")
server, port = start_server(scene, run_dir, short_run, ["--token-file", token_a])
client = start_client(port, 1, run_dir)
s, c, server_log, client_log = finish(run_dir, server, client)
check(s != 0 and c != 0, f"client without token: both exit non-zero (server {s}, client {c})")
check("presented no token" in server_log, "the server says the client presented no token")
check("presented no token" in client_log and "[AuthenticationFailed]" in client_log,
      "the client reports why it was refused")

# 4. The server has no token, the client has one: the client refuses the server.
run_dir = os.path.join(output, "server_without_token")
server, port = start_server(scene, run_dir, short_run)
client = start_client(port, 1, run_dir, ["--token-file", token_a])
s, c, server_log, client_log = finish(run_dir, server, client)
check(s != 0 and c != 0, f"server without token: both exit non-zero (server {s}, client {c})")
check("did not authenticate itself" in client_log, "the client says the server did not authenticate itself")
check("[AuthenticationFailed]" in server_log, "the server logs the client's refusal")

# 5. An impostor server with another token: the client refuses it and runs none of its set-up.
run_dir = os.path.join(output, "impostor")
os.makedirs(run_dir)
port_file = os.path.join(run_dir, "port")
impostor = subprocess.Popen([binary("fake_peer"), "impostor", port_file, token_b], stdout=subprocess.PIPE,
                            stderr=subprocess.STDOUT, text=True, env=ENV)
deadline = time.time() + 20
while not os.path.exists(port_file) and time.time() < deadline:
    time.sleep(0.05)
client = start_client(int(open(port_file).read()), 1, run_dir, ["--token-file", token_a])
c = wait(client, 30)
if c is None:
    kill_group(client)
    fail("fsi-client still runs 30 s after meeting an impostor")
client_log = read(run_dir, "client.stderr")
impostor_out = impostor.communicate(timeout=30)[0]
check(c != 0, f"the client exits non-zero ({c})")
check("authentication failed, it does not hold this fsi-client's token" in client_log,
      "the client says the server does not hold its token")
check("LIGGGHTS" not in client_log and "evil" not in client_log, "the client ran none of the impostor's set-up")
check("[AuthenticationFailed]" in impostor_out, "the impostor was told AuthenticationFailed")

# 6. No token on a non-loopback address: refused unless --allow-unauthenticated.
run_dir = os.path.join(output, "open_listen")
os.makedirs(run_dir)
result = subprocess.run([binary("fsi-server"), scene, "--output", run_dir, "--listen", "0.0.0.0"],
                        capture_output=True, text=True, timeout=60, env=ENV)
check(result.returncode == 2 and "refusing to listen on a non-loopback address without --token-file"
      in result.stderr, f"--listen 0.0.0.0 without a token is refused (exit {result.returncode})")
check("--allow-unauthenticated" in result.stderr, "the message names both remedies")
run_dir = os.path.join(output, "open_listen_allowed")
server, port = start_server(scene, run_dir, short_run, ["--listen", "0.0.0.0", "--allow-unauthenticated",
                                                        "--accept-timeout", "1"])
status = wait(server, 30)
log = read(run_dir, "server.stderr")
check("ANY host that reaches the port can connect" in log, "--allow-unauthenticated listens with a loud warning")

# 7. A token file others can read is refused by both programs.
loose = token("loose.token", "0123456789abcdef0123456789abcdef")
os.chmod(loose, 0o644)
run_dir = os.path.join(output, "loose")
os.makedirs(run_dir)
result = subprocess.run([binary("fsi-server"), scene, "--output", run_dir, "--token-file", loose],
                        capture_output=True, text=True, timeout=60, env=ENV)
check(result.returncode == 2 and "accessible to other users (mode 644)" in result.stderr
      and "chmod 600" in result.stderr, f"fsi-server refuses a token file of mode 644 (exit {result.returncode})")
result = subprocess.run(["mpirun", "-np", "1"] + (["--allow-run-as-root"] if os.geteuid() == 0 else []) +
                        [binary("fsi-client"), "--server", "127.0.0.1:9", "--token-file", loose],
                        capture_output=True, text=True, timeout=60, env=ENV)
check(result.returncode != 0 and "accessible to other users" in result.stderr,
      f"fsi-client refuses it too (exit {result.returncode})")
cleanup(output)
