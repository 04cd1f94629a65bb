// Message codecs. Each message's byte layout is written down once, in a layout() function that
// walks its fields in wire order; the size counter, the writer and the reader all walk it, so the
// encoder and the decoder cannot drift apart. Content checks that need the whole message (sizes
// that must agree, indices in range) live in check() and run after a complete read.
#include "fsi/protocol/messages.hpp"

#include <bit>
#include <cmath>
#include <concepts>
#include <cstdio>
#include <cstring>
#include <limits>
#include <optional>
#include <string_view>
#include <type_traits>
#include <utility>

namespace fsi::protocol {
namespace {

static_assert(std::endian::native == std::endian::little,
              "the codec copies little-endian values directly; add byte swapping for this host");
static_assert(std::numeric_limits<double>::is_iec559 && sizeof(double) == 8,
              "doubles travel as IEEE-754 binary64");

template <class Candidate, class Wanted>
concept MessageOf = std::same_as<std::remove_const_t<Candidate>, Wanted>;

// ---- one layout per message, in wire order (docs/protocol.md has the same tables) ----

void layout(auto& io, MessageOf<Hello> auto& m) {
  io.text("software_version", m.software_version);
  io.text("host", m.host);
  io.scalar("mpi_ranks", m.mpi_ranks);
  io.scalar("capabilities", m.capabilities);
}

void layout(auto& io, MessageOf<Welcome> auto& m) {
  io.scalar("accepted_minor", m.accepted_minor);
  io.scalar("capabilities", m.capabilities);
  io.text("software_version", m.software_version);
  io.text("run_name", m.run_name);
}

void layout(auto& io, MessageOf<ErrorMessage> auto& m) {
  io.scalar("code", m.code);
  io.text("text", m.text);
}

void layout(auto& io, MessageOf<AuthChallenge> auto& m) {
  io.scalar("server_nonce", m.server_nonce);
}

void layout(auto& io, MessageOf<AuthResponse> auto& m) {
  io.scalar("client_nonce", m.client_nonce);
  io.scalar("client_tag", m.client_tag);
}

void layout(auto& io, MessageOf<AuthProof> auto& m) {
  io.scalar("server_tag", m.server_tag);
}

void layout(auto&, MessageOf<Heartbeat> auto&) {}

void layout(auto& io, MessageOf<Setup> auto& m) {
  io.scalar("dimension", m.dimension);
  io.scalar("time_step", m.time_step);
  io.scalar("equilibration_steps", m.equilibration_steps);
  // A record is two strings, so at least two 4-byte lengths.
  io.records("liggghts_variables", m.liggghts_variables, 8, [](auto& record_io, auto& variable) {
    record_io.text("name", variable.name);
    record_io.text("value", variable.value);
  });
  io.text("script1_name", m.script1_name);
  io.text("script1_text", m.script1_text);
  io.text("script2_name", m.script2_name);
  io.text("script2_text", m.script2_text);
}

void layout(auto& io, MessageOf<Mesh> auto& m) {
  io.scalar("dimension", m.dimension);
  io.scalar("dynamic_vertex_count", m.dynamic_vertex_count);
  io.scalar("refinement_option", m.refinement_option);
  io.scalar("refinement_resolution", m.refinement_resolution);
  io.array("positions", m.positions);
  io.array("velocities", m.velocities);
  io.array("element_vertices", m.element_vertices);
}

void layout(auto& io, MessageOf<Particles> auto& m) {
  io.scalar("dimension", m.dimension);
  io.scalar("atom_type", m.atom_type);
  io.scalar("mass", m.mass);
  io.scalar("density", m.density);
  io.array("positions", m.positions);
  io.array("velocities", m.velocities);
}

void layout(auto& io, MessageOf<Ready> auto& m) {
  io.scalar("particle_count", m.particle_count);
  io.text("liggghts_version", m.liggghts_version);
  io.scalar("seconds_setup", m.seconds_setup);
  io.scalar("seconds_equilibration", m.seconds_equilibration);
}

void layout(auto& io, MessageOf<Step> auto& m) {
  io.scalar("step", m.step);
  io.scalar("time", m.time);
  io.scalar("time_step", m.time_step);
  io.array("positions", m.positions);
  io.array("velocities", m.velocities);
}

void layout(auto& io, MessageOf<Forces> auto& m) {
  io.scalar("step", m.step);
  io.array("forces", m.forces);
  auto& d = m.diagnostics;
  for (auto& component : d.force_on_fluid)
    io.scalar("force_on_fluid", component);
  for (auto& component : d.force_on_structure)
    io.scalar("force_on_structure", component);
  io.scalar("pair_force_magnitude_sum", d.pair_force_magnitude_sum);
  io.scalar("particles_in_range", d.particles_in_range);
  io.scalar("closest_approach_over_r0", d.closest_approach_over_r0);
  io.scalar("particle_count", d.particle_count);
  io.scalar("seconds_liggghts", d.seconds_liggghts);
  io.scalar("seconds_contact", d.seconds_contact);
  io.scalar("seconds_client_communication", d.seconds_client_communication);
}

void layout(auto& io, MessageOf<SnapshotRequest> auto& m) {
  io.scalar("step", m.step);
}

void layout(auto& io, MessageOf<Snapshot> auto& m) {
  io.scalar("step", m.step);
  io.scalar("time", m.time);
  io.scalar("dimension", m.dimension);
  io.array("ids", m.ids);
  io.array("positions", m.positions);
  io.array("velocities", m.velocities);
  io.array("density", m.density);
  io.array("pressure", m.pressure);
}

void layout(auto& io, MessageOf<Shutdown> auto& m) {
  io.text("reason", m.reason);
}

void layout(auto& io, MessageOf<Goodbye> auto& m) {
  io.scalar("steps_done", m.steps_done);
  io.scalar("seconds_total", m.seconds_total);
}

// ---- the three walkers ----

class SizeCounter {
 public:
  template <class T>
  void scalar(const char*, const T&) {
    size_ += sizeof(T);
  }
  void text(const char*, const std::string& value) {
    size_ += sizeof(std::uint32_t) + value.size();
  }
  template <class T>
  void array(const char*, const std::vector<T>& values) {
    size_ += sizeof(std::uint64_t) + values.size() * sizeof(T);
  }
  template <class T, class Each>
  void records(const char*, const std::vector<T>& items, std::size_t, Each&& each) {
    size_ += sizeof(std::uint64_t);
    for (const T& item : items)
      each(*this, item);
  }
  std::size_t size() const { return size_; }

 private:
  std::size_t size_ = 0;
};

class Writer {
 public:
  Writer(MessageType type, std::span<std::byte> bytes) : type_(type), bytes_(bytes) {}

  template <class T>
  void scalar(const char*, const T& value) {
    static_assert(std::is_trivially_copyable_v<T>);
    put(&value, sizeof(T));
  }
  void text(const char* field, const std::string& value) {
    if (value.size() > std::numeric_limits<std::uint32_t>::max()) {
      throw ProtocolError("cannot encode " + name(type_) + " field '" + field + "': a string of " +
                              std::to_string(value.size()) + " bytes does not fit a u32 length",
                          "encoding " + name(type_), "shorten the text");
    }
    const auto length = static_cast<std::uint32_t>(value.size());
    put(&length, sizeof length);
    put(value.data(), value.size());
  }
  template <class T>
  void array(const char*, const std::vector<T>& values) {
    const std::uint64_t count = values.size();
    put(&count, sizeof count);
    put(values.data(), values.size() * sizeof(T));
  }
  template <class T, class Each>
  void records(const char*, const std::vector<T>& items, std::size_t, Each&& each) {
    const std::uint64_t count = items.size();
    put(&count, sizeof count);
    for (const T& item : items)
      each(*this, item);
  }
  void finish() const {
    FSI_ASSERT(offset_ == bytes_.size(), "size counter and writer disagree on " + name(type_));
  }

 private:
  void put(const void* data, std::size_t size) {
    if (size == 0) return;
    std::memcpy(bytes_.data() + offset_, data, size);
    offset_ += size;
  }

  MessageType type_;
  std::span<std::byte> bytes_;
  std::size_t offset_ = 0;
};

class Reader {
 public:
  Reader(MessageType type, std::span<const std::byte> bytes) : type_(type), bytes_(bytes) {}

  template <class T>
  void scalar(const char* field, T& value) {
    static_assert(std::is_trivially_copyable_v<T>);
    begin(field);
    need(sizeof(T), "a " + std::to_string(sizeof(T)) + "-byte value");
    std::memcpy(&value, bytes_.data() + offset_, sizeof(T));
    offset_ += sizeof(T);
  }
  void text(const char* field, std::string& value) {
    begin(field);
    std::uint32_t length = 0;
    need(sizeof length, "its 4-byte length");
    std::memcpy(&length, bytes_.data() + offset_, sizeof length);
    offset_ += sizeof length;
    need(length, "a string of " + std::to_string(length) + " bytes");
    value.assign(reinterpret_cast<const char*>(bytes_.data() + offset_), length);
    offset_ += length;
  }
  template <class T>
  void array(const char* field, std::vector<T>& values) {
    begin(field);
    const std::uint64_t count = read_count();
    // Checked against what is left before anything is allocated.
    if (count > remaining() / sizeof(T)) {
      fail_here("announces " + std::to_string(count) + " elements of " + std::to_string(sizeof(T)) +
                " bytes but only " + std::to_string(remaining()) + " bytes remain");
    }
    values.resize(static_cast<std::size_t>(count));
    if (count > 0) std::memcpy(values.data(), bytes_.data() + offset_, count * sizeof(T));
    offset_ += count * sizeof(T);
  }
  template <class T, class Each>
  void records(const char* field, std::vector<T>& items, std::size_t minimum_record_size,
               Each&& each) {
    begin(field);
    const std::uint64_t count = read_count();
    if (count > remaining() / minimum_record_size) {
      fail_here("announces " + std::to_string(count) + " entries of at least " +
                std::to_string(minimum_record_size) + " bytes but only " +
                std::to_string(remaining()) + " bytes remain");
    }
    items.clear();
    // Grown entry by entry: the allocation follows the bytes actually read.
    for (std::uint64_t index = 0; index < count; ++index) {
      record_ = Record{field, index};
      T item{};
      each(*this, item);
      items.push_back(std::move(item));
    }
    record_.reset();
  }

  void finish() {
    if (offset_ != bytes_.size()) {
      current_field_ = "(end of message)";
      fail_here(std::to_string(bytes_.size() - offset_) +
                " bytes follow the last field; the message has fewer");
    }
  }

  // For content checks after the read: names the field and the offset where it began.
  [[noreturn]] void fail(std::string_view field, const std::string& problem) const {
    std::size_t offset = bytes_.size();
    for (const auto& [started, at] : field_offsets_) {
      if (started == field) {
        offset = at;
        break;
      }
    }
    throw_error(std::string(field), offset, problem);
  }

 private:
  struct Record {
    const char* field;
    std::uint64_t index;
  };

  void begin(const char* field) {
    current_field_ =
        record_ ? std::string(record_->field) + "[" + std::to_string(record_->index) + "]." + field
                : std::string(field);
    field_start_ = offset_;
    if (!record_) field_offsets_.emplace_back(field, offset_);
  }
  std::size_t remaining() const { return bytes_.size() - offset_; }
  void need(std::size_t size, const std::string& what) const {
    if (size > remaining()) {
      fail_here("is truncated: needs " + what + ", but only " + std::to_string(remaining()) +
                " bytes remain");
    }
  }
  std::uint64_t read_count() {
    std::uint64_t count = 0;
    need(sizeof count, "its 8-byte element count");
    std::memcpy(&count, bytes_.data() + offset_, sizeof count);
    offset_ += sizeof count;
    return count;
  }
  [[noreturn]] void fail_here(const std::string& problem) const {
    throw_error(current_field_, field_start_, problem);
  }
  [[noreturn]] void throw_error(const std::string& field, std::size_t offset,
                                const std::string& problem) const {
    throw ProtocolError("malformed " + name(type_) + " message: field '" + field + "' " + problem,
                        name(type_) + " payload byte " + std::to_string(offset) + " of " +
                            std::to_string(bytes_.size()),
                        "the peer is faulty or speaks another protocol version; use matching "
                        "releases of fsi-server and fsi-client");
  }

  MessageType type_;
  std::span<const std::byte> bytes_;
  std::size_t offset_ = 0;
  std::string current_field_;
  std::size_t field_start_ = 0;
  std::optional<Record> record_;
  std::vector<std::pair<std::string_view, std::size_t>> field_offsets_;
};

// ---- content checks, run on a completely read message ----

void check_dimension(const Reader& in, std::uint32_t dimension) {
  if (dimension != 2 && dimension != 3) {
    in.fail("dimension", "is " + std::to_string(dimension) + "; only 2 and 3 exist");
  }
}

void check_positive_finite(const Reader& in, const char* field, double value) {
  if (!(value > 0.0) || !std::isfinite(value)) {
    char text[64];
    std::snprintf(text, sizeof text, "%.17g", value);
    in.fail(field, std::string("is ") + text + "; it must be positive and finite");
  }
}

void check_count(const Reader& in, const char* field, std::size_t actual, std::size_t expected,
                 const std::string& because) {
  if (actual != expected) {
    in.fail(field, "has " + std::to_string(actual) + " values, expected " +
                       std::to_string(expected) + " (" + because + ")");
  }
}

void check_multiple(const Reader& in, const char* field, std::size_t size,
                    std::uint32_t dimension) {
  if (size % dimension != 0) {
    in.fail(field, "has " + std::to_string(size) + " values, not a multiple of the dimension " +
                       std::to_string(dimension));
  }
}

bool is_variable_name(const std::string& text) {
  if (text.empty()) return false;
  for (char c : text) {
    const bool word =
        (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_';
    if (!word) return false;
  }
  return true;
}

void check(const Reader&, const Hello&) {}
void check(const Reader&, const Welcome&) {}
void check(const Reader&, const ErrorMessage&) {}
void check(const Reader&, const AuthChallenge&) {}
void check(const Reader&, const AuthResponse&) {}
void check(const Reader&, const AuthProof&) {}
void check(const Reader&, const Heartbeat&) {}
void check(const Reader&, const Ready&) {}
void check(const Reader&, const Forces&) {}
void check(const Reader&, const SnapshotRequest&) {}
void check(const Reader&, const Shutdown&) {}
void check(const Reader&, const Goodbye&) {}

void check(const Reader& in, const Setup& m) {
  check_dimension(in, m.dimension);
  check_positive_finite(in, "time_step", m.time_step);
  for (std::size_t i = 0; i < m.liggghts_variables.size(); ++i) {
    const auto& variable = m.liggghts_variables[i];
    // Each variable becomes one LIGGGHTS command line on the client.
    if (!is_variable_name(variable.name)) {
      in.fail("liggghts_variables", "entry " + std::to_string(i) + " has the name '" +
                                        variable.name +
                                        "'; LIGGGHTS names are letters, digits and underscores");
    }
    if (variable.value.find_first_of(std::string_view("\n\r\0", 3)) != std::string::npos) {
      in.fail("liggghts_variables", "entry " + std::to_string(i) + " ('" + variable.name +
                                        "') has a line break or NUL in its value");
    }
  }
}

void check(const Reader& in, const Mesh& m) {
  check_dimension(in, m.dimension);
  check_positive_finite(in, "refinement_resolution", m.refinement_resolution);
  if (m.refinement_option > 3) {
    in.fail("refinement_option",
            "is " + std::to_string(m.refinement_option) + "; thesis Table 5.1 defines 0 to 3");
  }
  check_multiple(in, "positions", m.positions.size(), m.dimension);
  check_count(in, "velocities", m.velocities.size(), m.positions.size(), "one per position value");
  const std::size_t vertex_count = m.vertex_count();
  if (m.dynamic_vertex_count > vertex_count) {
    in.fail("dynamic_vertex_count", "is " + std::to_string(m.dynamic_vertex_count) +
                                        ", more than the " + std::to_string(vertex_count) +
                                        " vertices of the mesh");
  }
  // Segments in 2D and triangles in 3D: as many vertices per element as dimensions.
  if (m.element_vertices.size() % m.dimension != 0) {
    in.fail("element_vertices", "has " + std::to_string(m.element_vertices.size()) +
                                    " indices, not a multiple of the " +
                                    std::to_string(m.dimension) + " vertices per element");
  }
  for (std::size_t i = 0; i < m.element_vertices.size(); ++i) {
    if (m.element_vertices[i] >= vertex_count) {
      in.fail("element_vertices", "entry " + std::to_string(i) + " refers to vertex " +
                                      std::to_string(m.element_vertices[i]) + " of only " +
                                      std::to_string(vertex_count));
    }
  }
}

void check(const Reader& in, const Particles& m) {
  check_dimension(in, m.dimension);
  check_positive_finite(in, "mass", m.mass);
  check_positive_finite(in, "density", m.density);
  check_multiple(in, "positions", m.positions.size(), m.dimension);
  check_count(in, "velocities", m.velocities.size(), m.positions.size(), "one per position value");
}

void check(const Reader& in, const Step& m) {
  check_positive_finite(in, "time_step", m.time_step);
  check_count(in, "velocities", m.velocities.size(), m.positions.size(), "one per position value");
}

void check(const Reader& in, const Snapshot& m) {
  check_dimension(in, m.dimension);
  const std::size_t count = m.ids.size();
  const std::string per_id = std::to_string(m.dimension) + " per id";
  check_count(in, "positions", m.positions.size(), count * m.dimension, per_id);
  check_count(in, "velocities", m.velocities.size(), count * m.dimension, per_id);
  check_count(in, "density", m.density.size(), count, "one per id");
  check_count(in, "pressure", m.pressure.size(), count, "one per id");
}

// Encodes into the first bytes of buffer, which grows when it is too small but never shrinks
// (a channel reuses it: no allocation, zeroing or page faults for messages of a known size).
template <class T>
std::span<const std::byte> encode_message_into(const T& message, std::vector<std::byte>& buffer) {
  SizeCounter counter;
  layout(counter, message);
  if (buffer.size() < counter.size()) buffer.resize(counter.size());
  const auto bytes = std::span(buffer).first(counter.size());
  Writer writer(T::kType, bytes);
  layout(writer, message);
  writer.finish();
  return bytes;
}

template <class T>
std::vector<std::byte> encode_message(const T& message) {
  std::vector<std::byte> bytes;
  encode_message_into(message, bytes);
  return bytes;
}

}  // namespace

std::string name(ErrorCode code) {
  switch (code) {
    case ErrorCode::VersionMismatch:
      return "VersionMismatch";
    case ErrorCode::MalformedMessage:
      return "MalformedMessage";
    case ErrorCode::UnexpectedMessage:
      return "UnexpectedMessage";
    case ErrorCode::SetupFailed:
      return "SetupFailed";
    case ErrorCode::LiggghtsError:
      return "LiggghtsError";
    case ErrorCode::PeerAborted:
      return "PeerAborted";
    case ErrorCode::Internal:
      return "Internal";
    case ErrorCode::AuthenticationFailed:
      return "AuthenticationFailed";
  }
  return "code " + std::to_string(static_cast<std::uint32_t>(code));
}

PeerReportedError::PeerReportedError(ErrorCode code, const std::string& peer_text,
                                     const std::string& where)
    : ProtocolError("peer reported: " + peer_text + " [" + name(code) + "]", where,
                    "see the peer's output or log"),
      code_(code),
      peer_text_(peer_text) {}

std::optional<ErrorCode> error_code_for(const std::exception& failure, ErrorCode otherwise) {
  if (dynamic_cast<const PeerReportedError*>(&failure) != nullptr) return std::nullopt;
  if (dynamic_cast<const VersionMismatchError*>(&failure) != nullptr)
    return ErrorCode::VersionMismatch;
  if (dynamic_cast<const UnexpectedMessageError*>(&failure) != nullptr)
    return ErrorCode::UnexpectedMessage;
  if (dynamic_cast<const PeerTimeoutError*>(&failure) != nullptr) return ErrorCode::PeerAborted;
  if (dynamic_cast<const ProtocolError*>(&failure) != nullptr) return ErrorCode::MalformedMessage;
  return otherwise;
}

std::vector<std::byte> encode(const Hello& message) {
  return encode_message(message);
}
std::vector<std::byte> encode(const Welcome& message) {
  return encode_message(message);
}
std::vector<std::byte> encode(const ErrorMessage& message) {
  return encode_message(message);
}
std::vector<std::byte> encode(const AuthChallenge& message) {
  return encode_message(message);
}
std::vector<std::byte> encode(const AuthResponse& message) {
  return encode_message(message);
}
std::vector<std::byte> encode(const AuthProof& message) {
  return encode_message(message);
}
std::vector<std::byte> encode(const Heartbeat& message) {
  return encode_message(message);
}
std::vector<std::byte> encode(const Setup& message) {
  return encode_message(message);
}
std::vector<std::byte> encode(const Mesh& message) {
  return encode_message(message);
}
std::vector<std::byte> encode(const Particles& message) {
  return encode_message(message);
}
std::vector<std::byte> encode(const Ready& message) {
  return encode_message(message);
}
std::vector<std::byte> encode(const Step& message) {
  return encode_message(message);
}
std::vector<std::byte> encode(const Forces& message) {
  return encode_message(message);
}
std::vector<std::byte> encode(const SnapshotRequest& message) {
  return encode_message(message);
}
std::vector<std::byte> encode(const Snapshot& message) {
  return encode_message(message);
}
std::vector<std::byte> encode(const Shutdown& message) {
  return encode_message(message);
}
std::vector<std::byte> encode(const Goodbye& message) {
  return encode_message(message);
}
std::vector<std::byte> encode(const Message& message) {
  return std::visit([](const auto& alternative) { return encode_message(alternative); }, message);
}

template <class T>
std::span<const std::byte> encode_into(const T& message, std::vector<std::byte>& buffer) {
  return encode_message_into(message, buffer);
}

template std::span<const std::byte> encode_into(const Hello&, std::vector<std::byte>&);
template std::span<const std::byte> encode_into(const Welcome&, std::vector<std::byte>&);
template std::span<const std::byte> encode_into(const ErrorMessage&, std::vector<std::byte>&);
template std::span<const std::byte> encode_into(const AuthChallenge&, std::vector<std::byte>&);
template std::span<const std::byte> encode_into(const AuthResponse&, std::vector<std::byte>&);
template std::span<const std::byte> encode_into(const AuthProof&, std::vector<std::byte>&);
template std::span<const std::byte> encode_into(const Heartbeat&, std::vector<std::byte>&);
template std::span<const std::byte> encode_into(const Setup&, std::vector<std::byte>&);
template std::span<const std::byte> encode_into(const Mesh&, std::vector<std::byte>&);
template std::span<const std::byte> encode_into(const Particles&, std::vector<std::byte>&);
template std::span<const std::byte> encode_into(const Ready&, std::vector<std::byte>&);
template std::span<const std::byte> encode_into(const Step&, std::vector<std::byte>&);
template std::span<const std::byte> encode_into(const Forces&, std::vector<std::byte>&);
template std::span<const std::byte> encode_into(const SnapshotRequest&, std::vector<std::byte>&);
template std::span<const std::byte> encode_into(const Snapshot&, std::vector<std::byte>&);
template std::span<const std::byte> encode_into(const Shutdown&, std::vector<std::byte>&);
template std::span<const std::byte> encode_into(const Goodbye&, std::vector<std::byte>&);

template <class T>
T decode_as(std::span<const std::byte> payload) {
  Reader in(T::kType, payload);
  T message{};
  layout(in, message);
  in.finish();
  check(in, message);
  return message;
}

template Hello decode_as<Hello>(std::span<const std::byte>);
template Welcome decode_as<Welcome>(std::span<const std::byte>);
template ErrorMessage decode_as<ErrorMessage>(std::span<const std::byte>);
template AuthChallenge decode_as<AuthChallenge>(std::span<const std::byte>);
template AuthResponse decode_as<AuthResponse>(std::span<const std::byte>);
template AuthProof decode_as<AuthProof>(std::span<const std::byte>);
template Heartbeat decode_as<Heartbeat>(std::span<const std::byte>);
template Setup decode_as<Setup>(std::span<const std::byte>);
template Mesh decode_as<Mesh>(std::span<const std::byte>);
template Particles decode_as<Particles>(std::span<const std::byte>);
template Ready decode_as<Ready>(std::span<const std::byte>);
template Step decode_as<Step>(std::span<const std::byte>);
template Forces decode_as<Forces>(std::span<const std::byte>);
template SnapshotRequest decode_as<SnapshotRequest>(std::span<const std::byte>);
template Snapshot decode_as<Snapshot>(std::span<const std::byte>);
template Shutdown decode_as<Shutdown>(std::span<const std::byte>);
template Goodbye decode_as<Goodbye>(std::span<const std::byte>);

Message decode(MessageType type, std::span<const std::byte> payload) {
  switch (type) {
    case MessageType::Hello:
      return decode_as<Hello>(payload);
    case MessageType::Welcome:
      return decode_as<Welcome>(payload);
    case MessageType::Error:
      return decode_as<ErrorMessage>(payload);
    case MessageType::AuthChallenge:
      return decode_as<AuthChallenge>(payload);
    case MessageType::AuthResponse:
      return decode_as<AuthResponse>(payload);
    case MessageType::AuthProof:
      return decode_as<AuthProof>(payload);
    case MessageType::Heartbeat:
      return decode_as<Heartbeat>(payload);
    case MessageType::Setup:
      return decode_as<Setup>(payload);
    case MessageType::Mesh:
      return decode_as<Mesh>(payload);
    case MessageType::Particles:
      return decode_as<Particles>(payload);
    case MessageType::Ready:
      return decode_as<Ready>(payload);
    case MessageType::Step:
      return decode_as<Step>(payload);
    case MessageType::Forces:
      return decode_as<Forces>(payload);
    case MessageType::SnapshotRequest:
      return decode_as<SnapshotRequest>(payload);
    case MessageType::Snapshot:
      return decode_as<Snapshot>(payload);
    case MessageType::Shutdown:
      return decode_as<Shutdown>(payload);
    case MessageType::Goodbye:
      return decode_as<Goodbye>(payload);
  }
  throw ProtocolError("cannot decode a message of " + name(type) + ", which protocol " +
                          version_text(kMajorVersion, kMinorVersion) + " does not define",
                      "message decoder", "use matching releases of fsi-server and fsi-client");
}

MessageType type_of(const Message& message) {
  return std::visit([](const auto& m) { return std::decay_t<decltype(m)>::kType; }, message);
}

}  // namespace fsi::protocol
