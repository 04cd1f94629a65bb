#include "fsi/protocol/messages.hpp"

#include <bit>
#include <cstring>
#include <limits>

namespace fsi::protocol {
namespace {

static_assert(std::endian::native == std::endian::little,
              "the codec copies little-endian values directly; add byte swapping for this host");

class Writer {
 public:
  template <class T>
  void value(T v) {
    static_assert(std::is_trivially_copyable_v<T>);
    const auto* p = reinterpret_cast<const std::byte*>(&v);
    bytes_.insert(bytes_.end(), p, p + sizeof(T));
  }
  void text(const std::string& s) {
    if (s.size() > std::numeric_limits<std::uint32_t>::max()) {
      throw ProtocolError("string of " + std::to_string(s.size()) + " bytes is too long",
                          "encoding", "shorten the text");
    }
    value<std::uint32_t>(static_cast<std::uint32_t>(s.size()));
    const auto* p = reinterpret_cast<const std::byte*>(s.data());
    bytes_.insert(bytes_.end(), p, p + s.size());
  }
  template <class T>
  void array(const std::vector<T>& items) {
    value<std::uint64_t>(items.size());
    const auto* p = reinterpret_cast<const std::byte*>(items.data());
    bytes_.insert(bytes_.end(), p, p + items.size() * sizeof(T));
  }
  std::vector<std::byte> take() { return std::move(bytes_); }

 private:
  std::vector<std::byte> bytes_;
};

class Reader {
 public:
  Reader(MessageType type, std::span<const std::byte> bytes) : type_(type), bytes_(bytes) {}

  template <class T>
  T value(const char* field) {
    need(sizeof(T), field);
    T v;
    std::memcpy(&v, bytes_.data() + offset_, sizeof(T));
    offset_ += sizeof(T);
    return v;
  }
  std::string text(const char* field) {
    const auto length = value<std::uint32_t>(field);
    need(length, field);
    std::string s(reinterpret_cast<const char*>(bytes_.data() + offset_), length);
    offset_ += length;
    return s;
  }
  template <class T>
  std::vector<T> array(const char* field) {
    const auto count = value<std::uint64_t>(field);
    // Checked against what is left before anything is allocated.
    if (count > (bytes_.size() - offset_) / sizeof(T)) {
      fail(field, "announces " + std::to_string(count) + " elements of " +
                      std::to_string(sizeof(T)) + " bytes but only " +
                      std::to_string(bytes_.size() - offset_) + " bytes remain");
    }
    std::vector<T> items(count);
    std::memcpy(items.data(), bytes_.data() + offset_, count * sizeof(T));
    offset_ += count * sizeof(T);
    return items;
  }
  void finish() {
    if (offset_ != bytes_.size()) {
      fail("end", std::to_string(bytes_.size() - offset_) + " unexpected trailing bytes");
    }
  }
  [[noreturn]] void fail(const char* field, const std::string& what) const {
    throw ProtocolError("malformed " + name(type_) + " message: field '" + field + "' " + what,
                        name(type_) + " payload byte " + std::to_string(offset_),
                        "the peer is faulty or speaks another protocol version");
  }

 private:
  void need(std::size_t n, const char* field) const {
    if (n > bytes_.size() - offset_) {
      fail(field, "is truncated (needs " + std::to_string(n) + " bytes, " +
                      std::to_string(bytes_.size() - offset_) + " remain)");
    }
  }

  MessageType type_;
  std::span<const std::byte> bytes_;
  std::size_t offset_ = 0;
};

void check_dimension(Reader& in, std::uint32_t dimension) {
  if (dimension != 2 && dimension != 3)
    in.fail("dimension", "is " + std::to_string(dimension) + ", not 2 or 3");
}

void check_per_item(Reader& in, const char* field, std::size_t size, std::size_t per_item,
                    std::size_t items) {
  if (size != per_item * items) {
    in.fail(field, "has " + std::to_string(size) + " values, expected " +
                       std::to_string(per_item * items));
  }
}

}  // namespace

std::vector<std::byte> encode(const Hello& m) {
  Writer out;
  out.text(m.software_version);
  out.text(m.host);
  out.value(m.mpi_ranks);
  out.value(m.capabilities);
  return out.take();
}
std::vector<std::byte> encode(const Welcome& m) {
  Writer out;
  out.value(m.accepted_minor);
  out.value(m.capabilities);
  out.text(m.software_version);
  out.text(m.run_name);
  return out.take();
}
std::vector<std::byte> encode(const ErrorMessage& m) {
  Writer out;
  out.value(static_cast<std::uint32_t>(m.code));
  out.text(m.text);
  return out.take();
}
std::vector<std::byte> encode(const Setup& m) {
  Writer out;
  out.value(m.dimension);
  out.value(m.time_step);
  out.value(m.equilibration_steps);
  out.value<std::uint64_t>(m.liggghts_variables.size());
  for (const auto& variable : m.liggghts_variables) {
    out.text(variable.name);
    out.text(variable.value);
  }
  out.text(m.script1_name);
  out.text(m.script1_text);
  out.text(m.script2_name);
  out.text(m.script2_text);
  return out.take();
}
std::vector<std::byte> encode(const Mesh& m) {
  Writer out;
  out.value(m.dimension);
  out.value(m.dynamic_vertex_count);
  out.value(m.refinement_option);
  out.value(m.refinement_resolution);
  out.array(m.positions);
  out.array(m.velocities);
  out.array(m.element_vertices);
  return out.take();
}
std::vector<std::byte> encode(const Particles& m) {
  Writer out;
  out.value(m.dimension);
  out.value(m.atom_type);
  out.value(m.mass);
  out.value(m.density);
  out.array(m.positions);
  out.array(m.velocities);
  return out.take();
}
std::vector<std::byte> encode(const Ready& m) {
  Writer out;
  out.value(m.particle_count);
  out.text(m.liggghts_version);
  out.value(m.seconds_setup);
  out.value(m.seconds_equilibration);
  return out.take();
}
std::vector<std::byte> encode(const Step& m) {
  Writer out;
  out.value(m.step);
  out.value(m.time);
  out.value(m.time_step);
  out.array(m.positions);
  out.array(m.velocities);
  return out.take();
}
std::vector<std::byte> encode(const Forces& m) {
  Writer out;
  out.value(m.step);
  out.array(m.forces);
  const auto& d = m.diagnostics;
  for (double v : d.force_on_fluid)
    out.value(v);
  for (double v : d.force_on_structure)
    out.value(v);
  out.value(d.pair_force_magnitude_sum);
  out.value(d.particles_in_range);
  out.value(d.closest_approach_over_r0);
  out.value(d.particle_count);
  out.value(d.seconds_liggghts);
  out.value(d.seconds_contact);
  out.value(d.seconds_client_communication);
  return out.take();
}
std::vector<std::byte> encode(const SnapshotRequest& m) {
  Writer out;
  out.value(m.step);
  return out.take();
}
std::vector<std::byte> encode(const Snapshot& m) {
  Writer out;
  out.value(m.step);
  out.value(m.time);
  out.value(m.dimension);
  out.array(m.ids);
  out.array(m.positions);
  out.array(m.velocities);
  out.array(m.density);
  out.array(m.pressure);
  return out.take();
}
std::vector<std::byte> encode(const Shutdown& m) {
  Writer out;
  out.text(m.reason);
  return out.take();
}
std::vector<std::byte> encode(const Goodbye& m) {
  Writer out;
  out.value(m.steps_done);
  out.value(m.seconds_total);
  return out.take();
}

Message decode(MessageType type, std::span<const std::byte> payload) {
  Reader in(type, payload);
  Message result;
  switch (type) {
    case MessageType::Hello: {
      Hello m;
      m.software_version = in.text("software_version");
      m.host = in.text("host");
      m.mpi_ranks = in.value<std::uint32_t>("mpi_ranks");
      m.capabilities = in.value<std::uint32_t>("capabilities");
      result = std::move(m);
      break;
    }
    case MessageType::Welcome: {
      Welcome m;
      m.accepted_minor = in.value<std::uint16_t>("accepted_minor");
      m.capabilities = in.value<std::uint32_t>("capabilities");
      m.software_version = in.text("software_version");
      m.run_name = in.text("run_name");
      result = std::move(m);
      break;
    }
    case MessageType::Error: {
      ErrorMessage m;
      m.code = static_cast<ErrorCode>(in.value<std::uint32_t>("code"));
      m.text = in.text("text");
      result = std::move(m);
      break;
    }
    case MessageType::Setup: {
      Setup m;
      m.dimension = in.value<std::uint32_t>("dimension");
      check_dimension(in, m.dimension);
      m.time_step = in.value<double>("time_step");
      m.equilibration_steps = in.value<std::uint64_t>("equilibration_steps");
      const auto count = in.value<std::uint64_t>("liggghts_variables");
      // Each variable needs at least two 4-byte lengths.
      if (count > payload.size() / 8) in.fail("liggghts_variables", "count is implausible");
      for (std::uint64_t i = 0; i < count; ++i) {
        LiggghtsVariable variable;
        variable.name = in.text("liggghts_variables.name");
        variable.value = in.text("liggghts_variables.value");
        m.liggghts_variables.push_back(std::move(variable));
      }
      m.script1_name = in.text("script1_name");
      m.script1_text = in.text("script1_text");
      m.script2_name = in.text("script2_name");
      m.script2_text = in.text("script2_text");
      result = std::move(m);
      break;
    }
    case MessageType::Mesh: {
      Mesh m;
      m.dimension = in.value<std::uint32_t>("dimension");
      check_dimension(in, m.dimension);
      m.dynamic_vertex_count = in.value<std::uint32_t>("dynamic_vertex_count");
      m.refinement_option = in.value<std::uint32_t>("refinement_option");
      m.refinement_resolution = in.value<double>("refinement_resolution");
      if (!(m.refinement_resolution > 0.0) ||
          m.refinement_resolution == std::numeric_limits<double>::infinity()) {
        in.fail("refinement_resolution", "must be a positive finite length");
      }
      m.positions = in.array<double>("positions");
      m.velocities = in.array<double>("velocities");
      m.element_vertices = in.array<std::uint32_t>("element_vertices");
      if (m.positions.size() % m.dimension != 0)
        in.fail("positions", "is not a multiple of the dimension");
      check_per_item(in, "velocities", m.velocities.size(), 1, m.positions.size());
      if (m.dynamic_vertex_count > m.vertex_count()) {
        in.fail("dynamic_vertex_count",
                "exceeds the vertex count " + std::to_string(m.vertex_count()));
      }
      if (m.element_vertices.size() % m.dimension != 0) {
        in.fail("element_vertices", "is not a multiple of the vertices per element");
      }
      for (std::uint32_t index : m.element_vertices) {
        if (index >= m.vertex_count()) {
          in.fail("element_vertices", "refers to vertex " + std::to_string(index) + " of " +
                                          std::to_string(m.vertex_count()));
        }
      }
      result = std::move(m);
      break;
    }
    case MessageType::Particles: {
      Particles m;
      m.dimension = in.value<std::uint32_t>("dimension");
      check_dimension(in, m.dimension);
      m.atom_type = in.value<std::uint32_t>("atom_type");
      m.mass = in.value<double>("mass");
      m.density = in.value<double>("density");
      m.positions = in.array<double>("positions");
      m.velocities = in.array<double>("velocities");
      if (m.positions.size() % m.dimension != 0)
        in.fail("positions", "is not a multiple of the dimension");
      check_per_item(in, "velocities", m.velocities.size(), 1, m.positions.size());
      result = std::move(m);
      break;
    }
    case MessageType::Ready: {
      Ready m;
      m.particle_count = in.value<std::uint64_t>("particle_count");
      m.liggghts_version = in.text("liggghts_version");
      m.seconds_setup = in.value<double>("seconds_setup");
      m.seconds_equilibration = in.value<double>("seconds_equilibration");
      result = std::move(m);
      break;
    }
    case MessageType::Step: {
      Step m;
      m.step = in.value<std::uint64_t>("step");
      m.time = in.value<double>("time");
      m.time_step = in.value<double>("time_step");
      m.positions = in.array<double>("positions");
      m.velocities = in.array<double>("velocities");
      check_per_item(in, "velocities", m.velocities.size(), 1, m.positions.size());
      result = std::move(m);
      break;
    }
    case MessageType::Forces: {
      Forces m;
      m.step = in.value<std::uint64_t>("step");
      m.forces = in.array<double>("forces");
      auto& d = m.diagnostics;
      for (double& v : d.force_on_fluid)
        v = in.value<double>("force_on_fluid");
      for (double& v : d.force_on_structure)
        v = in.value<double>("force_on_structure");
      d.pair_force_magnitude_sum = in.value<double>("pair_force_magnitude_sum");
      d.particles_in_range = in.value<std::uint64_t>("particles_in_range");
      d.closest_approach_over_r0 = in.value<double>("closest_approach_over_r0");
      d.particle_count = in.value<std::uint64_t>("particle_count");
      d.seconds_liggghts = in.value<double>("seconds_liggghts");
      d.seconds_contact = in.value<double>("seconds_contact");
      d.seconds_client_communication = in.value<double>("seconds_client_communication");
      result = std::move(m);
      break;
    }
    case MessageType::SnapshotRequest: {
      SnapshotRequest m;
      m.step = in.value<std::uint64_t>("step");
      result = m;
      break;
    }
    case MessageType::Snapshot: {
      Snapshot m;
      m.step = in.value<std::uint64_t>("step");
      m.time = in.value<double>("time");
      m.dimension = in.value<std::uint32_t>("dimension");
      check_dimension(in, m.dimension);
      m.ids = in.array<std::uint64_t>("ids");
      m.positions = in.array<double>("positions");
      m.velocities = in.array<double>("velocities");
      m.density = in.array<double>("density");
      m.pressure = in.array<double>("pressure");
      const std::size_t n = m.ids.size();
      check_per_item(in, "positions", m.positions.size(), m.dimension, n);
      check_per_item(in, "velocities", m.velocities.size(), m.dimension, n);
      check_per_item(in, "density", m.density.size(), 1, n);
      check_per_item(in, "pressure", m.pressure.size(), 1, n);
      result = std::move(m);
      break;
    }
    case MessageType::Shutdown: {
      Shutdown m;
      m.reason = in.text("reason");
      result = std::move(m);
      break;
    }
    case MessageType::Goodbye: {
      Goodbye m;
      m.steps_done = in.value<std::uint64_t>("steps_done");
      m.seconds_total = in.value<double>("seconds_total");
      result = m;
      break;
    }
    default:
      throw ProtocolError("cannot decode " + name(type), "message decoder",
                          "use matching fsi-server and fsi-client releases");
  }
  in.finish();
  return result;
}

MessageType type_of(const Message& message) {
  return std::visit([](const auto& m) { return std::decay_t<decltype(m)>::kType; }, message);
}

std::string version_mismatch_text(const char* peer_role, std::uint16_t peer_major,
                                  std::uint16_t peer_minor, const char* own_role) {
  return std::string(peer_role) + " speaks " + version_text(peer_major, peer_minor) + ", this " +
         own_role + " speaks " + version_text(kMajorVersion, kMinorVersion) +
         "; the major versions must match (use matching fsi-server and fsi-client releases)";
}

}  // namespace fsi::protocol
