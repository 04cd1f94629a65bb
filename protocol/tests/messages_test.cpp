#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>

#include "fsi/protocol/messages.hpp"

namespace fsi::protocol {
namespace {

template <class T>
T round_trip(const T& message) {
  const auto payload = encode(message);
  Message decoded = decode(T::kType, payload);
  EXPECT_EQ(type_of(decoded), T::kType);
  return std::get<T>(decoded);
}

std::vector<double> tricky_doubles() {
  std::vector<double> values{0.0,
                             -0.0,
                             1.0,
                             -1.5,
                             std::numeric_limits<double>::infinity(),
                             -std::numeric_limits<double>::infinity(),
                             std::numeric_limits<double>::denorm_min(),
                             -std::numeric_limits<double>::denorm_min(),
                             std::numeric_limits<double>::min() / 3.0,
                             std::numeric_limits<double>::max(),
                             std::bit_cast<double>(0x7FF8000000000001ull),   // quiet NaN payload
                             std::bit_cast<double>(0x7FF0000000000BADull),   // signalling NaN
                             std::bit_cast<double>(0xFFF80000DEADBEEFull)};  // negative NaN
  std::mt19937_64 rng(11);
  for (int i = 0; i < 2000; ++i)
    values.push_back(std::bit_cast<double>(rng()));
  return values;
}

void expect_bits_equal(const std::vector<double>& a, const std::vector<double>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    ASSERT_EQ(std::bit_cast<std::uint64_t>(a[i]), std::bit_cast<std::uint64_t>(b[i])) << i;
  }
}

TEST(Messages, HandshakeAndControlRoundTrip) {
  Hello hello{"0.1.0", "node-7", 4, 0};
  auto h = round_trip(hello);
  EXPECT_EQ(h.software_version, "0.1.0");
  EXPECT_EQ(h.host, "node-7");
  EXPECT_EQ(h.mpi_ranks, 4u);
  Welcome welcome{0, 0, "0.1.0", "run-1"};
  EXPECT_EQ(round_trip(welcome).run_name, "run-1");
  ErrorMessage error{ErrorCode::LiggghtsError, "ERROR: bad pair style"};
  auto e = round_trip(error);
  EXPECT_EQ(e.code, ErrorCode::LiggghtsError);
  EXPECT_EQ(e.text, error.text);
  EXPECT_EQ(round_trip(SnapshotRequest{42}).step, 42u);
  EXPECT_EQ(round_trip(Shutdown{"end time reached"}).reason, "end time reached");
  auto bye = round_trip(Goodbye{1000, 12.5});
  EXPECT_EQ(bye.steps_done, 1000u);
  EXPECT_EQ(bye.seconds_total, 12.5);
  auto ready = round_trip(Ready{2000, "LIGGGHTS 3.8", 1.5, 30.25});
  EXPECT_EQ(ready.particle_count, 2000u);
  EXPECT_EQ(ready.seconds_equilibration, 30.25);
}

TEST(Messages, SetupRoundTrip) {
  protocol::Setup setup;
  setup.dimension = 2;
  setup.time_step = 5e-6;
  setup.equilibration_steps = 4000;
  setup.liggghts_variables = {{"h", "0.000614"}, {"name", "with space"}};
  setup.script1_name = "a.in1";
  setup.script1_text = "dimension 2\n# comment\n";
  setup.script2_name = "a.in2";
  setup.script2_text = "";
  const protocol::Setup back = round_trip(setup);
  EXPECT_EQ(back.time_step, 5e-6);
  EXPECT_EQ(back.equilibration_steps, 4000u);
  ASSERT_EQ(back.liggghts_variables.size(), 2u);
  EXPECT_EQ(back.liggghts_variables[1].value, "with space");
  EXPECT_EQ(back.script1_text, setup.script1_text);
}

TEST(Messages, ArraysAreBitExact) {
  const auto values = tricky_doubles();
  Step step{7, 0.125, 5e-6, values, values};
  const Step back = round_trip(step);
  expect_bits_equal(back.positions, values);
  expect_bits_equal(back.velocities, values);

  Forces forces;
  forces.step = 9;
  forces.forces = values;
  forces.diagnostics.force_on_fluid = {values[10], values[1], values[6]};
  forces.diagnostics.particles_in_range = 123;
  forces.diagnostics.closest_approach_over_r0 = 0.25;
  const Forces f = round_trip(forces);
  expect_bits_equal(f.forces, values);
  EXPECT_EQ(std::bit_cast<std::uint64_t>(f.diagnostics.force_on_fluid[0]),
            std::bit_cast<std::uint64_t>(values[10]));
  EXPECT_EQ(f.diagnostics.particles_in_range, 123u);

  Mesh mesh;
  mesh.dimension = 2;
  mesh.dynamic_vertex_count = 2;
  mesh.refinement_resolution = 0.001;
  mesh.positions = {0, 0, 1, 0, 1, 1};
  mesh.velocities = {0, 0, 0, 0, -0.0, 0};
  mesh.element_vertices = {0, 1, 1, 2};
  const Mesh m = round_trip(mesh);
  EXPECT_EQ(m.vertex_count(), 3u);
  EXPECT_EQ(m.element_vertices, mesh.element_vertices);
  EXPECT_TRUE(std::signbit(m.velocities[4]));

  Snapshot snapshot;
  snapshot.dimension = 2;
  snapshot.ids = {1, 2};
  snapshot.positions = {values[0], values[1], values[2], values[3]};
  snapshot.velocities = {1, 2, 3, 4};
  snapshot.density = {1000, 1001};
  snapshot.pressure = {values[11], 3};
  const Snapshot s = round_trip(snapshot);
  EXPECT_EQ(s.ids, snapshot.ids);
  expect_bits_equal(s.pressure, snapshot.pressure);

  Particles particles{2, 1, 1e-4, 1000, {0.1, 0.2}, {0, 0}};
  EXPECT_EQ(round_trip(particles).positions, particles.positions);
}

std::string decode_error(MessageType type, std::span<const std::byte> payload) {
  try {
    decode(type, payload);
  } catch (const ProtocolError& error) {
    return error.what();
  }
  return "";
}

TEST(Messages, EveryTruncationIsRejectedWithFieldAndOffset) {
  Mesh mesh;
  mesh.dynamic_vertex_count = 1;
  mesh.refinement_resolution = 0.5;
  mesh.positions = {0, 0, 1, 0};
  mesh.velocities = {0, 0, 0, 0};
  mesh.element_vertices = {0, 1};
  const auto payload = encode(mesh);
  for (std::size_t length = 0; length < payload.size(); ++length) {
    const std::string text = decode_error(MessageType::Mesh, std::span(payload).first(length));
    ASSERT_NE(text.find("malformed Mesh message"), std::string::npos) << length << ": " << text;
    ASSERT_NE(text.find("payload byte"), std::string::npos) << text;
  }
  auto longer = payload;
  longer.push_back(std::byte{0});
  EXPECT_NE(decode_error(MessageType::Mesh, longer).find("trailing"), std::string::npos);
}

TEST(Messages, CountsAreCheckedBeforeAllocation) {
  Step step{1, 0, 1e-5, {1, 2}, {3, 4}};
  auto payload = encode(step);
  // The positions count sits after step, time and time_step (24 bytes): claim 2^60 elements.
  const std::uint64_t huge = 1ull << 60;
  std::memcpy(payload.data() + 24, &huge, sizeof huge);
  const std::string text = decode_error(MessageType::Step, payload);
  EXPECT_NE(text.find("'positions' announces 1152921504606846976 elements"), std::string::npos)
      << text;
}

TEST(Messages, InconsistentContentIsRejected) {
  Mesh mesh;
  mesh.dynamic_vertex_count = 1;
  mesh.refinement_resolution = 0.5;
  mesh.positions = {0, 0, 1, 0};
  mesh.velocities = {0, 0, 0, 0};
  mesh.element_vertices = {0, 2};
  EXPECT_NE(decode_error(MessageType::Mesh, encode(mesh)).find("refers to vertex 2"),
            std::string::npos);
  mesh.element_vertices = {0, 1};
  mesh.dynamic_vertex_count = 3;
  EXPECT_NE(decode_error(MessageType::Mesh, encode(mesh)).find("dynamic_vertex_count"),
            std::string::npos);
  mesh.dynamic_vertex_count = 1;
  mesh.refinement_resolution = -1;
  EXPECT_NE(decode_error(MessageType::Mesh, encode(mesh)).find("refinement_resolution"),
            std::string::npos);
  Snapshot snapshot;
  snapshot.ids = {1, 2};
  snapshot.positions = {0, 0};
  EXPECT_NE(decode_error(MessageType::Snapshot, encode(snapshot)).find("'positions' has 2 values"),
            std::string::npos);
}

TEST(Messages, VersionMismatchTextNamesBothVersions) {
  const std::string text = version_mismatch_text("client", 2, 1, "server");
  EXPECT_NE(text.find("client speaks protocol 2.1"), std::string::npos);
  EXPECT_NE(text.find("server speaks protocol 1.0"), std::string::npos);
}

}  // namespace
}  // namespace fsi::protocol
