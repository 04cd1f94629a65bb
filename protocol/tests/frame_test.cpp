#include <gtest/gtest.h>

#include <chrono>
#include <cstring>
#include <random>

#include "fsi/protocol/frame.hpp"

namespace fsi::protocol {
namespace {

std::vector<std::byte> bytes_of(const std::string& text) {
  std::vector<std::byte> out(text.size());
  std::memcpy(out.data(), text.data(), text.size());
  return out;
}

std::string error_of(std::span<const std::byte> frame,
                     std::size_t max_payload = kDefaultMaxPayload) {
  try {
    decode_frame(frame, max_payload);
  } catch (const ProtocolError& error) {
    return error.what();
  }
  return "";
}

TEST(Crc32c, CheckValueAndContinuation) {
  EXPECT_EQ(crc32c(bytes_of("123456789")), 0xE3069283u);
  EXPECT_EQ(crc32c({}), 0u);
  std::mt19937 rng(3);
  std::vector<std::byte> data(100003);
  for (auto& b : data)
    b = std::byte(rng() & 0xFF);
  const std::uint32_t whole = crc32c(data);
  for (std::size_t cut : {0ul, 1ul, 7ul, 8ul, 4096ul, 99999ul}) {
    EXPECT_EQ(crc32c(std::span(data).subspan(cut), crc32c(std::span(data).first(cut))), whole);
  }
  data[50000] ^= std::byte{1};
  EXPECT_NE(crc32c(data), whole);
}

TEST(Crc32c, ThroughputIsPrinted) {
  std::vector<std::byte> data(64 << 20, std::byte{0x5A});
  const auto start = std::chrono::steady_clock::now();
  std::uint32_t c = crc32c(data);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("CRC-32C over 64 MiB: %.0f MB/s (crc %08x)\n", 64.0 * 1.048576 / seconds, c);
}

TEST(Frame, RoundTrip) {
  const auto payload = bytes_of("payload bytes");
  const auto frame = encode_frame(MessageType::Step, payload);
  ASSERT_EQ(frame.size(), kHeaderSize + payload.size());
  const Frame decoded = decode_frame(frame);
  EXPECT_EQ(decoded.header.type, MessageType::Step);
  EXPECT_EQ(decoded.header.major, kMajorVersion);
  EXPECT_EQ(decoded.header.minor, kMinorVersion);
  EXPECT_EQ(decoded.payload, payload);
}

TEST(Frame, RejectsEveryKindOfDamage) {
  const auto good = encode_frame(MessageType::Forces, bytes_of("0123456789"));
  auto damaged = good;
  damaged[0] = std::byte{'X'};
  EXPECT_NE(error_of(damaged).find("bad frame magic"), std::string::npos);

  damaged = good;
  damaged[25] ^= std::byte{0x10};
  const std::string crc = error_of(damaged);
  EXPECT_NE(crc.find("CRC-32C mismatch in Forces frame"), std::string::npos) << crc;

  damaged = good;
  damaged[8] = std::byte{0x77};
  damaged[9] = std::byte{0};
  EXPECT_NE(error_of(damaged).find("unknown type 0x0077"), std::string::npos);

  damaged = good;
  damaged[10] = std::byte{1};
  EXPECT_NE(error_of(damaged).find("flags"), std::string::npos);

  EXPECT_NE(error_of(good, 5).find("more than the 5 allowed"), std::string::npos);
  EXPECT_NE(error_of(std::span(good).first(good.size() - 1)).find("truncated Forces frame"),
            std::string::npos);
  EXPECT_NE(error_of(std::span(good).first(10)).find("truncated frame"), std::string::npos);
}

TEST(Frame, MajorVersionIsCheckedExceptForHelloAndError) {
  const auto payload = bytes_of("x");
  const auto step = encode_frame(MessageType::Step, payload, 2, 3);
  const std::string text = error_of(step);
  EXPECT_NE(text.find("protocol 2.3"), std::string::npos) << text;
  EXPECT_NE(text.find("protocol 1.0"), std::string::npos) << text;
  for (MessageType type : {MessageType::Hello, MessageType::Error}) {
    const Frame frame = decode_frame(encode_frame(type, payload, 2, 3));
    EXPECT_EQ(frame.header.major, 2);
    EXPECT_EQ(frame.header.minor, 3);
  }
}

}  // namespace
}  // namespace fsi::protocol
