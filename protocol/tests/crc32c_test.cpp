#include <gtest/gtest.h>

#include <boost/crc.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "crc32c_internal.hpp"
#include "fsi/protocol/frame.hpp"

namespace fsi::protocol {
namespace {

using Implementation = std::uint32_t (*)(std::span<const std::byte>, std::uint32_t);

// Boost's byte-wise CRC with the Castagnoli parameters serves as the independent reference.
std::uint32_t reference_crc(std::span<const std::byte> data) {
  boost::crc_optimal<32, 0x1EDC6F41, 0xFFFFFFFF, 0xFFFFFFFF, true, true> crc;
  crc.process_bytes(data.data(), data.size());
  return crc.checksum();
}

std::vector<std::byte> random_bytes(std::size_t size, unsigned seed) {
  std::mt19937 generator(seed);
  std::vector<std::byte> bytes(size);
  for (auto& b : bytes)
    b = static_cast<std::byte>(generator() & 0xFFu);
  return bytes;
}

std::vector<std::pair<std::string, Implementation>> implementations() {
  std::vector<std::pair<std::string, Implementation>> result{{"portable", &detail::crc32c_portable},
                                                             {"dispatching", &crc32c}};
  if (detail::crc32c_hardware_available()) result.emplace_back("sse4.2", &detail::crc32c_hardware);
  return result;
}

TEST(ProtocolCrc32c, CheckValueOf123456789) {
  const std::string text = "123456789";
  const auto bytes = std::as_bytes(std::span(text));
  EXPECT_EQ(reference_crc(bytes), 0xE3069283u);
  for (const auto& [label, crc] : implementations()) {
    EXPECT_EQ(crc(bytes, 0), 0xE3069283u) << label;
    EXPECT_EQ(crc({}, 0), 0u) << label;
  }
}

TEST(ProtocolCrc32c, AgreesWithTheReferenceForEveryLengthAndAlignment) {
  const auto data = random_bytes(4096 + 16, 7);
  for (const auto& [label, crc] : implementations()) {
    for (std::size_t start = 0; start < 8; ++start) {
      for (std::size_t length = 0; length < 300; ++length) {
        const auto piece = std::span(data).subspan(start, length);
        ASSERT_EQ(crc(piece, 0), reference_crc(piece))
            << label << " start " << start << " length " << length;
      }
    }
    const auto large = std::span(data).subspan(3, 4096);
    EXPECT_EQ(crc(large, 0), reference_crc(large)) << label;
  }
}

// The three-stream hardware CRC against the portable one: random lengths 0..10000 (below, at and
// above the 3 x 256-byte short blocks) at random, mostly unaligned, starts.
TEST(ProtocolCrc32c, HardwareAgreesWithPortableOnRandomLengthsAndStarts) {
  if (!detail::crc32c_hardware_available()) GTEST_SKIP() << "no SSE4.2 on this CPU";
  const auto data = random_bytes(10000 + 64, 11);
  std::mt19937 generator(12);
  std::uniform_int_distribution<std::size_t> length_of(0, 10000);
  std::uniform_int_distribution<std::size_t> start_of(0, 63);
  for (int trial = 0; trial < 3000; ++trial) {
    const std::size_t start = start_of(generator);
    const std::size_t length = length_of(generator);
    const auto piece = std::span(data).subspan(start, length);
    const std::uint32_t previous = trial % 2 == 0 ? 0u : static_cast<std::uint32_t>(generator());
    ASSERT_EQ(detail::crc32c_hardware(piece, previous), detail::crc32c_portable(piece, previous))
        << "start " << start << " length " << length << " previous " << previous;
  }
}

// Lengths at the edges of the long (3 x 8192 bytes) and short (3 x 256 bytes) three-stream blocks
// and of whole words, at every start within a word, so that every combination of the stages
// (bytes to a word boundary, long blocks, short blocks, words, bytes) runs.
TEST(ProtocolCrc32c, HardwareAgreesWithPortableAtItsBlockBoundaries) {
  if (!detail::crc32c_hardware_available()) GTEST_SKIP() << "no SSE4.2 on this CPU";
  const std::size_t long_triple = 3 * detail::kCrc32cLongBlock;
  const std::size_t short_triple = 3 * detail::kCrc32cShortBlock;
  const auto data = random_bytes(3 * long_triple + 2 * short_triple + 64, 13);
  std::vector<std::size_t> lengths;
  for (std::size_t longs = 0; longs <= 2; ++longs) {
    for (std::size_t shorts = 0; shorts <= 2; ++shorts) {
      const std::size_t base = longs * long_triple + shorts * short_triple;
      for (std::size_t extra : {0ul, 1ul, 7ul, 8ul, 9ul, 15ul, 17ul, 255ul, 767ul})
        lengths.push_back(base + extra);
      if (base > 0) lengths.push_back(base - 1);
    }
  }
  for (std::size_t start = 0; start < 8; ++start) {
    for (std::size_t length : lengths) {
      const auto piece = std::span(data).subspan(start, length);
      ASSERT_EQ(detail::crc32c_hardware(piece, 0), detail::crc32c_portable(piece, 0))
          << "start " << start << " length " << length;
    }
  }
  const auto whole = std::span(data).subspan(5);
  EXPECT_EQ(detail::crc32c_hardware(whole, 0), reference_crc(whole));
}

TEST(ProtocolCrc32c, ContinuesOverPieces) {
  const auto data = random_bytes(100003, 3);
  const std::uint32_t whole = reference_crc(data);
  for (const auto& [label, crc] : implementations()) {
    for (std::size_t cut : {0ul, 1ul, 7ul, 8ul, 13ul, 4096ul, 99999ul, 100003ul}) {
      const auto first = std::span(data).first(cut);
      const auto rest = std::span(data).subspan(cut);
      EXPECT_EQ(crc(rest, crc(first, 0)), whole) << label << " cut " << cut;
    }
  }
}

TEST(ProtocolCrc32c, NoticesEverySingleBitFlip) {
  auto data = random_bytes(64, 5);
  const std::uint32_t good = crc32c(data);
  for (std::size_t bit = 0; bit < data.size() * 8; ++bit) {
    data[bit / 8] ^= static_cast<std::byte>(1u << (bit % 8));
    ASSERT_NE(crc32c(data), good) << "bit " << bit;
    data[bit / 8] ^= static_cast<std::byte>(1u << (bit % 8));
  }
}

// Speed is reported, not asserted (shared machines vary); snapshots are megabytes per frame.
TEST(ProtocolCrc32c, ThroughputIsPrinted) {
  const auto data = random_bytes(32u << 20, 1);
  for (const auto& [label, crc] : implementations()) {
    // Best of three: the first pass may pay for page faults and a cold cache.
    std::uint32_t value = 0;
    double seconds = 1e30;
    for (int pass = 0; pass < 3; ++pass) {
      const auto start = std::chrono::steady_clock::now();
      value = crc(data, 0);
      seconds = std::min(
          seconds, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    }
    std::printf("CRC-32C %-11s over 32 MiB: %7.0f MB/s (crc 0x%08x)\n", label.c_str(),
                static_cast<double>(data.size()) / 1e6 / seconds, static_cast<unsigned>(value));
  }
}

}  // namespace
}  // namespace fsi::protocol
