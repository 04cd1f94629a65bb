// CRC-32C: the SSE4.2 instruction where the CPU has it (about 8 bytes per cycle), otherwise
// slice-by-8 tables (eight table look-ups per 8 bytes). Snapshot payloads are megabytes, so the
// byte-at-a-time table would cost more than the network.
#include <array>
#include <cstring>

#include "crc32c_internal.hpp"
#include "fsi/protocol/frame.hpp"

#if defined(__x86_64__)
#include <nmmintrin.h>
#endif

namespace fsi::protocol {
namespace detail {
namespace {

constexpr std::uint32_t kReflectedPolynomial = 0x82F63B78u;  // Castagnoli 0x1EDC6F41, reflected

// tables[k][b]: the CRC register after feeding byte b followed by k zero bytes.
using SliceTables = std::array<std::array<std::uint32_t, 256>, 8>;

constexpr SliceTables make_slice_tables() {
  SliceTables tables{};
  for (std::uint32_t byte = 0; byte < 256; ++byte) {
    std::uint32_t reg = byte;
    for (int bit = 0; bit < 8; ++bit)
      reg = (reg >> 1) ^ ((reg & 1u) ? kReflectedPolynomial : 0u);
    tables[0][byte] = reg;
  }
  for (std::size_t k = 1; k < 8; ++k) {
    for (std::uint32_t byte = 0; byte < 256; ++byte) {
      const std::uint32_t previous = tables[k - 1][byte];
      tables[k][byte] = (previous >> 8) ^ tables[0][previous & 0xFFu];
    }
  }
  return tables;
}

constexpr SliceTables kSliceTables = make_slice_tables();

std::uint32_t load_le32(const unsigned char* bytes) {
  std::uint32_t value;
  std::memcpy(&value, bytes, sizeof value);
  return value;  // the host is little-endian (static_assert in messages.cpp)
}

}  // namespace

std::uint32_t crc32c_portable(std::span<const std::byte> data, std::uint32_t previous) {
  const auto* bytes = reinterpret_cast<const unsigned char*>(data.data());
  std::size_t left = data.size();
  std::uint32_t reg = ~previous;
  const auto& t = kSliceTables;
  while (left >= 8) {
    const std::uint32_t low = load_le32(bytes) ^ reg;
    const std::uint32_t high = load_le32(bytes + 4);
    reg = t[7][low & 0xFFu] ^ t[6][(low >> 8) & 0xFFu] ^ t[5][(low >> 16) & 0xFFu] ^
          t[4][low >> 24] ^ t[3][high & 0xFFu] ^ t[2][(high >> 8) & 0xFFu] ^
          t[1][(high >> 16) & 0xFFu] ^ t[0][high >> 24];
    bytes += 8;
    left -= 8;
  }
  for (; left > 0; --left, ++bytes)
    reg = (reg >> 8) ^ t[0][(reg ^ *bytes) & 0xFFu];
  return ~reg;
}

#if defined(__x86_64__)

__attribute__((target("sse4.2"))) std::uint32_t crc32c_hardware(std::span<const std::byte> data,
                                                                std::uint32_t previous) {
  const auto* bytes = reinterpret_cast<const unsigned char*>(data.data());
  std::size_t left = data.size();
  std::uint64_t reg = ~previous;
  while (left >= 8) {
    std::uint64_t word;
    std::memcpy(&word, bytes, sizeof word);
    reg = _mm_crc32_u64(reg, word);
    bytes += 8;
    left -= 8;
  }
  auto narrow = static_cast<std::uint32_t>(reg);
  for (; left > 0; --left, ++bytes)
    narrow = _mm_crc32_u8(narrow, *bytes);
  return ~narrow;
}

bool crc32c_hardware_available() {
  static const bool available = [] {
    __builtin_cpu_init();  // may run before libgcc's own initialisation during static set-up
    return __builtin_cpu_supports("sse4.2") != 0;
  }();
  return available;
}

#else

std::uint32_t crc32c_hardware(std::span<const std::byte> data, std::uint32_t previous) {
  return crc32c_portable(data, previous);
}
bool crc32c_hardware_available() {
  return false;
}

#endif

}  // namespace detail

std::uint32_t crc32c(std::span<const std::byte> data, std::uint32_t previous) {
  return detail::crc32c_hardware_available() ? detail::crc32c_hardware(data, previous)
                                             : detail::crc32c_portable(data, previous);
}

}  // namespace fsi::protocol
