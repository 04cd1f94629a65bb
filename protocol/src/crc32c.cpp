// CRC-32C: the SSE4.2 crc32 instruction on three interleaved streams where the CPU has it (close
// to 3 x 8 bytes per cycle; one stream is bound by the instruction's 3-cycle latency), otherwise
// slice-by-8 tables (eight table look-ups per 8 bytes). Frames carry megabytes of doubles and the
// sender must finish the CRC before the header can go out, so its speed is part of the latency.
#include <array>
#include <cstdint>
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

namespace {

// ---- shifting a CRC register over zero bytes, for combining independent streams ----
//
// Without the initial and final inversion the register update is linear over GF(2): feeding A
// then B from register r gives shift(f(r, A), |B|) ^ f(0, B), where shift(x, n) is the register x
// after n zero bytes. shift(., n) is a fixed 32x32 bit matrix, so it is four table look-ups.

// column[i]: the image of register bit i.
using BitMatrix = std::array<std::uint32_t, 32>;

constexpr std::uint32_t times(const BitMatrix& matrix, std::uint32_t vector) {
  std::uint32_t result = 0;
  for (int bit = 0; bit < 32; ++bit) {
    if ((vector >> bit) & 1u) result ^= matrix[static_cast<std::size_t>(bit)];
  }
  return result;
}

// shift(., bytes) for a power of two: the one-bit step squared until it spans 8 * bytes bits.
constexpr BitMatrix zero_bytes_operator(std::size_t bytes) {
  BitMatrix matrix{};
  matrix[0] = kReflectedPolynomial;  // one zero bit
  for (std::size_t bit = 1; bit < 32; ++bit)
    matrix[bit] = std::uint32_t{1} << (bit - 1);
  for (std::size_t bits = 1; bits < 8 * bytes; bits *= 2) {
    BitMatrix squared{};
    for (std::size_t column = 0; column < 32; ++column)
      squared[column] = times(matrix, matrix[column]);
    matrix = squared;
  }
  return matrix;
}

// tables[k][b] = shift(b << 8k, bytes).
using ShiftTables = std::array<std::array<std::uint32_t, 256>, 4>;

constexpr ShiftTables make_shift_tables(std::size_t bytes) {
  const BitMatrix shift = zero_bytes_operator(bytes);
  ShiftTables tables{};
  for (std::size_t k = 0; k < 4; ++k) {
    for (std::uint32_t byte = 0; byte < 256; ++byte)
      tables[k][byte] = times(shift, byte << (8 * k));
  }
  return tables;
}

static_assert((kCrc32cLongBlock & (kCrc32cLongBlock - 1)) == 0 &&
                  (kCrc32cShortBlock & (kCrc32cShortBlock - 1)) == 0 && kCrc32cShortBlock % 8 == 0,
              "zero_bytes_operator squares, so the blocks are powers of two of whole words");
constexpr ShiftTables kShiftLong = make_shift_tables(kCrc32cLongBlock);
constexpr ShiftTables kShiftShort = make_shift_tables(kCrc32cShortBlock);

std::uint32_t shift(const ShiftTables& t, std::uint32_t reg) {
  return t[0][reg & 0xFFu] ^ t[1][(reg >> 8) & 0xFFu] ^ t[2][(reg >> 16) & 0xFFu] ^ t[3][reg >> 24];
}

std::uint64_t load_word(const unsigned char* bytes) {
  std::uint64_t word;
  std::memcpy(&word, bytes, sizeof word);
  return word;
}

// While at least three blocks are left: one stream per block, so that three crc32 instructions
// (latency 3 cycles, one issued per cycle) are in flight at once; then the three registers are
// combined into one.
template <std::size_t kBlock>
__attribute__((target("sse4.2"))) std::uint32_t three_streams(const unsigned char*& bytes,
                                                              std::size_t& left, std::uint32_t reg,
                                                              const ShiftTables& shift_block) {
  while (left >= 3 * kBlock) {
    std::uint64_t first = reg;
    std::uint64_t second = 0;
    std::uint64_t third = 0;
    for (std::size_t offset = 0; offset < kBlock; offset += 8) {
      first = _mm_crc32_u64(first, load_word(bytes + offset));
      second = _mm_crc32_u64(second, load_word(bytes + kBlock + offset));
      third = _mm_crc32_u64(third, load_word(bytes + 2 * kBlock + offset));
    }
    reg =
        shift(shift_block, static_cast<std::uint32_t>(first)) ^ static_cast<std::uint32_t>(second);
    reg = shift(shift_block, reg) ^ static_cast<std::uint32_t>(third);
    bytes += 3 * kBlock;
    left -= 3 * kBlock;
  }
  return reg;
}

}  // namespace

__attribute__((target("sse4.2"))) std::uint32_t crc32c_hardware(std::span<const std::byte> data,
                                                                std::uint32_t previous) {
  const auto* bytes = reinterpret_cast<const unsigned char*>(data.data());
  std::size_t left = data.size();
  std::uint32_t reg = ~previous;
  // Whole words from an 8-byte boundary on.
  for (; left > 0 && (reinterpret_cast<std::uintptr_t>(bytes) & 7u) != 0; --left, ++bytes)
    reg = _mm_crc32_u8(reg, *bytes);
  reg = three_streams<kCrc32cLongBlock>(bytes, left, reg, kShiftLong);
  reg = three_streams<kCrc32cShortBlock>(bytes, left, reg, kShiftShort);
  std::uint64_t wide = reg;
  for (; left >= 8; left -= 8, bytes += 8)
    wide = _mm_crc32_u64(wide, load_word(bytes));
  reg = static_cast<std::uint32_t>(wide);
  for (; left > 0; --left, ++bytes)
    reg = _mm_crc32_u8(reg, *bytes);
  return ~reg;
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
