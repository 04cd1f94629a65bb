// Message codecs. Each message's byte layout is written down once, in a layout() function that
// walks its fields in wire order; the size counter, the writer and the reader all walk it, so the
// encoder and the decoder cannot drift apart. Content checks that need the whole message (sizes
// that must agree, indices in range) live in check() and run after a complete read.
#include "fsi/protocol/messages.hpp"

#include <algorithm>
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

void layout(auto& io, MessageOf<Settling> auto& m) {
  for (auto& component : m.gravity)
    io.scalar("gravity", component);
  io.scalar("column_height", m.column_height);
  io.scalar("drag_rate", m.drag_rate);
  io.array("initial_densities", m.initial_densities);
}

void layout(auto& io, MessageOf<ReleaseState> auto& m) {
  io.scalar("drag_rate", m.drag_rate);
  io.scalar("column_height", m.column_height);
  io.scalar("fluid_mass", m.fluid_mass);
  io.scalar("kinetic_energy", m.kinetic_energy);
  io.scalar("potential_energy", m.potential_energy);
}

void layout(auto& io, MessageOf<ProbeSetup> auto& m) {
  io.scalar("every_steps", m.every_steps);
  for (auto& component : m.gravity)
    io.scalar("gravity", component);
  io.scalar("particle_spacing", m.particle_spacing);
  // A record is a kind, a name's length and a parameter count: at least 16 bytes.
  io.records("probes", m.probes, 16, [](auto& record_io, auto& probe) {
    record_io.scalar("kind", probe.kind);
    record_io.text("name", probe.name);
    record_io.array("parameters", probe.parameters);
  });
}

void layout(auto& io, MessageOf<ProbePlacement> auto& m) {
  io.scalar("step", m.step);
  // A record is an index and a parameter count: at least 12 bytes.
  io.records("probes", m.probes, 12, [](auto& record_io, auto& probe) {
    record_io.scalar("index", probe.index);
    record_io.array("parameters", probe.parameters);
  });
}

void layout(auto& io, MessageOf<Step> auto& m) {
  io.scalar("step", m.step);
  io.scalar("time", m.time);
  io.scalar("time_step", m.time_step);
  io.array("positions", m.positions);
  io.array("velocities", m.velocities);
}

void layout(auto& io, MessageOf<StepMotion> auto& m) {
  io.scalar("step", m.step);
  io.scalar("time", m.time);
  io.scalar("time_step", m.time_step);
  io.scalar("substeps", m.substeps);
  io.array("nodes", m.nodes);
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

void layout(auto& io, MessageOf<ProbeValues> auto& m) {
  io.scalar("step", m.step);
  io.array("values", m.values);
}

void layout(auto& io, MessageOf<FluidHealth> auto& m) {
  io.scalar("step", m.step);
  io.scalar("particle_count", m.particle_count);
  io.scalar("non_finite_particles", m.non_finite_particles);
  io.scalar("min_density", m.min_density);
  io.scalar("max_density", m.max_density);
  io.scalar("max_speed", m.max_speed);
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

void layout(auto& io, MessageOf<CheckpointRequest> auto& m) {
  io.scalar("step", m.step);
}

void layout(auto& io, MessageOf<FluidState> auto& m) {
  io.scalar("step", m.step);
  io.scalar("particle_count", m.particle_count);
  io.text("state", m.state);
}

void layout(auto& io, MessageOf<Resume> auto& m) {
  io.scalar("step", m.step);
  io.scalar("time", m.time);
  io.text("state", m.state);
}

void layout(auto& io, MessageOf<Shutdown> auto& m) {
  io.text("reason", m.reason);
}

void layout(auto& io, MessageOf<Goodbye> auto& m) {
  io.scalar("steps_done", m.steps_done);
  io.scalar("seconds_total", m.seconds_total);
}

// ---- the walkers: byte counters, Writer, Gatherer, Reader ----

class Writer {
 public:
  Writer(MessageType type, std::span<std::byte> bytes) : type_(type), bytes_(bytes) {}

  template <class T>
  void scalar(const char*, const T& value) {
    static_assert(std::is_trivially_copyable_v<T>);
    put(&value, sizeof(T));
  }
  void text(const char* field, const std::string& value) {
    check_text_length(field, value.size());
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
  // For Gatherer, whose bytes may be the first part of a larger buffer.
  void finish_part() const {
    FSI_ASSERT(offset_ <= bytes_.size(), "gather counter and gatherer disagree on " + name(type_));
  }
  std::size_t offset() const { return offset_; }
  void check_text_length(const char* field, std::size_t size) const {
    if (size > std::numeric_limits<std::uint32_t>::max()) {
      throw ProtocolError("cannot encode " + name(type_) + " field '" + field + "': a string of " +
                              std::to_string(size) + " bytes does not fit a u32 length",
                          "encoding " + name(type_), "shorten the text");
    }
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

// Gathering: like Writer, but arrays and strings of at least kGatherMinimumBytes stay where they
// are and become pieces of their own. Doubles and integers are sent as the bytes they are stored
// in, which is the wire format on a little-endian IEEE-754 host (static_assert above); another
// host would copy them, converted, like the small fields.
constexpr bool kStorageIsWireFormat = std::endian::native == std::endian::little;

bool referenced(std::size_t bytes) {
  return kStorageIsWireFormat && bytes >= kGatherMinimumBytes;
}

// Counts the bytes of a message's encoding: all of them (SizeCounter), or only those a Gatherer
// copies into GatheredPayload::encoded, leaving out what it references in place (GatherCounter).
template <bool kLeaveOutReferenced>
class ByteCounter {
 public:
  template <class T>
  void scalar(const char*, const T&) {
    size_ += sizeof(T);
  }
  void text(const char*, const std::string& value) {
    size_ += sizeof(std::uint32_t) + copied(value.size());
  }
  template <class T>
  void array(const char*, const std::vector<T>& values) {
    size_ += sizeof(std::uint64_t) + copied(values.size() * sizeof(T));
  }
  template <class T, class Each>
  void records(const char*, const std::vector<T>& items, std::size_t, Each&& each) {
    size_ += sizeof(std::uint64_t);
    for (const T& item : items)
      each(*this, item);
  }
  std::size_t size() const { return size_; }

 private:
  static std::size_t copied(std::size_t bytes) {
    return kLeaveOutReferenced && referenced(bytes) ? 0 : bytes;
  }
  std::size_t size_ = 0;
};
using SizeCounter = ByteCounter<false>;
using GatherCounter = ByteCounter<true>;

class Gatherer {
 public:
  // payload.encoded holds at least as many bytes as GatherCounter counted.
  Gatherer(MessageType type, GatheredPayload& payload)
      : copy_(type, payload.encoded), out_(payload) {
    out_.pieces.clear();
    out_.size = 0;
  }
  template <class T>
  void scalar(const char* field, const T& value) {
    copy_.scalar(field, value);
  }
  void text(const char* field, const std::string& value) {
    if (!referenced(value.size())) return copy_.text(field, value);
    copy_.check_text_length(field, value.size());
    const auto length = static_cast<std::uint32_t>(value.size());
    copy_.scalar(field, length);
    reference(value.data(), value.size());
  }
  template <class T>
  void array(const char* field, const std::vector<T>& values) {
    const std::size_t bytes = values.size() * sizeof(T);
    if (!referenced(bytes)) return copy_.array(field, values);
    const std::uint64_t count = values.size();
    copy_.scalar(field, count);
    reference(values.data(), bytes);
  }
  template <class T, class Each>
  void records(const char*, const std::vector<T>& items, std::size_t, Each&& each) {
    const std::uint64_t count = items.size();
    copy_.scalar("", count);
    for (const T& item : items)
      each(*this, item);
  }
  void finish() {
    close_encoded_piece();
    copy_.finish_part();
  }

 private:
  void reference(const void* data, std::size_t size) {
    close_encoded_piece();
    out_.pieces.emplace_back(static_cast<const std::byte*>(data), size);
    out_.size += size;
  }
  void close_encoded_piece() {
    const std::size_t end = copy_.offset();
    if (end > piece_start_) {
      out_.pieces.push_back(
          std::span<const std::byte>(out_.encoded).subspan(piece_start_, end - piece_start_));
      out_.size += end - piece_start_;
    }
    piece_start_ = end;
  }

  Writer copy_;
  GatheredPayload& out_;
  std::size_t piece_start_ = 0;
};

// Where Reader gets its bytes when the whole payload is in memory.
class SpanSource final : public PayloadSource {
 public:
  explicit SpanSource(std::span<const std::byte> bytes) : bytes_(bytes) {}
  std::size_t remaining() const override { return bytes_.size() - offset_; }
  std::size_t available() const override { return remaining(); }
  void read(std::span<std::byte> into) override {
    if (!into.empty()) std::memcpy(into.data(), bytes_.data() + offset_, into.size());
    offset_ += into.size();
  }

 private:
  std::span<const std::byte> bytes_;
  std::size_t offset_ = 0;
};

class Reader {
 public:
  Reader(MessageType type, PayloadSource& source)
      : type_(type), source_(source), size_(source.remaining()) {}

  template <class T>
  void scalar(const char* field, T& value) {
    static_assert(std::is_trivially_copyable_v<T>);
    begin(field);
    need(sizeof(T), "a " + std::to_string(sizeof(T)) + "-byte value");
    take(&value, sizeof(T));
  }
  void text(const char* field, std::string& value) {
    begin(field);
    std::uint32_t length = 0;
    need(sizeof length, "its 4-byte length");
    take(&length, sizeof length);
    need(length, "a string of " + std::to_string(length) + " bytes");
    fill(value, length);
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
    fill(values, static_cast<std::size_t>(count));
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
    if (offset_ != size_) {
      current_field_ = "(end of message)";
      fail_here(std::to_string(size_ - offset_) +
                " bytes follow the last field; the message has fewer");
    }
    source_.end();
  }

  // For content checks after the read: names the field and the offset where it began.
  [[noreturn]] void fail(std::string_view field, const std::string& problem) const {
    std::size_t offset = size_;
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

  // The first part of a vector or string is read into at most this much memory unless the bytes
  // are already here; it then doubles with the bytes that actually arrive.
  static constexpr std::size_t kFirstPieceBytes = std::size_t{1} << 20;

  void begin(const char* field) {
    current_field_ =
        record_ ? std::string(record_->field) + "[" + std::to_string(record_->index) + "]." + field
                : std::string(field);
    field_start_ = offset_;
    if (!record_) field_offsets_.emplace_back(field, offset_);
  }
  std::size_t remaining() const { return size_ - offset_; }
  void need(std::size_t size, const std::string& what) const {
    if (size > remaining()) {
      fail_here("is truncated: needs " + what + ", but only " + std::to_string(remaining()) +
                " bytes remain");
    }
  }
  void take(void* into, std::size_t size) {
    source_.read(std::span(static_cast<std::byte*>(into), size));
    offset_ += size;
  }
  // Reads count elements (already checked against remaining()) into a vector or string. Storage
  // that is big enough is reused as it is; otherwise it grows only as far as the bytes that are
  // here or have arrived, so a false count cannot make us allocate memory the peer never fills.
  template <class Container>
  void fill(Container& values, std::size_t count) {
    using Element = typename Container::value_type;
    const std::size_t bytes = count * sizeof(Element);
    if (count > values.capacity() && bytes > source_.available()) {
      // Growing the destination step by step would copy and first-touch it several times; a
      // buffer the source reuses from frame to frame costs one copy.
      const auto buffered = source_.read_buffered(bytes);
      if (buffered.size() == bytes) {
        offset_ += bytes;
        values.resize(count);
        std::memcpy(values.data(), buffered.data(), bytes);
        return;
      }
    }
    const std::size_t at_once = std::max({values.capacity(), source_.available() / sizeof(Element),
                                          kFirstPieceBytes / sizeof(Element)});
    std::size_t filled = 0;
    do {
      const std::size_t target = std::min(count, std::max(at_once, 2 * filled));
      values.resize(target);
      take(values.data() + filled, (target - filled) * sizeof(Element));
      filled = target;
    } while (filled < count);
  }
  std::uint64_t read_count() {
    std::uint64_t count = 0;
    need(sizeof count, "its 8-byte element count");
    take(&count, sizeof count);
    return count;
  }
  [[noreturn]] void fail_here(const std::string& problem) const {
    throw_error(current_field_, field_start_, problem);
  }
  [[noreturn]] void throw_error(const std::string& field, std::size_t offset,
                                const std::string& problem) const {
    throw ProtocolError(
        "malformed " + name(type_) + " message: field '" + field + "' " + problem,
        name(type_) + " payload byte " + std::to_string(offset) + " of " + std::to_string(size_),
        "the peer is faulty or speaks another protocol version; use matching "
        "releases of fsi-server and fsi-client");
  }

  MessageType type_;
  PayloadSource& source_;
  std::size_t size_;
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

void check_not_negative_finite(const Reader& in, const char* field, double value) {
  if (!(value >= 0.0) || !std::isfinite(value)) {
    char text[64];
    std::snprintf(text, sizeof text, "%.17g", value);
    in.fail(field, std::string("is ") + text + "; it must be zero or positive, and finite");
  }
}

void check_finite(const Reader& in, const char* field, double value) {
  if (!std::isfinite(value)) {
    char text[64];
    std::snprintf(text, sizeof text, "%.17g", value);
    in.fail(field, std::string("is ") + text + "; it must be finite");
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

// Messages whose fields need no agreement among themselves; the overloads below check the others.
void check(const Reader&, const ProtocolMessage auto&) {}

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
  // No particles (the scripts create the fluid): mass and density describe nothing and may be 0.
  if (m.positions.empty()) {
    check_not_negative_finite(in, "mass", m.mass);
    check_not_negative_finite(in, "density", m.density);
  } else {
    check_positive_finite(in, "mass", m.mass);
    check_positive_finite(in, "density", m.density);
  }
  check_multiple(in, "positions", m.positions.size(), m.dimension);
  check_count(in, "velocities", m.velocities.size(), m.positions.size(), "one per position value");
}

void check(const Reader& in, const Settling& m) {
  for (const double component : m.gravity)
    check_finite(in, "gravity", component);
  check_not_negative_finite(in, "column_height", m.column_height);
  check_finite(in, "drag_rate", m.drag_rate);
  for (const double density : m.initial_densities)
    check_positive_finite(in, "initial_densities", density);
}

void check(const Reader& in, const ReleaseState& m) {
  check_not_negative_finite(in, "drag_rate", m.drag_rate);
  check_not_negative_finite(in, "column_height", m.column_height);
  check_not_negative_finite(in, "fluid_mass", m.fluid_mass);
  check_not_negative_finite(in, "kinetic_energy", m.kinetic_energy);
  check_not_negative_finite(in, "potential_energy", m.potential_energy);
}

void check(const Reader& in, const ProbeSetup& m) {
  if (m.every_steps == 0) in.fail("every_steps", "is 0; probes are evaluated every N >= 1 steps");
  for (const double component : m.gravity)
    check_finite(in, "gravity", component);
  check_not_negative_finite(in, "particle_spacing", m.particle_spacing);
  for (std::size_t i = 0; i < m.probes.size(); ++i) {
    // Each name starts the names of sensors.csv columns.
    if (m.probes[i].name.empty())
      in.fail("probes", "entry " + std::to_string(i) + " has an empty name");
    for (const double parameter : m.probes[i].parameters)
      check_finite(in, "probes", parameter);
  }
}

void check(const Reader& in, const ProbePlacement& m) {
  for (std::size_t i = 0; i < m.probes.size(); ++i) {
    for (std::size_t j = 0; j < i; ++j) {
      if (m.probes[j].index == m.probes[i].index)
        in.fail("probes", "entry " + std::to_string(i) + " places probe " +
                              std::to_string(m.probes[i].index) + " a second time");
    }
    for (const double parameter : m.probes[i].parameters)
      check_finite(in, "probes", parameter);
  }
}

void check(const Reader& in, const Step& m) {
  check_positive_finite(in, "time_step", m.time_step);
  check_count(in, "velocities", m.velocities.size(), m.positions.size(), "one per position value");
}

void check(const Reader& in, const StepMotion& m) {
  check_positive_finite(in, "time_step", m.time_step);
  if (m.substeps < 2)
    in.fail("substeps", "is " + std::to_string(m.substeps) + "; a StepMotion has at least 2");
  if (m.nodes.size() < 2 || m.nodes.size() > 8)
    in.fail("nodes", "has " + std::to_string(m.nodes.size()) + " entries, not 2 to 8");
  for (std::size_t i = 0; i < m.nodes.size(); ++i) {
    if (!(m.nodes[i] >= 0.0 && m.nodes[i] <= 1.0) || (i > 0 && !(m.nodes[i] > m.nodes[i - 1])))
      in.fail("nodes", "entry " + std::to_string(i) + " breaks 0 <= theta_0 < ... <= 1");
  }
  if (m.nodes.back() != 1.0) in.fail("nodes", "the last is not 1 (the end of the step)");
  if (m.positions.size() % m.nodes.size() != 0) {
    in.fail("positions", "has " + std::to_string(m.positions.size()) +
                             " values, not a multiple of the " + std::to_string(m.nodes.size()) +
                             " nodes");
  }
  check_count(in, "velocities", m.velocities.size(), m.positions.size(), "one per position value");
}

// The extremes may be infinite (no finite particle) or NaN-free garbage of a failing fluid: the
// server judges them; only the counts must agree.
void check(const Reader& in, const FluidHealth& m) {
  if (m.non_finite_particles > m.particle_count) {
    in.fail("non_finite_particles", "is " + std::to_string(m.non_finite_particles) +
                                        ", more than the " + std::to_string(m.particle_count) +
                                        " particles");
  }
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
void gather_message(const T& message, GatheredPayload& payload) {
  GatherCounter counter;
  layout(counter, message);
  if (payload.encoded.size() < counter.size()) payload.encoded.resize(counter.size());
  Gatherer gatherer(T::kType, payload);
  layout(gatherer, message);
  gatherer.finish();
}

template <class T>
std::vector<std::byte> encode_message(const T& message) {
  std::vector<std::byte> bytes;
  encode_message_into(message, bytes);
  return bytes;
}

template <class T>
Message decode_as_new(PayloadSource& source) {
  T message{};
  decode_into(source, message);
  return message;
}

}  // namespace

std::string name(ErrorCode code) {
  switch (code) {
#define FSI_PROTOCOL_ERROR_CODE_NAME(enumerator, value) \
  case ErrorCode::enumerator:                           \
    return #enumerator;
    FSI_PROTOCOL_ERROR_CODES(FSI_PROTOCOL_ERROR_CODE_NAME)
#undef FSI_PROTOCOL_ERROR_CODE_NAME
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

template <ProtocolMessage T>
std::vector<std::byte> encode(const T& message) {
  return encode_message(message);
}

std::vector<std::byte> encode(const Message& message) {
  return std::visit([](const auto& alternative) { return encode_message(alternative); }, message);
}

template <ProtocolMessage T>
std::span<const std::byte> encode_into(const T& message, std::vector<std::byte>& buffer) {
  return encode_message_into(message, buffer);
}

template <ProtocolMessage T>
void encode_gathered(const T& message, GatheredPayload& payload) {
  gather_message(message, payload);
}

template <ProtocolMessage T>
void decode_into(PayloadSource& source, T& message) {
  Reader in(T::kType, source);
  layout(in, message);
  in.finish();
  check(in, message);
}

template <ProtocolMessage T>
T decode_as(std::span<const std::byte> payload) {
  SpanSource source(payload);
  T message{};
  decode_into(source, message);
  return message;
}

// The codec of every listed message is compiled here, where its layout() is.
#define FSI_PROTOCOL_INSTANTIATE_CODEC(enumerator, message, id)                             \
  template std::vector<std::byte> encode(const message&);                                   \
  template std::span<const std::byte> encode_into(const message&, std::vector<std::byte>&); \
  template void encode_gathered(const message&, GatheredPayload&);                          \
  template void decode_into(PayloadSource&, message&);                                      \
  template message decode_as<message>(std::span<const std::byte>);
FSI_PROTOCOL_MESSAGES(FSI_PROTOCOL_INSTANTIATE_CODEC)
#undef FSI_PROTOCOL_INSTANTIATE_CODEC

Message decode(MessageType type, std::span<const std::byte> payload) {
  SpanSource source(payload);
  return decode(type, source);
}

Message decode(MessageType type, PayloadSource& source) {
  switch (type) {
#define FSI_PROTOCOL_DECODE_CASE(enumerator, message, id) \
  case MessageType::enumerator:                           \
    return decode_as_new<message>(source);
    FSI_PROTOCOL_MESSAGES(FSI_PROTOCOL_DECODE_CASE)
#undef FSI_PROTOCOL_DECODE_CASE
  }
  throw ProtocolError("cannot decode a message of " + name(type) + ", which protocol " +
                          version_text(kMajorVersion, kMinorVersion) + " does not define",
                      "message decoder", "use matching releases of fsi-server and fsi-client");
}

MessageType type_of(const Message& message) {
  return std::visit([](const auto& m) { return std::decay_t<decltype(m)>::kType; }, message);
}

}  // namespace fsi::protocol
