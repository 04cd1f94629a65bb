// Writes the seed corpora of the protocol fuzz targets: for every message type one valid message
// made by the encoder, as a frame (corpus/frame/) and as decoder-byte + payload (corpus/messages/).
// The doubles include the values the codec must carry bit for bit (±0, subnormals, ±inf, NaN).
// Usage: write_seeds OUTPUT_DIR   (scripts/run-fuzzers --write-seeds runs it into
// protocol/fuzz/corpus)
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <type_traits>

#include "decoders.hpp"

namespace {

using namespace fsi::protocol;
namespace fs = std::filesystem;

constexpr double kInf = std::numeric_limits<double>::infinity();
const double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kSubnormal = std::numeric_limits<double>::denorm_min();

AuthBytes nonce(std::uint8_t start) {
  AuthBytes bytes{};
  for (std::size_t k = 0; k < bytes.size(); ++k)
    bytes[k] = static_cast<std::uint8_t>(start + 37 * k);
  return bytes;
}

// One seed per message type; a type of message_list.hpp without one here does not compile.
Hello seed(std::type_identity<Hello>) {
  return {"0.1.0", "host-a", 2, kNoCapabilities};
}
Welcome seed(std::type_identity<Welcome>) {
  return {0, kNoCapabilities, "0.1.0", "static_tank"};
}
ErrorMessage seed(std::type_identity<ErrorMessage>) {
  return {ErrorCode::SetupFailed, "script 1 failed: unknown command"};
}
AuthChallenge seed(std::type_identity<AuthChallenge>) {
  return {nonce(1)};
}
AuthResponse seed(std::type_identity<AuthResponse>) {
  return {nonce(2), nonce(3)};
}
AuthProof seed(std::type_identity<AuthProof>) {
  return {nonce(4)};
}
Heartbeat seed(std::type_identity<Heartbeat>) {
  return {};
}
Setup seed(std::type_identity<Setup>) {
  return {2,
          1e-5,
          100,
          {{"SPHdensity", "1000"}, {"h", "0.0013"}},
          "script1.in",
          "atom_style sph\nvariable x equal 1\n",
          "script2.in",
          "run 0\n"};
}
Mesh seed(std::type_identity<Mesh>) {
  return {
      2,           2, 1, 0.001, {0.0, 0.0, 1.0, 0.0, 1.0, 1.0}, {0.0, -0.0, kSubnormal, 0, 0, 0},
      {0, 1, 1, 2}};
}
Particles seed(std::type_identity<Particles>) {
  return {3, 1, 1e-6, 1000.0, {0.1, 0.2, 0.3, 0.4, 0.5, 0.6}, {0, 0, 0, 0, 0, -1}};
}
Ready seed(std::type_identity<Ready>) {
  return {1200, "LIGGGHTS 3.8.0", 0.5, 12.25};
}
Settling seed(std::type_identity<Settling>) {
  return {{0.0, -9.81, 0.0}, 0.13, kAutomaticDragRate, {1001.25, 1000.5}};
}
ReleaseState seed(std::type_identity<ReleaseState>) {
  return {54.6, 0.13, 16.9, 1.5e-7, 10.7};
}
ProbeSetup seed(std::type_identity<ProbeSetup>) {
  return {20, {0.0, -9.81, 0.0}, 0.001, {{2, "gauge", {0.02, kSubnormal, -0.0}}, {1, "water", {}}}};
}
ProbeValues seed(std::type_identity<ProbeValues>) {
  return {40, {0.1, -0.0, 196.2, 12.0, 1.0}};
}
ProbePlacement seed(std::type_identity<ProbePlacement>) {
  return {40, {{0, {0.05, 0.0, -0.0, 0.6, 200.0}}, {3, {kSubnormal, 1.0, 0.0}}}};
}
StepMotion seed(std::type_identity<StepMotion>) {
  return {8,
          8e-5,
          1e-5,
          4,
          {0.0, 0.5, 1.0},
          {1.0, -0.0, kInf, 0.5, kSubnormal, 2.0},
          {kNaN, 0.0, -kSubnormal, 1.0, 2.0, 3.0}};
}
Step seed(std::type_identity<Step>) {
  return {7, 7e-5, 1e-5, {1.0, -0.0, kInf, -kInf}, {kNaN, kSubnormal, -kSubnormal, 0.0}};
}
Forces seed(std::type_identity<Forces>) {
  Forces forces{7, {0.5, -0.5, 1e300, -1e-300}, {}};
  forces.diagnostics.force_on_fluid = {1.0, 2.0, 0.0};
  forces.diagnostics.particles_in_range = 12;
  forces.diagnostics.particle_count = 1200;
  return forces;
}
FluidHealth seed(std::type_identity<FluidHealth>) {
  return {7, 1200, 1, 998.5, 1004.25, 0.75};
}
SnapshotRequest seed(std::type_identity<SnapshotRequest>) {
  return {42};
}
Snapshot seed(std::type_identity<Snapshot>) {
  return {42, 4.2e-4, 2, {5, 9}, {0.1, 0.2, 0.3, 0.4}, {0, 0, 0, 0}, {1000, 1001}, {0.0, 12.5}};
}
CheckpointRequest seed(std::type_identity<CheckpointRequest>) {
  return {420};
}
FluidState seed(std::type_identity<FluidState>) {
  return {420, 2, std::string("FSIF\0\x01 records", 14)};
}
Resume seed(std::type_identity<Resume>) {
  return {420, 4.2e-3, std::string("FSIF\0\x01 records", 14)};
}
Shutdown seed(std::type_identity<Shutdown>) {
  return {"end time reached"};
}
Goodbye seed(std::type_identity<Goodbye>) {
  return {100, 3.5};
}

void write(const fs::path& path, const std::vector<std::byte>& bytes) {
  std::ofstream out(path, std::ios::binary);
  out.write(reinterpret_cast<const char*>(bytes.data()),
            static_cast<std::streamsize>(bytes.size()));
  if (!out) throw ProtocolError("cannot write " + path.string(), "write_seeds", "check the folder");
}

std::string file_name(MessageType type) {
  std::string text;
  for (const char c : name(type)) {
    if (std::isupper(static_cast<unsigned char>(c)) && !text.empty()) text += '_';
    text += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  }
  return text;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: write_seeds OUTPUT_DIR\n");
    return 2;
  }
  const fs::path out = argv[1];
  fs::create_directories(out / "frame");
  fs::create_directories(out / "messages");
  // The message target picks its decoder by the first byte: the index in the list.
  std::size_t index = 0;
  for_each_message_type([&]<class T>(std::type_identity<T> type) {
    const std::vector<std::byte> payload = encode(seed(type));
    write(out / "frame" / (file_name(T::kType) + ".bin"), encode_frame(T::kType, payload));
    std::vector<std::byte> selected{static_cast<std::byte>(index++)};
    selected.insert(selected.end(), payload.begin(), payload.end());
    write(out / "messages" / (file_name(T::kType) + ".bin"), selected);
  });
  std::printf("write_seeds: %zu frames and %zu payloads in %s\n", fuzz::kDecoders.size(),
              fuzz::kDecoders.size(), out.c_str());
  return 0;
}
