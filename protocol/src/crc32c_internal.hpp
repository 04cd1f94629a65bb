#pragma once
// The two CRC-32C implementations behind fsi::protocol::crc32c, visible to the tests so that the
// portable one is checked even on machines where the hardware one is chosen.

#include <cstddef>
#include <cstdint>
#include <span>

namespace fsi::protocol::detail {

// Slice-by-8 tables; any CPU.
std::uint32_t crc32c_portable(std::span<const std::byte> data, std::uint32_t previous = 0);

// The SSE4.2 crc32 instruction. Only call it when crc32c_hardware_available() says so.
std::uint32_t crc32c_hardware(std::span<const std::byte> data, std::uint32_t previous = 0);
bool crc32c_hardware_available();

}  // namespace fsi::protocol::detail
