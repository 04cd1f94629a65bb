// libFuzzer target: the frame decoder and the receive path behind it. Input: the bytes of one
// frame (header and payload). decode_frame must accept it, and then the same header and payload
// encode to exactly these bytes, or throw ProtocolError; an accepted frame's payload then goes to
// the message decoder of its type, as in Channel::receive. The payload limit is small (64 KiB) so
// that oversize lengths are exercised against the check that precedes any allocation.
#include <cstdint>
#include <cstdlib>
#include <cstring>

#include "decoders.hpp"

namespace {

using fsi::protocol::fuzz::kDecoders;

constexpr std::size_t kMaxPayload = std::size_t{1} << 16;

// Frames decode_frame accepted, per type; frames it rejected; payloads the message decoders
// accepted behind an accepted frame. Printed at exit for scripts/run-fuzzers (decoders.hpp).
std::array<std::size_t, kDecoders.size()> frames_accepted{};
std::size_t frames_rejected = 0;
std::size_t payloads_accepted = 0;

void print_reach_at_exit() {
  std::fprintf(stderr, "fuzz-reach: frames rejected=%zu\n", frames_rejected);
  std::fprintf(stderr, "fuzz-reach: payloads accepted=%zu\n", payloads_accepted);
  for (std::size_t i = 0; i < kDecoders.size(); ++i) {
    std::fprintf(stderr, "fuzz-reach: %s frames accepted=%zu\n", name(kDecoders[i].type).c_str(),
                 frames_accepted[i]);
  }
}

std::size_t index_of(fsi::protocol::MessageType type) {
  for (std::size_t i = 0; i < kDecoders.size(); ++i) {
    if (kDecoders[i].type == type) return i;
  }
  std::fprintf(stderr, "decode_frame accepted a frame of %s\n", name(type).c_str());
  std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  std::atexit(print_reach_at_exit);
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace fsi::protocol;
  const auto bytes = std::as_bytes(std::span(data, size));
  Frame frame;
  try {
    frame = decode_frame(bytes, kMaxPayload);
  } catch (const ProtocolError&) {
    ++frames_rejected;
    return 0;
  }
  const FrameHeader& header = frame.header;
  if (header.payload_length != frame.payload.size() || frame.payload.size() > kMaxPayload) {
    std::fprintf(stderr, "accepted frame: length field %u, %zu payload bytes\n",
                 header.payload_length, frame.payload.size());
    std::abort();
  }
  // Flags are zero in protocol 1; only Hello and Error of another major may carry others.
  if (header.flags == 0) {
    const auto again = encode_frame(header.type, frame.payload, header.major, header.minor);
    if (again.size() != size || std::memcmp(again.data(), data, size) != 0) {
      std::fprintf(stderr, "an accepted %s frame of %zu bytes re-encodes differently\n",
                   name(header.type).c_str(), size);
      std::abort();
    }
  }
  ++frames_accepted[index_of(header.type)];
  try {
    decode(header.type, frame.payload);
    ++payloads_accepted;
  } catch (const ProtocolError&) {
  }
  return 0;
}
