#pragma once
// The messages of protocol 1.0 (docs/protocol.md gives the byte layout of each). encode() makes a
// payload; decode() checks every length against the remaining bytes before allocating and throws
// ProtocolError naming the message, the field and the byte offset.

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <variant>
#include <vector>

#include "fsi/protocol/frame.hpp"

namespace fsi::protocol {

enum class ErrorCode : std::uint32_t {
  VersionMismatch = 1,
  MalformedMessage = 2,
  UnexpectedMessage = 3,
  SetupFailed = 4,
  LiggghtsError = 5,
  PeerAborted = 6,
  Internal = 7,
};

struct Hello {  // client -> server
  static constexpr MessageType kType = MessageType::Hello;
  std::string software_version;
  std::string host;
  std::uint32_t mpi_ranks = 1;
  std::uint32_t capabilities = 0;
};

struct Welcome {  // server -> client
  static constexpr MessageType kType = MessageType::Welcome;
  std::uint16_t accepted_minor = kMinorVersion;
  std::uint32_t capabilities = 0;
  std::string software_version;
  std::string run_name;
};

struct ErrorMessage {  // either way
  static constexpr MessageType kType = MessageType::Error;
  ErrorCode code = ErrorCode::Internal;
  std::string text;
};

struct LiggghtsVariable {
  std::string name;
  std::string value;
};

struct Setup {  // server -> client
  static constexpr MessageType kType = MessageType::Setup;
  std::uint32_t dimension = 2;
  double time_step = 0.0;
  std::uint64_t equilibration_steps = 0;
  std::vector<LiggghtsVariable> liggghts_variables;
  std::string script1_name;
  std::string script1_text;
  std::string script2_name;
  std::string script2_text;
};

struct Mesh {  // server -> client; dynamic vertices first, static ones after
  static constexpr MessageType kType = MessageType::Mesh;
  std::uint32_t dimension = 2;
  std::uint32_t dynamic_vertex_count = 0;
  std::uint32_t refinement_option = 1;
  double refinement_resolution = 0.0;
  std::vector<double> positions;                // dimension per vertex
  std::vector<double> velocities;               // dimension per vertex
  std::vector<std::uint32_t> element_vertices;  // 2 per segment (2D), 3 per triangle (3D)

  std::size_t vertex_count() const { return dimension ? positions.size() / dimension : 0; }
};

struct Particles {  // server -> client
  static constexpr MessageType kType = MessageType::Particles;
  std::uint32_t dimension = 2;
  std::uint32_t atom_type = 1;
  double mass = 0.0;
  double density = 0.0;
  std::vector<double> positions;
  std::vector<double> velocities;
};

struct Ready {  // client -> server, after script 1, equilibration and script 2
  static constexpr MessageType kType = MessageType::Ready;
  std::uint64_t particle_count = 0;
  std::string liggghts_version;
  double seconds_setup = 0.0;
  double seconds_equilibration = 0.0;
};

struct Step {  // server -> client: the structure at the end of the step
  static constexpr MessageType kType = MessageType::Step;
  std::uint64_t step = 0;
  double time = 0.0;
  double time_step = 0.0;
  std::vector<double> positions;  // dynamic vertices only
  std::vector<double> velocities;
};

struct ForceDiagnostics {
  std::array<double, 3> force_on_fluid{};
  std::array<double, 3> force_on_structure{};
  double pair_force_magnitude_sum = 0.0;
  std::uint64_t particles_in_range = 0;
  double closest_approach_over_r0 = 0.0;
  std::uint64_t particle_count = 0;
  double seconds_liggghts = 0.0;
  double seconds_contact = 0.0;
  double seconds_client_communication = 0.0;
};

struct Forces {  // client -> server
  static constexpr MessageType kType = MessageType::Forces;
  std::uint64_t step = 0;
  std::vector<double> forces;  // dynamic vertices only
  ForceDiagnostics diagnostics;
};

struct SnapshotRequest {  // server -> client
  static constexpr MessageType kType = MessageType::SnapshotRequest;
  std::uint64_t step = 0;
};

struct Snapshot {  // client -> server
  static constexpr MessageType kType = MessageType::Snapshot;
  std::uint64_t step = 0;
  double time = 0.0;
  std::uint32_t dimension = 2;
  std::vector<std::uint64_t> ids;
  std::vector<double> positions;
  std::vector<double> velocities;
  std::vector<double> density;
  std::vector<double> pressure;
};

struct Shutdown {  // server -> client
  static constexpr MessageType kType = MessageType::Shutdown;
  std::string reason;
};

struct Goodbye {  // client -> server
  static constexpr MessageType kType = MessageType::Goodbye;
  std::uint64_t steps_done = 0;
  double seconds_total = 0.0;
};

using Message = std::variant<Hello, Welcome, ErrorMessage, Setup, Mesh, Particles, Ready, Step,
                             Forces, SnapshotRequest, Snapshot, Shutdown, Goodbye>;

std::vector<std::byte> encode(const Hello&);
std::vector<std::byte> encode(const Welcome&);
std::vector<std::byte> encode(const ErrorMessage&);
std::vector<std::byte> encode(const Setup&);
std::vector<std::byte> encode(const Mesh&);
std::vector<std::byte> encode(const Particles&);
std::vector<std::byte> encode(const Ready&);
std::vector<std::byte> encode(const Step&);
std::vector<std::byte> encode(const Forces&);
std::vector<std::byte> encode(const SnapshotRequest&);
std::vector<std::byte> encode(const Snapshot&);
std::vector<std::byte> encode(const Shutdown&);
std::vector<std::byte> encode(const Goodbye&);

Message decode(MessageType type, std::span<const std::byte> payload);

MessageType type_of(const Message& message);

// Text naming two versions, for VersionMismatch errors.
std::string version_mismatch_text(const char* peer_role, std::uint16_t peer_major,
                                  std::uint16_t peer_minor, const char* own_role);

}  // namespace fsi::protocol
