#pragma once
// The one list of protocol message types (docs/protocol.md, "Message types"). Each entry is
//   X(enumerator of MessageType, message struct in messages.hpp, type id on the wire)
// The MessageType enumerators, name(), is_known(), the Message variant, the decode dispatch, the
// explicit instantiations of the codec and of Channel::expect_into, and the fuzzers' decoder table
// and seed corpus all expand this list, so a new message is its struct, its layout() and one line
// here (protocol/README.md, "Adding a message"). Type ids are part of the wire format: never
// renumber an entry; the order of the entries is the order of the Message alternatives and of
// the fuzzers' decoder table.
#define FSI_PROTOCOL_MESSAGES(X)                \
  X(Hello, Hello, 0x01)                         \
  X(Welcome, Welcome, 0x02)                     \
  X(Error, ErrorMessage, 0x03)                  \
  X(AuthChallenge, AuthChallenge, 0x04)         \
  X(AuthResponse, AuthResponse, 0x05)           \
  X(AuthProof, AuthProof, 0x06)                 \
  X(Heartbeat, Heartbeat, 0x07)                 \
  X(Setup, Setup, 0x10)                         \
  X(Mesh, Mesh, 0x11)                           \
  X(Particles, Particles, 0x12)                 \
  X(Ready, Ready, 0x13)                         \
  X(Settling, Settling, 0x14)                   \
  X(ReleaseState, ReleaseState, 0x15)           \
  X(ProbeSetup, ProbeSetup, 0x16)               \
  X(Step, Step, 0x20)                           \
  X(Forces, Forces, 0x21)                       \
  X(ProbeValues, ProbeValues, 0x22)             \
  X(FluidHealth, FluidHealth, 0x23)             \
  X(ProbePlacement, ProbePlacement, 0x24)       \
  X(StepMotion, StepMotion, 0x25)               \
  X(SnapshotRequest, SnapshotRequest, 0x30)     \
  X(Snapshot, Snapshot, 0x31)                   \
  X(CheckpointRequest, CheckpointRequest, 0x32) \
  X(FluidState, FluidState, 0x33)               \
  X(Resume, Resume, 0x17)                       \
  X(Shutdown, Shutdown, 0x40)                   \
  X(Goodbye, Goodbye, 0x41)
