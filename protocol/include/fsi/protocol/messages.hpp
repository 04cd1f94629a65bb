#pragma once
// The messages of protocol 1.3; docs/protocol.md gives the byte layout of each. encode() makes a
// payload; decode() checks every count against the bytes that remain before allocating, checks
// the content for consistency, and throws ProtocolError naming the message, the field and the
// byte offset.

#include <array>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <optional>
#include <span>
#include <string>
#include <type_traits>
#include <variant>
#include <vector>

#include "fsi/protocol/frame.hpp"

namespace fsi::protocol {

// Capability bits of Hello and Welcome, agreed as the AND of both sides' bits (docs/protocol.md,
// "Versions"). Protocol 1.0 defines none.
inline constexpr std::uint32_t kNoCapabilities = 0;
// 1.1: the sender holds a shared token and proves it (AuthChallenge, AuthResponse, AuthProof).
inline constexpr std::uint32_t kCapabilityAuthentication = 1u << 0;
// 1.1: the sender understands Heartbeat frames (the peer may send them while it computes).
inline constexpr std::uint32_t kCapabilityHeartbeat = 1u << 1;
// 1.2: the sender takes part in the settling of the fluid and the check at release (Settling,
// ReleaseState).
inline constexpr std::uint32_t kCapabilitySettling = 1u << 2;
// 1.3: the sender evaluates (client) or records (server) probes of the fluid (ProbeSetup,
// ProbeValues).
inline constexpr std::uint32_t kCapabilityProbes = 1u << 3;
// 1.3: the sender reports the fluid's health after every Forces (FluidHealth), so that the server
// can stop a run whose fluid is failing before it writes NaN (docs/user-guide.md, "When a run
// stops: the health checks").
inline constexpr std::uint32_t kCapabilityFluidHealth = 1u << 4;
// 1.4: the sender places (server) or moves (client) probes that move with a body
// (ProbePlacement; docs/user-guide.md, "Probes that move with a body").
inline constexpr std::uint32_t kCapabilityMovingProbes = 1u << 5;
// 1.5: the sender sends (server) or takes (client) structure steps of several fluid steps with
// the boundary's stage values (StepMotion; docs/theory.md, "Multi-rate coupling").
inline constexpr std::uint32_t kCapabilityMultiRate = 1u << 6;
// 1.6: coupled checkpoints (CheckpointRequest, FluidState) and resumes (Resume in place of
// Particles and Settling; docs/user-guide.md, "Checkpoints and resume").
inline constexpr std::uint32_t kCapabilityCheckpoint = 1u << 7;

// The codes of an Error message (docs/protocol.md §7) as X(enumerator, value); AuthenticationFailed
// came with 1.1.
#define FSI_PROTOCOL_ERROR_CODES(X) \
  X(VersionMismatch, 1)             \
  X(MalformedMessage, 2)            \
  X(UnexpectedMessage, 3)           \
  X(SetupFailed, 4)                 \
  X(LiggghtsError, 5)               \
  X(PeerAborted, 6)                 \
  X(Internal, 7)                    \
  X(AuthenticationFailed, 8)
enum class ErrorCode : std::uint32_t {
#define FSI_PROTOCOL_ERROR_CODE(enumerator, value) enumerator = value,
  FSI_PROTOCOL_ERROR_CODES(FSI_PROTOCOL_ERROR_CODE)
#undef FSI_PROTOCOL_ERROR_CODE
};
// "VersionMismatch", ..., or "code 42" for codes this version does not know.
std::string name(ErrorCode code);

// The peer sent an Error message: it has given up and explains why. Do not answer with an Error.
class PeerReportedError : public ProtocolError {
 public:
  PeerReportedError(ErrorCode code, const std::string& peer_text, const std::string& where);
  ErrorCode code() const noexcept { return code_; }
  const std::string& peer_text() const noexcept { return peer_text_; }

 private:
  ErrorCode code_;
  std::string peer_text_;
};

// The code of the Error this side sends when `failure` ends its session (docs/protocol.md §7):
// VersionMismatch, UnexpectedMessage, PeerAborted (timeouts) or MalformedMessage for protocol
// faults, `otherwise` for everything else (a scene, script or solver failure); nullopt for the
// peer's own Error, which is never answered.
std::optional<ErrorCode> error_code_for(const std::exception& failure, ErrorCode otherwise);

struct Hello {  // client -> server; layout frozen in every major version
  static constexpr MessageType kType = MessageType::Hello;
  std::string software_version;
  std::string host;
  std::uint32_t mpi_ranks = 1;
  std::uint32_t capabilities = kNoCapabilities;
  bool operator==(const Hello&) const = default;
};

struct Welcome {  // server -> client
  static constexpr MessageType kType = MessageType::Welcome;
  std::uint16_t accepted_minor = kMinorVersion;
  std::uint32_t capabilities = kNoCapabilities;
  std::string software_version;
  std::string run_name;
  bool operator==(const Welcome&) const = default;
};

struct ErrorMessage {  // either way; layout frozen in every major version
  static constexpr MessageType kType = MessageType::Error;
  ErrorCode code = ErrorCode::Internal;  // codes unknown to this version are kept as they are
  std::string text;
  bool operator==(const ErrorMessage&) const = default;
};

// Authentication (1.1, capability kCapabilityAuthentication; docs/protocol.md §5): 32-byte
// nonces from a CSPRNG and HMAC-SHA256 tags.
using AuthBytes = std::array<std::uint8_t, 32>;

struct AuthChallenge {  // server -> client, after a Hello with kCapabilityAuthentication
  static constexpr MessageType kType = MessageType::AuthChallenge;
  AuthBytes server_nonce{};
  bool operator==(const AuthChallenge&) const = default;
};

struct AuthResponse {  // client -> server
  static constexpr MessageType kType = MessageType::AuthResponse;
  AuthBytes client_nonce{};
  AuthBytes client_tag{};  // HMAC(token, "fsi-client" | server_nonce | client_nonce)
  bool operator==(const AuthResponse&) const = default;
};

struct AuthProof {  // server -> client, once the client's tag is verified; Welcome follows
  static constexpr MessageType kType = MessageType::AuthProof;
  AuthBytes server_tag{};  // HMAC(token, "fsi-server" | client_nonce | server_nonce)
  bool operator==(const AuthProof&) const = default;
};

// 1.1, capability kCapabilityHeartbeat: "still computing". Carries no payload; a receiving Channel
// consumes it and starts its timeout again.
struct Heartbeat {
  static constexpr MessageType kType = MessageType::Heartbeat;
  bool operator==(const Heartbeat&) const = default;
};

struct LiggghtsVariable {
  std::string name;
  std::string value;
  bool operator==(const LiggghtsVariable&) const = default;
};

struct Setup {  // server -> client
  static constexpr MessageType kType = MessageType::Setup;
  std::uint32_t dimension = 2;  // 2 or 3
  double time_step = 0.0;       // > 0, finite
  std::uint64_t equilibration_steps = 0;
  std::vector<LiggghtsVariable> liggghts_variables;
  std::string script1_name;
  std::string script1_text;
  std::string script2_name;
  std::string script2_text;
  bool operator==(const Setup&) const = default;
};

// The boundary meshes of all bodies in one vertex list: the dynamic vertices (those that move
// with the structure and travel in every Step) first, the static ones after (thesis §5.2).
struct Mesh {  // server -> client
  static constexpr MessageType kType = MessageType::Mesh;
  std::uint32_t dimension = 2;
  std::uint32_t dynamic_vertex_count = 0;
  std::uint32_t refinement_option = 1;
  double refinement_resolution = 0.0;           // > 0, finite
  std::vector<double> positions;                // dimension values per vertex
  std::vector<double> velocities;               // as positions
  std::vector<std::uint32_t> element_vertices;  // 2 per segment (2D), 3 per triangle (3D)
  bool operator==(const Mesh&) const = default;

  std::size_t vertex_count() const { return dimension ? positions.size() / dimension : 0; }
};

struct Particles {  // server -> client: the fluid particles to create
  static constexpr MessageType kType = MessageType::Particles;
  std::uint32_t dimension = 2;
  std::uint32_t atom_type = 1;
  double mass = 0.0;
  double density = 0.0;
  std::vector<double> positions;   // dimension values per particle
  std::vector<double> velocities;  // as positions
  bool operator==(const Particles&) const = default;
};

// 1.2, capability kCapabilitySettling: how the fluid settles during the equilibration (a velocity
// drag, removed before script 2; docs/theory.md, "Settling the fluid").
inline constexpr double kAutomaticDragRate = -1.0;
struct Settling {  // server -> client, after Particles
  static constexpr MessageType kType = MessageType::Settling;
  std::array<double, 3> gravity{};  // the scene's gravity [m/s^2] (2D: z = 0)
  double column_height = 0.0;       // H [m] of the server's fluid region; 0: measure the particles
  // [1/s]: 0 no drag, > 0 this rate, kAutomaticDragRate (any negative value): derived by the
  // client from H, |g| and the time step.
  double drag_rate = kAutomaticDragRate;
  // The initial density of every particle of Particles, in its order (a hydrostatic start); empty:
  // all start at Particles::density.
  std::vector<double> initial_densities;
  bool operator==(const Settling&) const = default;
};

struct Ready {  // client -> server, after script 1, insertion, equilibration and script 2
  static constexpr MessageType kType = MessageType::Ready;
  std::uint64_t particle_count = 0;
  std::string liggghts_version;
  double seconds_setup = 0.0;
  double seconds_equilibration = 0.0;
  bool operator==(const Ready&) const = default;
};

// 1.2, capability kCapabilitySettling: the fluid as the structure is released (after script 2 and
// its run with set-up), for the server's check that the water is at rest.
struct ReleaseState {  // client -> server, right after Ready
  static constexpr MessageType kType = MessageType::ReleaseState;
  double drag_rate = 0.0;         // the settling drag applied [1/s] (0: none)
  double column_height = 0.0;     // H the drag was derived from [m]
  double fluid_mass = 0.0;        // sum of the particle masses [kg; 2D kg/m]
  double kinetic_energy = 0.0;    // sum of m v^2 / 2 [J; 2D J/m]
  double potential_energy = 0.0;  // sum of m |g| (height above the lowest particle) [J; 2D J/m]
  bool operator==(const ReleaseState&) const = default;
};

// 1.3, capability kCapabilityProbes: one probe of the fluid (docs/user-guide.md, "Probes"). The
// kinds and the order of their parameters are fsi::probes' (probes/include/fsi/probes/probe.hpp);
// the protocol carries them as numbers.
struct ProbeRecord {
  std::uint32_t kind = 0;
  std::string name;
  std::vector<double> parameters;
  bool operator==(const ProbeRecord&) const = default;
};

struct ProbeSetup {  // server -> client, after Settling, whenever both sides agreed on probes
  static constexpr MessageType kType = MessageType::ProbeSetup;
  // The probes are evaluated after the steps that are multiples of this (step 0 included).
  std::uint64_t every_steps = 1;
  std::array<double, 3> gravity{};  // [m/s^2] (2D: z = 0)
  double particle_spacing = 0.0;    // d [m]; 0: the client derives it from the particles
  std::vector<ProbeRecord> probes;  // may be empty
  bool operator==(const ProbeSetup&) const = default;
};

// 1.4, capability kCapabilityMovingProbes: where the probes that move with a body are at the end
// of a probe step. Each record gives a probe (its index in ProbeSetup) its whole parameter list
// in its kind's layout, placed by its body's motion; the others stay as they are.
struct PlacedProbe {
  std::uint32_t index = 0;
  std::vector<double> parameters;
  bool operator==(const PlacedProbe&) const = default;
};

struct ProbePlacement {  // server -> client, right before the Step of a probe step
  static constexpr MessageType kType = MessageType::ProbePlacement;
  std::uint64_t step = 0;  // the step of the Step that follows
  std::vector<PlacedProbe> probes;
  bool operator==(const ProbePlacement&) const = default;
};

struct Step {  // server -> client: the dynamic vertices at the end of the step
  static constexpr MessageType kType = MessageType::Step;
  std::uint64_t step = 0;
  double time = 0.0;               // end of the step
  double time_step = 0.0;          // > 0, finite
  std::vector<double> positions;   // dynamic vertices only, dimension values each
  std::vector<double> velocities;  // as positions
  bool operator==(const Step&) const = default;
};

// 1.5, capability kCapabilityMultiRate: one structure step of `substeps` fluid steps (multi-rate
// coupling, SolverOptions.Timeint.substeps). The fluid takes `substeps` steps of `time_step`,
// the last ending at `step` and `time`; in substep j the dynamic vertices are where the Hermite
// interpolant through the nodes puts them at theta = j / substeps (fsi/protocol/step_motion.hpp),
// so the last substep sees the nodes' last block (theta = 1) exactly. The client answers with one
// Forces: the vertex forces and force sums averaged over the substeps (the impulse over the
// structure step divided by its length), the closest approach of all substeps, and its health
// and probes at the end.
struct StepMotion {  // server -> client, in place of a Step
  static constexpr MessageType kType = MessageType::StepMotion;
  std::uint64_t step = 0;          // the last fluid step of the structure step
  double time = 0.0;               // its end
  double time_step = 0.0;          // the fluid step, > 0, finite
  std::uint32_t substeps = 0;      // >= 2
  std::vector<double> nodes;       // theta: 2 to 8, distinct, ascending in [0, 1], the last 1
  std::vector<double> positions;   // dynamic vertices at each node, node-major
  std::vector<double> velocities;  // as positions
  bool operator==(const StepMotion&) const = default;
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
  bool operator==(const ForceDiagnostics&) const = default;
};

struct Forces {  // client -> server
  static constexpr MessageType kType = MessageType::Forces;
  std::uint64_t step = 0;
  std::vector<double> forces;  // dynamic vertices only, dimension values each
  ForceDiagnostics diagnostics;
  bool operator==(const Forces&) const = default;
};

// 1.3, capability kCapabilityProbes: the probes' values (one per column, fsi::probes::columns)
// at the end of a probe step, reduced over the client's ranks.
struct ProbeValues {  // client -> server, after the Forces (and FluidHealth) of a probe step
  static constexpr MessageType kType = MessageType::ProbeValues;
  std::uint64_t step = 0;
  std::vector<double> values;
  bool operator==(const ProbeValues&) const = default;
};

// 1.3, capability kCapabilityFluidHealth: the state of every particle at the end of a step,
// reduced over all ranks. Extremes are over the particles whose position, velocity and density
// are all finite; the others are only counted.
struct FluidHealth {  // client -> server, right after each Forces (step 0 included)
  static constexpr MessageType kType = MessageType::FluidHealth;
  std::uint64_t step = 0;
  std::uint64_t particle_count = 0;
  std::uint64_t non_finite_particles = 0;  // a NaN or inf in position, velocity or density
  double min_density = 0.0;                // [kg/m^3]; +inf when no particle is finite
  double max_density = 0.0;                // [kg/m^3]; -inf when no particle is finite
  double max_speed = 0.0;                  // max |v| [m/s]
  bool operator==(const FluidHealth&) const = default;
};

struct SnapshotRequest {  // server -> client
  static constexpr MessageType kType = MessageType::SnapshotRequest;
  std::uint64_t step = 0;
  bool operator==(const SnapshotRequest&) const = default;
};

struct Snapshot {  // client -> server: all particles, gathered on rank 0
  static constexpr MessageType kType = MessageType::Snapshot;
  std::uint64_t step = 0;
  double time = 0.0;
  std::uint32_t dimension = 2;
  std::vector<std::uint64_t> ids;
  std::vector<double> positions;   // dimension values per id
  std::vector<double> velocities;  // dimension values per id
  std::vector<double> density;     // one per id
  std::vector<double> pressure;    // one per id
  bool operator==(const Snapshot&) const = default;
};

// 1.6, capability kCapabilityCheckpoint: the fluid's complete state at the end of the exchange of
// `step` (a checkpoint). The client answers with a FluidState and goes on from exactly the state a
// Resume with these bytes starts in.
struct CheckpointRequest {  // server -> client, between exchanges
  static constexpr MessageType kType = MessageType::CheckpointRequest;
  std::uint64_t step = 0;
  bool operator==(const CheckpointRequest&) const = default;
};

struct FluidState {  // client -> server: opaque to the server, read back only by a client
  static constexpr MessageType kType = MessageType::FluidState;
  std::uint64_t step = 0;
  std::uint64_t particle_count = 0;
  std::string state;  // the client's bytes (sph_client/src/fluid_state.hpp)
  bool operator==(const FluidState&) const = default;
};

// 1.6, capability kCapabilityCheckpoint: a resumed run, sent after the Particles in place of the
// Settling. The client runs its scripts on the scene's particles as in a new run but without an
// equilibration, then replaces the fluid by `state` (a FluidState's bytes) and answers with Ready
// (no ReleaseState, no Forces of step 0); the next Step is step + 1 (or a StepMotion ending at
// step + substeps).
struct Resume {  // server -> client
  static constexpr MessageType kType = MessageType::Resume;
  std::uint64_t step = 0;
  double time = 0.0;
  std::string state;
  bool operator==(const Resume&) const = default;
};

struct Shutdown {  // server -> client
  static constexpr MessageType kType = MessageType::Shutdown;
  std::string reason;
  bool operator==(const Shutdown&) const = default;
};

struct Goodbye {  // client -> server, the last message of a session
  static constexpr MessageType kType = MessageType::Goodbye;
  std::uint64_t steps_done = 0;
  double seconds_total = 0.0;
  bool operator==(const Goodbye&) const = default;
};

namespace detail {
// The list's entries each add ", Message"; the leading void takes the first comma.
template <class Void, class... Messages>
using VariantOfListed = std::variant<Messages...>;

template <class T, class Variant>
inline constexpr bool kIsAlternative = false;
template <class T, class... Alternatives>
inline constexpr bool kIsAlternative<T, std::variant<Alternatives...>> =
    (std::is_same_v<T, Alternatives> || ...);
}  // namespace detail

// Every message of message_list.hpp, in its order.
#define FSI_PROTOCOL_LISTED_MESSAGE(enumerator, message, id) , message
using Message = detail::VariantOfListed<void FSI_PROTOCOL_MESSAGES(FSI_PROTOCOL_LISTED_MESSAGE)>;
#undef FSI_PROTOCOL_LISTED_MESSAGE

#define FSI_PROTOCOL_CHECK_TYPE(enumerator, message, id)   \
  static_assert(message::kType == MessageType::enumerator, \
                #message "::kType differs from its entry in message_list.hpp");
FSI_PROTOCOL_MESSAGES(FSI_PROTOCOL_CHECK_TYPE)
#undef FSI_PROTOCOL_CHECK_TYPE

// One of the message structs above (the codec templates below exist for these only).
template <class T>
concept ProtocolMessage = detail::kIsAlternative<T, Message>;

inline constexpr std::size_t kMessageTypeCount = std::variant_size_v<Message>;

// Calls visit(std::type_identity<T>{}) for every message type T, in the order of the list.
template <class Visit>
constexpr void for_each_message_type(Visit&& visit) {
  [&]<class... Messages>(std::type_identity<std::variant<Messages...>>) {
    (visit(std::type_identity<Messages>{}), ...);
  }(std::type_identity<Message>{});
}

// Payload bytes (without the frame header).
template <ProtocolMessage T>
std::vector<std::byte> encode(const T& message);
std::vector<std::byte> encode(const Message& message);
// Encodes into the first bytes of buffer (grown when too small, never shrunk) and returns them:
// no allocation when the buffer is reused for messages of similar size. Any message type.
template <ProtocolMessage T>
std::span<const std::byte> encode_into(const T& message, std::vector<std::byte>& buffer);

// A payload as byte ranges to be sent one after another (scatter-gather): the small fields
// encoded into `encoded`, arrays and strings of at least kGatherMinimumBytes referenced where they
// lie in the message, so that nothing large is copied. The pieces in order are exactly the bytes
// encode() gives. They point into the message and into this object, so they are valid until
// either changes. Reused for many messages, it allocates nothing for sizes it has seen.
struct GatheredPayload {
  std::vector<std::byte> encoded;
  std::vector<std::span<const std::byte>> pieces;
  std::size_t size = 0;  // sum of the pieces' sizes
};
inline constexpr std::size_t kGatherMinimumBytes = 4096;
template <ProtocolMessage T>
void encode_gathered(const T& message, GatheredPayload& payload);

// Decodes the payload of a frame of the given type. Throws ProtocolError.
Message decode(MessageType type, std::span<const std::byte> payload);
// Decodes a payload known to hold a T (one of the alternatives of Message).
template <ProtocolMessage T>
T decode_as(std::span<const std::byte> payload);

// The payload of one frame as it arrives, for decoding straight into a message's own storage
// (Channel implements it over the socket). The decoder asks only for bytes that remain.
class PayloadSource {
 public:
  virtual ~PayloadSource() = default;
  // Payload bytes not yet read.
  virtual std::size_t remaining() const = 0;
  // Of those, how many are already here; a decoder allocates for an announced array up to this
  // much at once, beyond it only as the bytes arrive (a false length costs no memory).
  virtual std::size_t available() const = 0;
  // Fills `into` (at most remaining() bytes) with the next payload bytes.
  virtual void read(std::span<std::byte> into) = 0;
  // For a destination that would have to grow: the next `bytes` (at most remaining()) payload
  // bytes in a buffer the source keeps, valid until the next call; or nothing, if the source has
  // no such buffer (the decoder then grows the destination as the bytes arrive).
  virtual std::span<const std::byte> read_buffered(std::size_t bytes) {
    static_cast<void>(bytes);
    return {};
  }
  // Called when every field is read and nothing remains, before the content checks (a channel
  // verifies the CRC here, so a damaged frame is reported as such).
  virtual void end() {}
};
// Decodes a T from source into message, reusing the capacity of its vectors: a vector with room
// for the elements that arrive is filled in place, without allocation (and without zeroing, if it
// already holds as many). Throws ProtocolError as decode_as does; message then holds an
// unspecified mix of old and new values.
template <ProtocolMessage T>
void decode_into(PayloadSource& source, T& message);
Message decode(MessageType type, PayloadSource& source);

MessageType type_of(const Message& message);

}  // namespace fsi::protocol
