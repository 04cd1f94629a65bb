"""The protocol's framing (docs/protocol.md §1-§2) written independently of the C++ code, for the
fake peers of the integration tests: its own CRC-32C, frames, strings, message type numbers."""
import struct

HELLO, WELCOME, ERROR, HEARTBEAT = 0x01, 0x02, 0x03, 0x07
SETUP, MESH, PARTICLES, READY = 0x10, 0x11, 0x12, 0x13
STEP, FORCES, SNAPSHOT_REQUEST, SNAPSHOT, SHUTDOWN, GOODBYE = 0x20, 0x21, 0x30, 0x31, 0x40, 0x41
ERROR_CODES = {1: "VersionMismatch", 2: "MalformedMessage", 3: "UnexpectedMessage", 4: "SetupFailed",
               5: "LiggghtsError", 6: "PeerAborted", 7: "Internal", 8: "AuthenticationFailed"}


def _crc32c_table():
    table = []
    for byte in range(256):
        crc = byte
        for _ in range(8):
            crc = (crc >> 1) ^ 0x82F63B78 if crc & 1 else crc >> 1
        table.append(crc)
    return table


_TABLE = _crc32c_table()


def crc32c(data, crc=0):
    crc ^= 0xFFFFFFFF
    for byte in data:
        crc = _TABLE[(crc ^ byte) & 0xFF] ^ (crc >> 8)
    return crc ^ 0xFFFFFFFF


assert crc32c(b"123456789") == 0xE3069283  # the check value of docs/protocol.md


def frame(kind, payload, major=1, minor=1, length=None, crc_error=0):
    head = b"FSIP" + struct.pack("<HHHHI", major, minor, kind, 0, len(payload) if length is None else length)
    return head + struct.pack("<I", crc32c(payload, crc32c(head)) ^ crc_error) + payload


def text(value):
    data = value.encode()
    return struct.pack("<I", len(data)) + data


def doubles(values):
    return struct.pack("<Q", len(values)) + struct.pack(f"<{len(values)}d", *values)


def hello(capabilities=0x2):
    return frame(HELLO, text("fake-python") + text("test") + struct.pack("<II", 1, capabilities))


def welcome(capabilities=0x2):
    return frame(WELCOME, struct.pack("<HI", 1, capabilities) + text("fake-server") + text("run"))


def error(code, message):
    return frame(ERROR, struct.pack("<I", code) + text(message))


def ready(particles=1980):
    return frame(READY, struct.pack("<Q", particles) + text("fake LIGGGHTS") + struct.pack("<dd", 0.1, 0.2))


def forces(step, values):
    diagnostics = struct.pack("<6d", 0, 0, 0, 0, 0, 0) + struct.pack("<dQdQddd", 0, 0, 1e9, 1980, 0, 0, 0)
    return frame(FORCES, struct.pack("<Q", step) + doubles(values) + diagnostics)


def step(number, positions):
    return frame(STEP, struct.pack("<Qdd", number, 1e-5 * number, 1e-5) + doubles(positions) + doubles(positions))


def receive_exactly(connection, size):
    data = b""
    while len(data) < size:
        piece = connection.recv(size - len(data))
        if not piece:
            return None
        data += piece
    return data


def receive_frame(connection, skip_heartbeats=False):
    """(type, payload) of the next frame, or None when the peer closed the connection."""
    while True:
        head = receive_exactly(connection, 20)
        if head is None:
            return None
        kind, _, length = struct.unpack("<HHI", head[8:16])
        payload = receive_exactly(connection, length)
        if not (skip_heartbeats and kind == HEARTBEAT):
            return kind, payload


def error_of(payload):
    """(code name, text) of an Error payload."""
    code, size = struct.unpack("<II", payload[:8])
    return ERROR_CODES.get(code, f"code {code}"), payload[8:8 + size].decode()
