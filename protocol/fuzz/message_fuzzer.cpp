// libFuzzer target: every message decoder. Input: one byte choosing the decoder (modulo the number
// of message types, see decoders.hpp), then the payload. A decoder must either accept the payload,
// and then re-encoding the message gives back the same bytes, or throw ProtocolError; anything else
// (a crash, a sanitizer report, another exception, a mismatch) is a finding.
#include <cstdint>
#include <cstring>
#include <string>

#include "decoders.hpp"
#include "fuzz_target.hpp"

namespace {

using fsi::protocol::fuzz::kDecoders;

std::array<fsi::protocol::fuzz::Reach, kDecoders.size()> reach;

}  // namespace

void fsi::fuzz::print_reach() {
  fsi::protocol::fuzz::print_reach(reach);
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const std::size_t index = data[0] % kDecoders.size();
  const auto payload = std::as_bytes(std::span(data + 1, size - 1));
  std::vector<std::byte> again;
  try {
    again = kDecoders[index].run(payload);
  } catch (const fsi::protocol::ProtocolError&) {
    ++reach[index].rejected;
    return 0;
  }
  ++reach[index].accepted;
  if (again.size() != payload.size() ||
      (!again.empty() && std::memcmp(again.data(), payload.data(), again.size()) != 0)) {
    fsi::fuzz::finding(name(kDecoders[index].type) + ": an accepted payload of " +
                       std::to_string(payload.size()) + " bytes re-encodes to " +
                       std::to_string(again.size()) + " other bytes");
  }
  return 0;
}
