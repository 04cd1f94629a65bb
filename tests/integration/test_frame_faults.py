#!/usr/bin/python3
"""Broken frames at the process level (docs/protocol.md §2, §7): a fake client written here in
Python (its own CRC-32C, independent of the C++ one) completes the handshake and receives the
set-up from the real fsi-server, then, instead of Ready, sends half a frame and goes silent, a
truncated frame and hangs up, or a frame with a wrong CRC, an oversize length, an unknown type or
another major version. Each time the server ends with a message naming the fault and a non-zero
status, within its --peer-timeout where it has to wait; decodable faults are answered with an
Error frame. Likewise a fake server that sends half a frame to the real fsi-client."""
import os
import socket
import struct

from fsi_test import (check, cleanup, example, fail, protocol_version, read, start_client_for_fake_server, start_server, wait_for_exit,
                      work_dir)
from wire import ERROR, HELLO, MESH, PARTICLES, READY, SETUP, WELCOME, error_of, frame, receive_frame, text

scene = example("static_tank", "static_tank_coarse.scene")
output = work_dir("frame_faults")
timeout = 2.0


READY_PAYLOAD = struct.pack("<Q", 1980) + text("fake LIGGGHTS") + struct.pack("<dd", 0.1, 0.2)


def fake_client_until_setup(port):
    connection = socket.create_connection(("127.0.0.1", port), timeout=30)
    connection.sendall(frame(HELLO, text("fake-python") + text("test") + struct.pack("<II", 1, 0x2)))
    kinds = [receive_frame(connection)[0] for _ in range(4)]
    if kinds != [WELCOME, SETUP, MESH, PARTICLES]:
        fail(f"expected Welcome, Setup, Mesh, Particles from the server, got {kinds}")
    return connection


def server_case(name, send, needle, hang_up=False, answered="MalformedMessage"):
    run_dir = os.path.join(output, name)
    server, port = start_server(scene, run_dir, extra=["--peer-timeout", str(timeout)])
    connection = fake_client_until_setup(port)
    send(connection)
    if hang_up:
        connection.close()
    status, elapsed = wait_for_exit(server, 20, f"{name}: fsi-server still runs 20 s after the fault")
    log = read(run_dir, "server.stderr")
    check(status != 0 and needle in log,
          f"{name}: server exits {status} after {elapsed:.2f} s, naming the fault: "
          f"{next((line for line in log.splitlines() if needle in line), '(not found)')[-170:]}")
    if answered:
        connection.settimeout(5)
        reply = receive_frame(connection, skip_heartbeats=True)
        code = error_of(reply[1])[0] if reply and reply[0] == ERROR else None
        check(code == answered, f"{name}: the server answered with an Error frame {answered} (got {code})")
    if not hang_up:
        connection.close()
    return elapsed


ready = frame(READY, READY_PAYLOAD)

# Half a header, then silence: ended after --peer-timeout.
elapsed = server_case("half_header_silent", lambda c: c.sendall(ready[:10]),
                      "timed out after 2 s while waiting for Ready from 127.0.0.1", answered="PeerAborted")
check(timeout <= elapsed < timeout + 1.5, f"half a header: ended within the timeout ({elapsed:.2f} s)")
check("received 10 of the 20 header bytes" in read(os.path.join(output, "half_header_silent"), "server.stderr"),
      "half a header: the message says how much of the frame arrived")
# The header and half the payload, then silence.
elapsed = server_case("half_payload_silent", lambda c: c.sendall(ready[:20 + len(READY_PAYLOAD) // 2]),
                      f"received {len(READY_PAYLOAD) // 2} of the {len(READY_PAYLOAD)} payload bytes of a Ready frame",
                      answered="PeerAborted")
check(timeout <= elapsed < timeout + 1.5, f"half a payload: ended within the timeout ({elapsed:.2f} s)")
# A truncated frame, then the connection closes.
server_case("truncated_then_closed", lambda c: c.sendall(ready[:20 + 5]),
            "connection closed by peer", hang_up=True, answered=False)
server_case("wrong_crc", lambda c: c.sendall(frame(READY, READY_PAYLOAD, crc_error=0x40)),
            "CRC-32C mismatch in Ready frame")
server_case("oversize_length", lambda c: c.sendall(frame(READY, b"", length=0xFFFFFFF0)),
            "Ready frame announces a payload of 4294967280 bytes, more than the 1073741824 bytes")
server_case("unknown_type", lambda c: c.sendall(frame(0x99, READY_PAYLOAD)),
            f"frame of unknown type 0x0099, which protocol {protocol_version()} does not define")
server_case("other_major", lambda c: c.sendall(frame(READY, READY_PAYLOAD, major=2, minor=0)),
            f"Ready frame of protocol 2.0, but this side speaks {protocol_version()}", answered="VersionMismatch")
server_case("bad_payload", lambda c: c.sendall(frame(READY, READY_PAYLOAD[:-3])),
            "malformed Ready message: field 'seconds_equilibration' is truncated")

# A fake server sends the real client half a Setup frame and goes silent.
run_dir = os.path.join(output, "client_half_frame")
client, connection = start_client_for_fake_server(run_dir, 1, ["--peer-timeout", str(timeout)])
if receive_frame(connection)[0] != HELLO:
    fail("the client did not start with Hello")
connection.sendall(frame(WELCOME, struct.pack("<HI", 1, 0x2) + text("fake-server") + text("run")))
connection.sendall(frame(SETUP, b"\x02\x00\x00\x00" + b"\x00" * 40)[:30])
try:
    status, elapsed = wait_for_exit(client, 20, "fsi-client still runs 20 s after receiving half a frame")
finally:
    connection.close()
log = read(run_dir, "client.stderr")
check(status != 0 and "timed out after 2 s while waiting for the next message from fsi-server" in log
      and "payload bytes of a Setup frame" in log,
      f"client: exits {status} after {elapsed:.2f} s naming the half Setup frame")
# The timeout fires after 2 s (the message above says so); the exit then takes MPI_Abort and
# mpirun's teardown of both ranks, allowed 3 s here.
check(elapsed < timeout + 3.0, f"client: process ended {elapsed:.2f} s after the half frame (timeout {timeout} s + MPI teardown)")
cleanup(output)
