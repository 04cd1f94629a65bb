// CRC-32C with the SSE4.2 instruction where the CPU has it, slice-by-8 tables otherwise.
#include <array>
#include <cstring>

#include "fsi/protocol/frame.hpp"

#if defined(__x86_64__)
#include <nmmintrin.h>
#endif

namespace fsi::protocol {
namespace {

constexpr std::uint32_t kPolynomial = 0x82F63B78u;  // reflected 0x1EDC6F41

struct Tables {
  std::array<std::array<std::uint32_t, 256>, 8> t{};
  constexpr Tables() {
    for (std::uint32_t i = 0; i < 256; ++i) {
      std::uint32_t c = i;
      for (int k = 0; k < 8; ++k)
        c = (c & 1u) ? (c >> 1) ^ kPolynomial : c >> 1;
      t[0][i] = c;
    }
    for (std::uint32_t i = 0; i < 256; ++i) {
      for (int s = 1; s < 8; ++s)
        t[s][i] = (t[s - 1][i] >> 8) ^ t[0][t[s - 1][i] & 0xFFu];
    }
  }
};
constexpr Tables kTables;

std::uint32_t crc_tables(const unsigned char* p, std::size_t n, std::uint32_t c) {
  while (n >= 8) {
    std::uint32_t low;
    std::uint32_t high;
    std::memcpy(&low, p, 4);
    std::memcpy(&high, p + 4, 4);
    low ^= c;
    c = kTables.t[7][low & 0xFF] ^ kTables.t[6][(low >> 8) & 0xFF] ^
        kTables.t[5][(low >> 16) & 0xFF] ^ kTables.t[4][low >> 24] ^ kTables.t[3][high & 0xFF] ^
        kTables.t[2][(high >> 8) & 0xFF] ^ kTables.t[1][(high >> 16) & 0xFF] ^
        kTables.t[0][high >> 24];
    p += 8;
    n -= 8;
  }
  while (n--)
    c = (c >> 8) ^ kTables.t[0][(c ^ *p++) & 0xFF];
  return c;
}

#if defined(__x86_64__)
__attribute__((target("sse4.2"))) std::uint32_t crc_hardware(const unsigned char* p, std::size_t n,
                                                             std::uint32_t c) {
  std::uint64_t wide = c;
  while (n >= 8) {
    std::uint64_t word;
    std::memcpy(&word, p, 8);
    wide = _mm_crc32_u64(wide, word);
    p += 8;
    n -= 8;
  }
  c = static_cast<std::uint32_t>(wide);
  while (n--)
    c = _mm_crc32_u8(c, *p++);
  return c;
}
const bool kHaveHardware = __builtin_cpu_supports("sse4.2");
#endif

}  // namespace

std::uint32_t crc32c(std::span<const std::byte> data, std::uint32_t previous) {
  const auto* p = reinterpret_cast<const unsigned char*>(data.data());
  std::uint32_t c = ~previous;
#if defined(__x86_64__)
  if (kHaveHardware) return ~crc_hardware(p, data.size(), c);
#endif
  return ~crc_tables(p, data.size(), c);
}

}  // namespace fsi::protocol
