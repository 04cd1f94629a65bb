#!/usr/bin/python3
"""The session's state machine (docs/protocol.md §6) against the error rules of §7, walked with
fake peers written in Python (wire.py) against the real fsi-server and the real fsi-client: in
each state a message that has no place there is answered with Error UnexpectedMessage naming the
expected and the received type, a wait that runs out with PeerAborted, a frame of another major
with VersionMismatch, a broken frame with MalformedMessage, and an Error from the peer is never
answered. Every time the real program exits non-zero and says why."""
import os
import socket
import struct

from fsi_test import (check, cleanup, example, fail, protocol_version, read, start_client_for_fake_server, start_server, wait_for_exit,
                      work_dir)
from wire import (ERROR, MESH, PARTICLES, READY, SETUP, STEP, WELCOME, error, error_of, forces, frame, hello,
                  receive_frame, ready, step, welcome)

scene = example("static_tank", "static_tank_coarse.scene")
output = work_dir("protocol_states")
timeout = 2.0


def until_setup(connection):
    """Hello, then Welcome, Setup, Mesh, Particles from the server; the dynamic vertex count."""
    connection.sendall(hello())
    received = [receive_frame(connection, skip_heartbeats=True) for _ in range(4)]
    kinds = [item[0] if item else None for item in received]
    if kinds != [WELCOME, SETUP, MESH, PARTICLES]:
        fail(f"expected Welcome, Setup, Mesh, Particles from the server, got {kinds}")
    return struct.unpack("<I", received[2][1][4:8])[0]


def misbehave_and_check_answer(name, program, process, run_dir, connection, act, expected_code, needle):
    """Lets the fake peer misbehave with `act`, then checks that the real `program` ("server" or
    "client") answers with Error `expected_code` (None: does not answer a peer's Error) and exits
    non-zero with `needle` in its log."""
    peer = "client" if program == "server" else "server"
    act(connection)
    connection.settimeout(timeout + 10)
    reply = receive_frame(connection, skip_heartbeats=True)
    try:
        status, elapsed = wait_for_exit(process, 20, f"{name}: fsi-{program} still runs 20 s after the fault")
    finally:
        connection.close()
    log = read(run_dir, f"{program}.stderr")
    got = error_of(reply[1]) if reply and reply[0] == ERROR else None
    if expected_code is None:
        check(reply is None, f"{name}: the {program} does not answer the {peer}'s Error (got {reply and reply[0]})")
    else:
        check(got is not None and got[0] == expected_code and needle in got[1],
              f"{name}: the {program} answers Error {expected_code} ({got[1][:110] if got else got})")
    check(status != 0 and needle in log,
          f"{name}: the {program} exits {status} {elapsed:.1f} s later and its log says '{needle}'")


def server_state(name, state, act, expected_code, needle):
    """Brings a real fsi-server into `state` with a fake client, lets `act` misbehave, and checks
    the Error the server answers with (None: no answer) and its exit."""
    run_dir = os.path.join(output, name)
    # No particle snapshots: the first message after Forces 0 is then Step 1 (with snapshots it
    # is SnapshotRequest 0, the fluid as equilibrated at t = 0).
    server, port = start_server(scene, run_dir, ["Resolution.end_time=1e-4",
                                                 "Resolution.snapshot_every_steps=0"],
                                ["--peer-timeout", str(timeout)])
    connection = socket.create_connection(("127.0.0.1", port), timeout=30)
    if state != "handshake":
        dynamic = until_setup(connection)
        if state == "coupled":
            connection.sendall(ready())
            connection.sendall(forces(0, [0.0] * (2 * dynamic)))
            kind = receive_frame(connection, skip_heartbeats=True)
            if not kind or kind[0] != STEP:
                fail(f"{name}: the server did not send Step 1 after Ready and Forces 0 ({kind})")
    misbehave_and_check_answer(name, "server", server, run_dir, connection, act, expected_code, needle)


# In the handshake: the client must begin with Hello.
server_state("ready_instead_of_hello", "handshake", lambda c: c.sendall(ready()),
             "UnexpectedMessage", "expected a Hello message but received Ready")
# In the set-up: the server waits for Ready.
server_state("forces_instead_of_ready", "setup", lambda c: c.sendall(forces(0, [])),
             "UnexpectedMessage", "expected a Ready message but received Forces")
server_state("silence_instead_of_ready", "setup", lambda c: None,
             "PeerAborted", "timed out after 2 s while waiting for Ready")
server_state("other_major_instead_of_ready", "setup",
             lambda c: c.sendall(frame(READY, ready()[20:], major=2, minor=0)),
             "VersionMismatch", f"Ready frame of protocol 2.0, but this side speaks {protocol_version()}")
server_state("broken_ready", "setup", lambda c: c.sendall(frame(READY, ready()[20:], crc_error=1)),
             "MalformedMessage", "CRC-32C mismatch in Ready frame")
server_state("client_error_instead_of_ready", "setup",
             lambda c: c.sendall(error(4, "tank.in1:7: unknown command 'fixx'")),
             None, "peer reported: tank.in1:7: unknown command 'fixx' [SetupFailed]")
# In the coupled steps: Step 1 is out, the server waits for Forces 1.
server_state("ready_instead_of_forces", "coupled", lambda c: c.sendall(ready()),
             "UnexpectedMessage", "expected a Forces message but received Ready")
server_state("client_error_instead_of_forces", "coupled",
             lambda c: c.sendall(error(5, "ERROR: Lost atoms: original 1980 current 1979")),
             None, "peer reported: ERROR: Lost atoms: original 1980 current 1979 [LiggghtsError]")


def client_state(name, act, expected_code, needle):
    """A fake server welcomes a real `mpirun -np 2 fsi-client`, then misbehaves with `act`."""
    run_dir = os.path.join(output, name)
    client, connection = start_client_for_fake_server(run_dir, 2, ["--peer-timeout", str(timeout)])
    connection.settimeout(timeout + 10)
    first = receive_frame(connection)
    if not first or first[0] != 0x01:
        fail(f"{name}: the client did not start with Hello ({first})")
    connection.sendall(welcome())
    misbehave_and_check_answer(name, "client", client, run_dir, connection, act, expected_code, needle)


# After Welcome the client waits for Setup.
client_state("step_instead_of_setup", lambda c: c.sendall(step(1, [0.0, 0.0])),
             "UnexpectedMessage", "expected a Setup message but received Step")
client_state("silence_instead_of_setup", lambda c: None,
             "PeerAborted", "timed out after 2 s while waiting for the next message from fsi-server")
client_state("server_error_instead_of_setup",
             lambda c: c.sendall(error(4, "tank.scene:12:3: unknown key 'lenght'")),
             None, "peer reported: tank.scene:12:3: unknown key 'lenght' [SetupFailed]")
cleanup(output)
