#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "error_text.hpp"
#include "fsi/protocol/frame.hpp"
#include "fsi/protocol/messages.hpp"

namespace fsi::protocol {
namespace {

using namespace test;

using Limits = std::numeric_limits<double>;

// One fully populated example of every message.
Hello sample_hello() {
  return {"0.1.0", "node-7", 4, 0};
}
Welcome sample_welcome() {
  return {0, 0, "0.1.0", "tank-2024"};
}
ErrorMessage sample_error() {
  return {ErrorCode::LiggghtsError, "ERROR: Illegal pair_style"};
}
Setup sample_setup() {
  return {2,          5e-6,
          4000,       {{"h", "0.000614"}, {"title", "tank with space"}, {"empty", ""}},
          "tank.in1", "dimension 2\n# comment \xc3\xa4\n",
          "tank.in2", ""};
}
Mesh sample_mesh() {
  return {2, 2, 1, 0.001, {0, 0, 1, 0, 1, 1}, {0.5, 0, 0.5, 0, 0, 0}, {0, 1, 1, 2}};
}
Particles sample_particles() {
  return {2, 1, 1e-4, 1000, {0.1, 0.2, 0.3, 0.4}, {0, -1, 0, 1}};
}
Ready sample_ready() {
  return {13892, "LIGGGHTS-PUBLIC 3.8.0", 1.5, 30.25};
}
Settling sample_settling() {
  return {{0.0, -9.81, 0.5}, 0.13, 250.0, {1000.5, 1000.25, 1000.0}};
}
ReleaseState sample_release_state() {
  return {54.625, 0.13, 16.875, 1.5e-7, 10.75};
}
Step sample_step() {
  return {7, 0.125, 5e-6, {1, 2, 3, 4}, {-1, -2, -3, -4}};
}
Forces sample_forces() {
  return {
      7, {0.5, -0.25, 1e-9, 3}, {{1, 2, 3}, {-1, -2, -3}, 17.5, 42, 0.75, 13892, 0.5, 0.1, 0.01}};
}
FluidHealth sample_fluid_health() {
  return {7, 13892, 2, 996.5, 1003.25, 0.375};
}
SnapshotRequest sample_snapshot_request() {
  return {99};
}
Snapshot sample_snapshot() {
  return {100, 0.0005, 2, {5, 9}, {0, 1, 2, 3}, {4, 5, 6, 7}, {1000, 1001}, {0, 12.5}};
}
CheckpointRequest sample_checkpoint_request() {
  return {1200};
}
FluidState sample_fluid_state() {
  return {1200, 3, std::string("state\0with zeros\xff", 17)};
}
Resume sample_resume() {
  return {1200, 0.012, std::string("state\0with zeros\xff", 17)};
}
Shutdown sample_shutdown() {
  return {"end time reached"};
}
Goodbye sample_goodbye() {
  return {140000, 3600.5};
}

AuthBytes counting_bytes(std::uint8_t first) {
  AuthBytes bytes{};
  for (std::size_t i = 0; i < bytes.size(); ++i)
    bytes[i] = static_cast<std::uint8_t>(first + i);
  return bytes;
}

ProbeSetup sample_probe_setup() {
  return {20, {0.0, -9.81, 0.0}, 0.001, {{2, "gauge", {0.02, 0.01, 0.0}}, {1, "water", {}}}};
}

ProbeValues sample_probe_values() {
  return {40, {0.1, -0.0, 196.2, 12.0, 1.0}};
}

ProbePlacement sample_probe_placement() {
  return {40, {{0, {0.05, 0.0, 0.0, 0.6, 200.0}}, {3, {0.1, 0.2, 0.0}}}};
}

StepMotion sample_step_motion() {
  // Two dynamic vertices in 2D at the nodes 0, 0.5, 1 of a step of 4 fluid steps.
  return {48,
          4.8e-3,
          1e-4,
          4,
          {0.0, 0.5, 1.0},
          {0.0, 1.0, 2.0, 3.0, 0.1, 1.1, 2.1, 3.1, 0.2, 1.2, 2.2, 3.2},
          {1.0, 0.0, 1.0, 0.0, 1.0, 0.0, 1.0, 0.0, 1.0, 0.0, 1.0, 0.0}};
}

std::vector<Message> all_samples() {
  return {sample_hello(),
          sample_welcome(),
          sample_error(),
          AuthChallenge{counting_bytes(1)},
          AuthResponse{counting_bytes(40), counting_bytes(80)},
          AuthProof{counting_bytes(200)},
          Heartbeat{},
          sample_setup(),
          sample_mesh(),
          sample_particles(),
          sample_ready(),
          sample_settling(),
          sample_release_state(),
          sample_probe_setup(),
          sample_step(),
          sample_forces(),
          sample_probe_values(),
          sample_probe_placement(),
          sample_step_motion(),
          sample_fluid_health(),
          sample_snapshot_request(),
          sample_snapshot(),
          sample_checkpoint_request(),
          sample_fluid_state(),
          sample_resume(),
          sample_shutdown(),
          sample_goodbye()};
}

using test::decode_error;
template <class T>
std::string decode_error(const T& message) {
  return decode_error(T::kType, encode(message));
}

TEST(ProtocolMessages, EveryMessageRoundTrips) {
  const auto samples = all_samples();
  ASSERT_EQ(samples.size(), std::variant_size_v<Message>);
  for (const Message& sample : samples) {
    const MessageType type = type_of(sample);
    const Message back = decode(type, encode(sample));
    EXPECT_EQ(back, sample) << name(type);
    EXPECT_EQ(type_of(back), type);
  }
}

TEST(ProtocolMessages, TypedEncodeAndDecodeAgreeWithTheVariantOnes) {
  EXPECT_EQ(encode(sample_mesh()), encode(Message{sample_mesh()}));
  EXPECT_EQ(decode_as<Step>(encode(sample_step())), sample_step());
  EXPECT_EQ(decode_as<protocol::Setup>(encode(sample_setup())).liggghts_variables[1].value,
            "tank with space");
}

TEST(ProtocolMessages, PayloadSizesFollowTheSpecTables) {
  // docs/protocol.md: fixed part + counts and elements.
  EXPECT_EQ(encode(sample_hello()).size(), 4u + 5 + 4 + 6 + 4 + 4);
  EXPECT_EQ(encode(sample_step()).size(), 8u + 8 + 8 + (8 + 4 * 8) + (8 + 4 * 8));
  EXPECT_EQ(encode(sample_forces()).size(), 8u + (8 + 4 * 8) + 6 * 8 + 8 + 8 + 8 + 8 + 3 * 8);
  EXPECT_EQ(encode(sample_mesh()).size(), 4u + 4 + 4 + 8 + (8 + 6 * 8) * 2 + (8 + 4 * 4));
  EXPECT_EQ(encode(sample_snapshot_request()).size(), 8u);
  EXPECT_EQ(encode(Welcome{}).size(), 2u + 4 + 4 + 4);
  EXPECT_EQ(encode(AuthChallenge{}).size(), 32u);
  EXPECT_EQ(encode(AuthResponse{}).size(), 64u);
  EXPECT_EQ(encode(AuthProof{}).size(), 32u);
  EXPECT_EQ(encode(Heartbeat{}).size(), 0u);
  EXPECT_EQ(encode(sample_settling()).size(), 3u * 8 + 8 + 8 + (8 + 3 * 8));
  EXPECT_EQ(encode(sample_release_state()).size(), 5u * 8);
  // Each probe: kind, name, parameter count and parameters.
  EXPECT_EQ(encode(sample_probe_setup()).size(),
            8u + 3 * 8 + 8 + 8 + (4 + 4 + 5 + 8 + 3 * 8) + (4 + 4 + 5 + 8));
  EXPECT_EQ(encode(sample_probe_values()).size(), 8u + 8 + 5 * 8);
  // Each placed probe: index, parameter count and parameters.
  EXPECT_EQ(encode(sample_probe_placement()).size(), 8u + 8 + (4 + 8 + 5 * 8) + (4 + 8 + 3 * 8));
  EXPECT_EQ(encode(sample_fluid_health()).size(), 3u * 8 + 3 * 8);
}

std::vector<double> awkward_doubles() {
  std::vector<double> values{0.0,
                             -0.0,
                             1.0,
                             -1.5,
                             Limits::infinity(),
                             -Limits::infinity(),
                             Limits::denorm_min(),
                             -Limits::denorm_min(),
                             Limits::min() / 3.0,
                             Limits::max(),
                             Limits::lowest(),
                             std::bit_cast<double>(0x7FF8000000000001ull),   // quiet NaN, payload
                             std::bit_cast<double>(0x7FF0000000000BADull),   // signalling NaN
                             std::bit_cast<double>(0xFFF80000DEADBEEFull)};  // negative NaN
  std::mt19937_64 generator(11);
  for (int i = 0; i < 2000; ++i)
    values.push_back(std::bit_cast<double>(generator()));
  return values;
}

void expect_same_bits(const std::vector<double>& expected, const std::vector<double>& actual) {
  ASSERT_EQ(expected.size(), actual.size());
  for (std::size_t i = 0; i < expected.size(); ++i) {
    ASSERT_EQ(std::bit_cast<std::uint64_t>(expected[i]), std::bit_cast<std::uint64_t>(actual[i]))
        << "value " << i;
  }
}

void expect_same_bits(double expected, double actual) {
  EXPECT_EQ(std::bit_cast<std::uint64_t>(expected), std::bit_cast<std::uint64_t>(actual));
}

TEST(ProtocolMessages, DoublesSurviveBitExactInArraysAndScalars) {
  const auto values = awkward_doubles();
  const Step step{7, values[11], 5e-6, values, values};
  const Step step_back = decode_as<Step>(encode(step));
  expect_same_bits(values, step_back.positions);
  expect_same_bits(values, step_back.velocities);
  expect_same_bits(values[11], step_back.time);

  Forces forces;
  forces.forces = values;
  forces.diagnostics.force_on_fluid = {values[1], values[6], values[12]};
  forces.diagnostics.seconds_contact = values[13];
  const Forces forces_back = decode_as<Forces>(encode(forces));
  expect_same_bits(values, forces_back.forces);
  for (int k = 0; k < 3; ++k)
    expect_same_bits(forces.diagnostics.force_on_fluid[k],
                     forces_back.diagnostics.force_on_fluid[k]);
  expect_same_bits(values[13], forces_back.diagnostics.seconds_contact);

  Snapshot snapshot;
  snapshot.dimension = 2;
  snapshot.time = values[7];
  snapshot.ids.resize(values.size() / 2);
  snapshot.positions.assign(values.begin(), values.begin() + 2 * snapshot.ids.size());
  snapshot.velocities = snapshot.positions;
  snapshot.density.assign(values.begin(), values.begin() + snapshot.ids.size());
  snapshot.pressure = snapshot.density;
  const Snapshot snapshot_back = decode_as<Snapshot>(encode(snapshot));
  expect_same_bits(snapshot.positions, snapshot_back.positions);
  expect_same_bits(snapshot.pressure, snapshot_back.pressure);
  expect_same_bits(values[7], snapshot_back.time);

  const Goodbye goodbye{1, values[12]};
  expect_same_bits(values[12], decode_as<Goodbye>(encode(goodbye)).seconds_total);
}

// Random values of each awkward class: subnormals (exponent 0, random mantissa), NaNs with random
// payloads (quiet and signalling, both signs), ±0, ±inf, and random normal numbers.
std::vector<double> random_awkward_doubles(std::size_t per_class, std::uint64_t seed) {
  std::mt19937_64 generator(seed);
  constexpr std::uint64_t kMantissa = (1ull << 52) - 1;
  constexpr std::uint64_t kSign = 1ull << 63;
  constexpr std::uint64_t kExponentAllOnes = 0x7FFull << 52;
  std::vector<double> values{0.0, -0.0, Limits::infinity(), -Limits::infinity()};
  for (std::size_t i = 0; i < per_class; ++i) {
    const std::uint64_t sign = generator() & kSign;
    const std::uint64_t mantissa = (generator() & kMantissa) | 1;  // never 0: not zero nor inf
    values.push_back(std::bit_cast<double>(sign | mantissa));      // subnormal
    values.push_back(std::bit_cast<double>(sign | kExponentAllOnes | mantissa));  // NaN payload
    const std::uint64_t exponent = 1 + generator() % 0x7FE;                       // normal
    values.push_back(std::bit_cast<double>(sign | (exponent << 52) | (generator() & kMantissa)));
  }
  std::shuffle(values.begin(), values.end(), generator);
  return values;
}

// The whole receive path (frame, CRC, message decoder) for every message with double fields:
// every double arrives with the bits it was sent with.
TEST(ProtocolMessages, RandomAwkwardDoublesSurviveFramesOfEveryMessageBitForBit) {
  const std::vector<double> values = random_awkward_doubles(300, 2026);
  std::size_t subnormals = 0;
  std::size_t nans = 0;
  for (const double value : values) {
    subnormals += std::fpclassify(value) == FP_SUBNORMAL;
    nans += std::isnan(value);
  }
  ASSERT_GE(subnormals, 300u);
  ASSERT_GE(nans, 300u);
  std::size_t next = 0;
  const auto take = [&] { return values[next++ % values.size()]; };
  const auto through_frame = [](const auto& message) {
    using T = std::decay_t<decltype(message)>;
    const Frame frame = decode_frame(encode_frame(T::kType, encode(message)));
    return std::get<T>(decode(frame.header.type, frame.payload));
  };
  const std::vector<double> triples(values.begin(), values.begin() + 3 * (values.size() / 3));

  Mesh mesh = sample_mesh();
  mesh.dimension = 3;
  mesh.dynamic_vertex_count = 0;
  mesh.element_vertices.clear();
  mesh.positions = triples;
  mesh.velocities.assign(triples.rbegin(), triples.rend());
  const Mesh mesh_back = through_frame(mesh);
  expect_same_bits(mesh.positions, mesh_back.positions);
  expect_same_bits(mesh.velocities, mesh_back.velocities);

  Particles particles = sample_particles();
  particles.dimension = 3;
  particles.positions = triples;
  particles.velocities = triples;
  expect_same_bits(particles.velocities, through_frame(particles).velocities);

  Step step{1, take(), 1e-5, values, values};
  const Step step_back = through_frame(step);
  expect_same_bits(step.time, step_back.time);
  expect_same_bits(values, step_back.positions);

  Forces forces;
  forces.forces = values;
  forces.diagnostics.force_on_structure = {take(), take(), take()};
  forces.diagnostics.closest_approach_over_r0 = take();
  forces.diagnostics.seconds_client_communication = take();
  const Forces forces_back = through_frame(forces);
  expect_same_bits(values, forces_back.forces);
  for (int k = 0; k < 3; ++k)
    expect_same_bits(forces.diagnostics.force_on_structure[k],
                     forces_back.diagnostics.force_on_structure[k]);
  expect_same_bits(forces.diagnostics.closest_approach_over_r0,
                   forces_back.diagnostics.closest_approach_over_r0);
  expect_same_bits(forces.diagnostics.seconds_client_communication,
                   forces_back.diagnostics.seconds_client_communication);

  Snapshot snapshot;
  snapshot.dimension = 3;
  snapshot.time = take();
  snapshot.ids.resize(triples.size() / 3);
  snapshot.positions = triples;
  snapshot.velocities = triples;
  snapshot.density.assign(values.begin(), values.begin() + snapshot.ids.size());
  snapshot.pressure.assign(values.rbegin(), values.rbegin() + snapshot.ids.size());
  const Snapshot snapshot_back = through_frame(snapshot);
  expect_same_bits(snapshot.time, snapshot_back.time);
  expect_same_bits(snapshot.velocities, snapshot_back.velocities);
  expect_same_bits(snapshot.density, snapshot_back.density);
  expect_same_bits(snapshot.pressure, snapshot_back.pressure);

  const Ready ready{1, "LIGGGHTS", take(), take()};
  const Ready ready_back = through_frame(ready);
  expect_same_bits(ready.seconds_setup, ready_back.seconds_setup);
  expect_same_bits(ready.seconds_equilibration, ready_back.seconds_equilibration);
}

TEST(ProtocolMessages, EveryTruncationOfEveryMessageIsRejected) {
  for (const Message& sample : all_samples()) {
    const MessageType type = type_of(sample);
    const auto payload = encode(sample);
    for (std::size_t length = 0; length < payload.size(); ++length) {
      const std::string text = decode_error(type, std::span(payload).first(length));
      ASSERT_NE(text.find("malformed " + name(type) + " message: field '"), std::string::npos)
          << name(type) << " cut to " << length << ": " << text;
      ASSERT_NE(text.find(name(type) + " payload byte "), std::string::npos) << text;
    }
  }
}

TEST(ProtocolMessages, TruncationNamesTheFieldAndItsOffset) {
  const auto payload = encode(sample_step());
  const std::string text = decode_error(MessageType::Step, std::span(payload).first(12));
  EXPECT_NE(text.find("Step payload byte 8 of 12"), std::string::npos) << text;
  EXPECT_NE(text.find("field 'time' is truncated"), std::string::npos) << text;
  const auto setup = encode(sample_setup());
  // Cut inside the second variable's name, which starts after 28 bytes of fixed fields and count
  // and the 17 bytes of the first variable. (Shorter cuts fail the count check, 3 entries of at
  // least 8 bytes, before any entry is read.)
  const std::string inner = decode_error(MessageType::Setup, std::span(setup).first(52));
  EXPECT_NE(inner.find("field 'liggghts_variables[1].name'"), std::string::npos) << inner;
  EXPECT_NE(inner.find("Setup payload byte 45"), std::string::npos) << inner;
  EXPECT_NE(inner.find("needs a string of 5 bytes, but only 3 bytes remain"), std::string::npos)
      << inner;
  const std::string count = decode_error(MessageType::Setup, std::span(setup).first(47));
  EXPECT_NE(count.find("'liggghts_variables' announces 3 entries of at least 8 bytes but only 19"),
            std::string::npos)
      << count;
}

TEST(ProtocolMessages, TrailingBytesAreRejected) {
  auto payload = encode(sample_goodbye());
  payload.push_back(std::byte{0});
  EXPECT_NE(decode_error(MessageType::Goodbye, payload).find("1 bytes follow the last field"),
            std::string::npos);
}

TEST(ProtocolMessages, CountsAreCheckedBeforeAllocation) {
  auto step = encode(sample_step());
  // The positions count follows step, time and time_step (24 bytes).
  const std::uint64_t huge = 1ull << 60;
  std::memcpy(step.data() + 24, &huge, sizeof huge);
  const std::string array_text = decode_error(MessageType::Step, step);
  EXPECT_NE(array_text.find("field 'positions' announces 1152921504606846976 elements of 8 bytes "
                            "but only 72 bytes remain"),
            std::string::npos)
      << array_text;
  EXPECT_NE(array_text.find("Step payload byte 24"), std::string::npos) << array_text;

  auto shutdown = encode(sample_shutdown());
  const std::uint32_t long_string = 0xFFFFFFFFu;
  std::memcpy(shutdown.data(), &long_string, sizeof long_string);
  EXPECT_NE(decode_error(MessageType::Shutdown, shutdown)
                .find("'reason' is truncated: needs a string of 4294967295 bytes"),
            std::string::npos);

  auto setup = encode(sample_setup());
  // The variable count follows dimension, time_step and equilibration_steps (20 bytes).
  std::memcpy(setup.data() + 20, &huge, sizeof huge);
  EXPECT_NE(decode_error(MessageType::Setup, setup)
                .find("'liggghts_variables' announces 1152921504606846976 entries"),
            std::string::npos);
}

TEST(ProtocolMessages, MeshContentIsChecked) {
  Mesh mesh = sample_mesh();
  mesh.element_vertices = {0, 3};
  std::string text = decode_error(mesh);
  EXPECT_NE(text.find("'element_vertices' entry 1 refers to vertex 3 of only 3"), std::string::npos)
      << text;
  // element_vertices starts after 4+4+4+8 bytes and two arrays of 8 + 6*8 bytes.
  EXPECT_NE(text.find("Mesh payload byte 132"), std::string::npos) << text;

  mesh = sample_mesh();
  mesh.element_vertices = {0, 1, 2};
  EXPECT_NE(decode_error(mesh).find("not a multiple of the 2 vertices per element"),
            std::string::npos);

  mesh = sample_mesh();
  mesh.dynamic_vertex_count = 4;
  EXPECT_NE(decode_error(mesh).find("'dynamic_vertex_count' is 4, more than the 3 vertices"),
            std::string::npos);

  for (double bad : {0.0, -1.0, Limits::infinity(), Limits::quiet_NaN()}) {
    mesh = sample_mesh();
    mesh.refinement_resolution = bad;
    EXPECT_NE(decode_error(mesh).find("'refinement_resolution' is"), std::string::npos) << bad;
  }

  mesh = sample_mesh();
  mesh.refinement_option = 4;
  EXPECT_NE(decode_error(mesh).find("'refinement_option' is 4"), std::string::npos);

  mesh = sample_mesh();
  mesh.positions.push_back(2);
  EXPECT_NE(decode_error(mesh).find("'positions' has 7 values, not a multiple of the dimension 2"),
            std::string::npos);

  mesh = sample_mesh();
  mesh.velocities.pop_back();
  EXPECT_NE(decode_error(mesh).find("'velocities' has 5 values, expected 6"), std::string::npos);

  mesh = sample_mesh();
  mesh.dimension = 3;
  mesh.positions = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  mesh.velocities.assign(9, 0.0);
  mesh.element_vertices = {0, 1, 2};
  EXPECT_EQ(decode_as<Mesh>(encode(mesh)), mesh);
}

TEST(ProtocolMessages, OtherContentIsChecked) {
  protocol::Setup setup = sample_setup();
  setup.dimension = 4;
  EXPECT_NE(decode_error(setup).find("'dimension' is 4; only 2 and 3 exist"), std::string::npos);
  setup = sample_setup();
  setup.time_step = 0.0;
  EXPECT_NE(decode_error(setup).find("'time_step' is 0;"), std::string::npos);
  setup = sample_setup();
  setup.liggghts_variables[0].name = "h; shell";
  EXPECT_NE(decode_error(setup).find("entry 0 has the name 'h; shell'"), std::string::npos);
  setup = sample_setup();
  setup.liggghts_variables[1].value = "a\nrun 1000";
  EXPECT_NE(decode_error(setup).find("line break"), std::string::npos);

  Particles particles = sample_particles();
  particles.mass = -1;
  EXPECT_NE(decode_error(particles).find("'mass' is -1"), std::string::npos);
  // Without particles (a script creates the fluid) mass and density may be 0, not negative.
  Particles none{2, 1, 0.0, 0.0, {}, {}};
  EXPECT_EQ(std::get<Particles>(decode(MessageType::Particles, encode(none))), none);
  none.density = -1;
  EXPECT_NE(decode_error(none).find("'density' is -1"), std::string::npos);
  particles = sample_particles();
  particles.velocities.pop_back();
  EXPECT_NE(decode_error(particles).find("'velocities' has 3 values, expected 4"),
            std::string::npos);

  Step step = sample_step();
  step.velocities.push_back(0);
  EXPECT_NE(decode_error(step).find("'velocities' has 5 values, expected 4"), std::string::npos);
  step = sample_step();
  step.time_step = Limits::quiet_NaN();
  EXPECT_NE(decode_error(step).find("'time_step' is nan"), std::string::npos);

  Snapshot snapshot = sample_snapshot();
  snapshot.positions.pop_back();
  EXPECT_NE(decode_error(snapshot).find("'positions' has 3 values, expected 4 (2 per id)"),
            std::string::npos);
  snapshot = sample_snapshot();
  snapshot.pressure.push_back(1);
  EXPECT_NE(decode_error(snapshot).find("'pressure' has 3 values, expected 2"), std::string::npos);
}

TEST(ProtocolMessages, SettlingAndReleaseStateContentIsChecked) {
  Settling settling = sample_settling();
  settling.drag_rate = kAutomaticDragRate;
  EXPECT_EQ(std::get<Settling>(decode(MessageType::Settling, encode(settling))), settling);
  settling.gravity[1] = Limits::infinity();
  EXPECT_NE(decode_error(settling).find("'gravity' is inf; it must be finite"), std::string::npos);
  settling = sample_settling();
  settling.column_height = -0.1;
  EXPECT_NE(decode_error(settling).find("'column_height' is -0.10000000000000001"),
            std::string::npos);
  settling = sample_settling();
  settling.drag_rate = Limits::quiet_NaN();
  EXPECT_NE(decode_error(settling).find("'drag_rate' is nan"), std::string::npos);
  settling = sample_settling();
  settling.initial_densities[1] = 0.0;
  EXPECT_NE(decode_error(settling).find("'initial_densities' is 0; it must be positive"),
            std::string::npos);

  ReleaseState release = sample_release_state();
  release.kinetic_energy = -1e-9;
  EXPECT_NE(decode_error(release).find("'kinetic_energy' is -1.0000000000000001e-09; it must be "
                                       "zero or positive, and finite"),
            std::string::npos);
  release = sample_release_state();
  release.fluid_mass = Limits::infinity();
  EXPECT_NE(decode_error(release).find("'fluid_mass' is inf"), std::string::npos);
  release = sample_release_state();
  release.drag_rate = -1;
  EXPECT_NE(decode_error(release).find("'drag_rate' is -1"), std::string::npos);
}

TEST(ProtocolMessages, ProbePlacementContentIsChecked) {
  ProbePlacement placement = sample_probe_placement();
  placement.probes[1].index = 0;
  EXPECT_NE(decode_error(placement).find("'probes' entry 1 places probe 0 a second time"),
            std::string::npos);
  placement = sample_probe_placement();
  placement.probes[0].parameters[1] = Limits::infinity();
  EXPECT_NE(decode_error(placement).find("'probes' is inf"), std::string::npos);
  std::vector<std::byte> payload = encode(sample_probe_placement());
  const std::uint64_t huge = 1u << 30;
  std::memcpy(payload.data() + 8, &huge, sizeof huge);
  EXPECT_NE(decode_error(MessageType::ProbePlacement, payload)
                .find("announces 1073741824 entries of at least 12 bytes"),
            std::string::npos);
}

TEST(ProtocolMessages, StepMotionContentIsChecked) {
  StepMotion motion = sample_step_motion();
  motion.substeps = 1;
  EXPECT_NE(decode_error(motion).find("'substeps' is 1; a StepMotion has at least 2"),
            std::string::npos);
  motion = sample_step_motion();
  motion.nodes = {0.0};
  motion.positions.resize(4);
  motion.velocities.resize(4);
  EXPECT_NE(decode_error(motion).find("'nodes' has 1 entries, not 2 to 8"), std::string::npos);
  motion = sample_step_motion();
  motion.nodes = {0.0, 0.5, 0.5};
  EXPECT_NE(decode_error(motion).find("'nodes' entry 2 breaks"), std::string::npos);
  motion = sample_step_motion();
  motion.nodes = {0.0, 0.5, 0.9};
  EXPECT_NE(decode_error(motion).find("the last is not 1"), std::string::npos);
  motion = sample_step_motion();
  motion.positions.pop_back();
  motion.velocities.pop_back();
  EXPECT_NE(decode_error(motion).find("'positions' has 11 values, not a multiple of the 3 nodes"),
            std::string::npos);
  motion = sample_step_motion();
  motion.velocities.pop_back();
  EXPECT_NE(decode_error(motion).find("'velocities'"), std::string::npos);
  motion = sample_step_motion();
  motion.time_step = 0.0;
  EXPECT_NE(decode_error(motion).find("'time_step' is 0"), std::string::npos);
}

TEST(ProtocolMessages, ProbeSetupContentIsChecked) {
  ProbeSetup probes = sample_probe_setup();
  probes.every_steps = 0;
  EXPECT_NE(decode_error(probes).find("'every_steps' is 0; probes are evaluated every N >= 1"),
            std::string::npos);
  probes = sample_probe_setup();
  probes.probes[1].name.clear();
  EXPECT_NE(decode_error(probes).find("'probes' entry 1 has an empty name"), std::string::npos);
  probes = sample_probe_setup();
  probes.probes[0].parameters[2] = Limits::quiet_NaN();
  EXPECT_NE(decode_error(probes).find("'probes' is nan"), std::string::npos);
  probes = sample_probe_setup();
  probes.particle_spacing = -1e-3;
  EXPECT_NE(decode_error(probes).find("'particle_spacing' is -0.001"), std::string::npos);
  // A count of probes larger than the bytes that could hold them is refused before allocating.
  std::vector<std::byte> payload = encode(sample_probe_setup());
  const std::uint64_t huge = 1u << 30;
  std::memcpy(payload.data() + 8 + 3 * 8 + 8, &huge, sizeof huge);
  EXPECT_NE(decode_error(MessageType::ProbeSetup, payload)
                .find("announces 1073741824 entries of at least 16 bytes"),
            std::string::npos);
}

TEST(ProtocolMessages, FluidHealthCarriesAFailingFluidAndChecksItsCounts) {
  // A blown-up fluid is what the message exists to report: infinite extremes must arrive intact.
  FluidHealth failing = sample_fluid_health();
  failing.min_density = Limits::infinity();
  failing.max_density = -Limits::infinity();
  failing.max_speed = 1e300;
  failing.non_finite_particles = failing.particle_count;
  EXPECT_EQ(std::get<FluidHealth>(decode(MessageType::FluidHealth, encode(failing))), failing);
  FluidHealth impossible = sample_fluid_health();
  impossible.non_finite_particles = impossible.particle_count + 1;
  EXPECT_NE(decode_error(impossible)
                .find("'non_finite_particles' is 13893, more than the 13892 particles"),
            std::string::npos);
}

TEST(ProtocolMessages, UnknownErrorCodesAndEmptyValuesDecode) {
  ErrorMessage future{static_cast<ErrorCode>(99), "a code from a later version"};
  const ErrorMessage back = decode_as<ErrorMessage>(encode(future));
  EXPECT_EQ(static_cast<std::uint32_t>(back.code), 99u);
  EXPECT_EQ(name(back.code), "code 99");
  EXPECT_EQ(name(ErrorCode::VersionMismatch), "VersionMismatch");
  EXPECT_EQ(decode_as<Shutdown>(encode(Shutdown{})), Shutdown{});
  Snapshot empty;
  EXPECT_EQ(decode_as<Snapshot>(encode(empty)), empty);
}

// ---- gathered encoding and decoding from a source (the channel's zero-copy paths) ----

// Every sample, and versions whose arrays and strings are large enough to be referenced.
std::vector<Message> samples_small_and_large() {
  std::vector<Message> messages = all_samples();
  Setup setup = sample_setup();
  setup.script1_text.assign(3 * kGatherMinimumBytes, 'x');
  messages.emplace_back(setup);
  Step step = sample_step();
  step.positions.assign(5000, 0.25);
  step.velocities.assign(5000, -0.5);
  messages.emplace_back(step);
  Forces forces = sample_forces();
  forces.forces.assign(kGatherMinimumBytes / sizeof(double), 1.5);  // exactly at the threshold
  messages.emplace_back(forces);
  Snapshot snapshot = sample_snapshot();
  snapshot.ids.assign(3000, 4);
  snapshot.positions.assign(6000, 0.5);
  snapshot.velocities.assign(6000, 0.25);
  snapshot.density.assign(3000, 1000);
  snapshot.pressure.assign(100, 1);  // small: copied
  snapshot.pressure.resize(3000, 2);
  messages.emplace_back(snapshot);
  return messages;
}

std::vector<std::byte> concatenated(const GatheredPayload& payload) {
  std::vector<std::byte> bytes;
  for (const auto& piece : payload.pieces)
    bytes.insert(bytes.end(), piece.begin(), piece.end());
  return bytes;
}

TEST(ProtocolMessages, GatheredPiecesAreExactlyTheEncodedBytes) {
  GatheredPayload payload;  // reused across messages, as a channel does
  for (const Message& message : samples_small_and_large()) {
    std::visit([&](const auto& m) { encode_gathered(m, payload); }, message);
    const auto expected = encode(message);
    EXPECT_EQ(payload.size, expected.size()) << name(type_of(message));
    EXPECT_EQ(concatenated(payload), expected) << name(type_of(message));
  }
}

TEST(ProtocolMessages, GatheringReferencesLargeArraysWhereTheyLie) {
  Forces forces = sample_forces();
  forces.forces.assign(100000, 0.125);
  GatheredPayload payload;
  encode_gathered(forces, payload);
  // step and count encoded, the array itself, the diagnostics encoded.
  ASSERT_EQ(payload.pieces.size(), 3u);
  EXPECT_EQ(payload.pieces[1].data(), reinterpret_cast<const std::byte*>(forces.forces.data()));
  EXPECT_EQ(payload.pieces[1].size(), forces.forces.size() * sizeof(double));
  EXPECT_LT(payload.encoded.size(), std::size_t{1024});  // nothing large was copied

  Step small = sample_step();
  encode_gathered(small, payload);
  ASSERT_EQ(payload.pieces.size(), 1u);  // small arrays are copied: one piece
  EXPECT_EQ(payload.pieces[0].data(), payload.encoded.data());
}

// Hands out the payload in small pieces and says that only a few bytes are ever there at once,
// as a socket does.
class TricklingSource final : public PayloadSource {
 public:
  TricklingSource(std::span<const std::byte> bytes, unsigned seed)
      : bytes_(bytes), generator_(seed) {}
  std::size_t remaining() const override { return bytes_.size() - offset_; }
  std::size_t available() const override { return std::min<std::size_t>(remaining(), 7); }
  void read(std::span<std::byte> into) override {
    EXPECT_LE(into.size(), remaining());
    std::size_t done = 0;
    while (done < into.size()) {
      const std::size_t piece = std::min(into.size() - done, 1 + generator_() % 300);
      std::memcpy(into.data() + done, bytes_.data() + offset_, piece);
      done += piece;
      offset_ += piece;
    }
  }
  void end() override {
    EXPECT_EQ(remaining(), 0u);
    ++ends;
  }
  int ends = 0;

 private:
  std::span<const std::byte> bytes_;
  std::size_t offset_ = 0;
  std::mt19937 generator_;
};

TEST(ProtocolMessages, DecodingFromATricklingSourceAgreesWithDecodingABuffer) {
  unsigned seed = 1;
  for (const Message& message : samples_small_and_large()) {
    const auto bytes = encode(message);
    TricklingSource source(bytes, seed++);
    EXPECT_EQ(decode(type_of(message), source), message) << name(type_of(message));
    EXPECT_EQ(source.ends, 1);
  }
  // Faults are worded the same way, at the same offsets.
  auto truncated = encode(sample_step());
  truncated.pop_back();
  TricklingSource source(truncated, 99);
  std::string from_source;
  try {
    decode(MessageType::Step, source);
  } catch (const ProtocolError& error) {
    from_source = error.what();
  }
  EXPECT_EQ(from_source, decode_error(MessageType::Step, truncated));
  EXPECT_EQ(source.ends, 0);  // end() only after a complete read
}

TEST(ProtocolMessages, DecodeIntoReusesTheStorageOfItsVectors) {
  Forces sent = sample_forces();
  sent.forces.assign(50000, 0.5);
  Forces received;
  received.forces.reserve(60000);  // a fresh vector would get exactly the 50000 that arrive
  const auto first_bytes = encode(sent);
  TricklingSource first(first_bytes, 1);
  decode_into(first, received);
  EXPECT_EQ(received, sent);
  EXPECT_EQ(received.forces.capacity(), 60000u);
  const double* storage = received.forces.data();
  sent.step = 8;
  for (std::size_t i = 0; i < sent.forces.size(); ++i)
    sent.forces[i] = static_cast<double>(i);
  const auto second_bytes = encode(sent);
  TricklingSource second(second_bytes, 2);
  decode_into(second, received);
  EXPECT_EQ(received, sent);
  EXPECT_EQ(received.forces.data(), storage);  // filled in place, no allocation
  EXPECT_EQ(received.forces.capacity(), 60000u);
}

// A payload that announces 100 MB of doubles but breaks off early: the decoder must not have
// allocated for more than it received (doubling from 1 MiB as bytes arrive).
class BreakingSource final : public PayloadSource {
 public:
  std::size_t remaining() const override { return kAnnounced - offset_; }
  std::size_t available() const override { return 0; }
  void read(std::span<std::byte> into) override {
    if (offset_ == 0) {  // the 8-byte step, then the element count
      ASSERT_EQ(into.size(), 8u);
      std::memset(into.data(), 0, 8);
    } else if (offset_ == 8) {
      ASSERT_EQ(into.size(), 8u);
      const std::uint64_t count = (kAnnounced - 16 - 104) / sizeof(double);
      std::memcpy(into.data(), &count, 8);
    } else {
      if (offset_ + into.size() > kBreakAfter) throw ProtocolError("broke off", "test", "none");
      std::memset(into.data(), 0, into.size());
    }
    offset_ += into.size();
  }

 private:
  static constexpr std::size_t kAnnounced = 100'000'000;
  static constexpr std::size_t kBreakAfter = 3'000'000;
  std::size_t offset_ = 0;
};

TEST(ProtocolMessages, DecodeIntoAllocatesOnlyAsTheBytesArrive) {
  BreakingSource source;
  Forces received;
  EXPECT_THROW(decode_into(source, received), ProtocolError);
  EXPECT_LE(received.forces.capacity() * sizeof(double), std::size_t{8} << 20);
}

TEST(ProtocolMessages, UnknownTypeCannotBeDecoded) {
  EXPECT_NE(decode_error(static_cast<MessageType>(0x50), {}).find("unknown type 0x0050"),
            std::string::npos);
}

}  // namespace
}  // namespace fsi::protocol
