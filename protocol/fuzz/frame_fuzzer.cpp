// libFuzzer target: the frame decoder and the receive path behind it. Input: the bytes of one
// frame (header and payload). decode_frame must accept it, and then the same header and payload
// encode to exactly these bytes, or throw ProtocolError; an accepted frame's payload then goes to
// the message decoder of its type, as in Channel::receive. The payload limit is small (64 KiB) so
// that oversize lengths are exercised against the check that precedes any allocation.
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>

#include "decoders.hpp"
#include "fuzz_target.hpp"

namespace {

using fsi::protocol::fuzz::kDecoders;

constexpr std::size_t kMaxPayload = std::size_t{1} << 16;

// Frames decode_frame accepted, per type; frames it rejected; payloads the message decoders
// accepted behind an accepted frame. Printed at exit for scripts/run-fuzzers (decoders.hpp).
std::array<std::size_t, kDecoders.size()> frames_accepted{};
std::size_t frames_rejected = 0;
std::size_t payloads_accepted = 0;

std::size_t index_of(fsi::protocol::MessageType type) {
  for (std::size_t i = 0; i < kDecoders.size(); ++i) {
    if (kDecoders[i].type == type) return i;
  }
  fsi::fuzz::finding("decode_frame accepted a frame of " + name(type));
}

}  // namespace

void fsi::fuzz::print_reach() {
  std::fprintf(stderr, "fuzz-reach: frames rejected=%zu\n", frames_rejected);
  std::fprintf(stderr, "fuzz-reach: payloads accepted=%zu\n", payloads_accepted);
  for (std::size_t i = 0; i < kDecoders.size(); ++i) {
    std::fprintf(stderr, "fuzz-reach: %s frames accepted=%zu\n", name(kDecoders[i].type).c_str(),
                 frames_accepted[i]);
  }
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
    fsi::fuzz::finding("accepted frame: length field " + std::to_string(header.payload_length) +
                       ", " + std::to_string(frame.payload.size()) + " payload bytes");
  }
  // Flags are zero in protocol 1; only Hello and Error of another major may carry others.
  if (header.flags == 0) {
    const auto again = encode_frame(header.type, frame.payload, header.major, header.minor);
    if (again.size() != size || std::memcmp(again.data(), data, size) != 0) {
      fsi::fuzz::finding("an accepted " + name(header.type) + " frame of " + std::to_string(size) +
                         " bytes re-encodes differently");
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
