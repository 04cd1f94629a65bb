#pragma once
// The two CRC-32C implementations behind fsi::protocol::crc32c, visible to the tests so that the
// portable one is checked even on machines where the hardware one is chosen.

#include <cstddef>
#include <cstdint>
#include <span>

namespace fsi::protocol::detail {

// Slice-by-8 tables; any CPU.
std::uint32_t crc32c_portable(std::span<const std::byte> data, std::uint32_t previous = 0);

// The SSE4.2 crc32 instruction, on three streams of kCrc32cLongBlock bytes each while at least
// three such blocks are left, then of kCrc32cShortBlock bytes, then one stream; the streams'
// registers are combined by shifting them over the zero bytes that follow them. Only call it when
// crc32c_hardware_available() says so.
inline constexpr std::size_t kCrc32cLongBlock = 8192;
inline constexpr std::size_t kCrc32cShortBlock = 256;
std::uint32_t crc32c_hardware(std::span<const std::byte> data, std::uint32_t previous = 0);
bool crc32c_hardware_available();

}  // namespace fsi::protocol::detail
