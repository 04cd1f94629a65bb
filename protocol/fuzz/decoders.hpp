#pragma once
// The table both protocol fuzz targets and the seed writer share: every message type with its
// decoder, in the order of message_list.hpp. The message target's first input byte picks the entry
// (modulo the table size), so a seed for entry i starts with the byte i.

#include <array>
#include <cstddef>
#include <cstdio>
#include <span>
#include <type_traits>
#include <variant>
#include <vector>

#include "fsi/protocol/messages.hpp"

namespace fsi::protocol::fuzz {

// Decodes `payload` as a T and, if it is accepted, returns its re-encoding (the decoder and the
// encoder walk one layout, so an accepted payload must come back byte for byte).
using DecodeAndReencode = std::vector<std::byte> (*)(std::span<const std::byte> payload);

template <class T>
std::vector<std::byte> decode_and_reencode(std::span<const std::byte> payload) {
  return encode(decode_as<T>(payload));
}

struct Decoder {
  MessageType type;
  DecodeAndReencode run;
};

// One entry per message type, in the order of message_list.hpp.
inline constexpr auto kDecoders =
    []<class... Messages>(std::type_identity<std::variant<Messages...>>) {
      return std::array<Decoder, sizeof...(Messages)>{
          {{Messages::kType, &decode_and_reencode<Messages>}...}};
    }(std::type_identity<Message>{});

// Per decoder: inputs it accepted and inputs it rejected with a ProtocolError. Printed at exit as
// "fuzz-reach: <type> accepted=N rejected=M"; scripts/run-fuzzers fails a run in which any
// decoder has a zero, so a corpus or dispatch mistake cannot hide a decoder from the fuzzer.
struct Reach {
  std::size_t accepted = 0;
  std::size_t rejected = 0;
};

inline void print_reach(const std::array<Reach, kDecoders.size()>& reach) {
  for (std::size_t i = 0; i < kDecoders.size(); ++i) {
    std::fprintf(stderr, "fuzz-reach: %s accepted=%zu rejected=%zu\n",
                 name(kDecoders[i].type).c_str(), reach[i].accepted, reach[i].rejected);
  }
}

}  // namespace fsi::protocol::fuzz
