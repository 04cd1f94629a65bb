#include <gtest/gtest.h>

#include <cstring>
#include <string>
#include <vector>

#include "error_text.hpp"
#include "fsi/protocol/frame.hpp"
#include "fsi/protocol/messages.hpp"

namespace fsi::protocol {
namespace {

using namespace test;

std::vector<std::byte> bytes_of(std::initializer_list<unsigned> values) {
  std::vector<std::byte> out;
  for (unsigned v : values)
    out.push_back(static_cast<std::byte>(v));
  return out;
}

std::vector<std::byte> bytes_of(const std::string& text) {
  const auto view = std::as_bytes(std::span(text));
  return {view.begin(), view.end()};
}

// Written by an independent CRC-32C in Python from the tables of docs/protocol.md. These bytes
// are frozen: any major version must produce and accept them.
const std::vector<std::byte> kGoldenHello = bytes_of(
    {0x46, 0x53, 0x49, 0x50, 0x01, 0x00, 0x00, 0x00, 0x01, 0x00, 0x00, 0x00, 0x19, 0x00, 0x00,
     0x00, 0xc3, 0x94, 0xb5, 0x92, 0x05, 0x00, 0x00, 0x00, 0x31, 0x2e, 0x32, 0x2e, 0x33, 0x04,
     0x00, 0x00, 0x00, 0x6e, 0x6f, 0x64, 0x65, 0x04, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00});
// An Error{VersionMismatch, "old"} frame from a peer speaking protocol 7.3.
const std::vector<std::byte> kGoldenErrorFromVersion7 = bytes_of(
    {0x46, 0x53, 0x49, 0x50, 0x07, 0x00, 0x03, 0x00, 0x03, 0x00, 0x00, 0x00, 0x0b, 0x00, 0x00, 0x00,
     0xba, 0x4b, 0xca, 0xd3, 0x01, 0x00, 0x00, 0x00, 0x03, 0x00, 0x00, 0x00, 0x6f, 0x6c, 0x64});

TEST(ProtocolFrame, HelloMatchesTheFrozenBytes) {
  const Hello hello{"1.2.3", "node", 4, 0};
  // A Hello of protocol 1.0: later minors write their own minor into the header.
  EXPECT_EQ(encode_frame(MessageType::Hello, encode(hello), 1, 0), kGoldenHello);
  const Frame frame = decode_frame(kGoldenHello);
  EXPECT_EQ(std::get<Hello>(decode(frame.header.type, frame.payload)), hello);
}

TEST(ProtocolFrame, ErrorOfAnotherMajorVersionStillDecodes) {
  const Frame frame = decode_frame(kGoldenErrorFromVersion7);
  EXPECT_EQ(frame.header.major, 7);
  EXPECT_EQ(frame.header.minor, 3);
  const auto error = std::get<ErrorMessage>(decode(frame.header.type, frame.payload));
  EXPECT_EQ(error.code, ErrorCode::VersionMismatch);
  EXPECT_EQ(error.text, "old");
}

TEST(ProtocolFrame, HeaderFieldsSitWhereTheSpecSays) {
  const auto payload = bytes_of("abc");
  const auto header = encode_header(MessageType::SnapshotRequest, payload, 0x0102, 0x0304);
  EXPECT_EQ(std::vector(header.begin(), header.begin() + 4), bytes_of("FSIP"));
  EXPECT_EQ(std::vector(header.begin() + 4, header.begin() + 16),
            bytes_of({0x02, 0x01, 0x04, 0x03, 0x30, 0x00, 0x00, 0x00, 0x03, 0x00, 0x00, 0x00}));
  std::vector<std::byte> covered(header.begin(), header.begin() + 16);
  covered.insert(covered.end(), payload.begin(), payload.end());
  const std::uint32_t crc = crc32c(covered);
  EXPECT_EQ(std::vector(header.begin() + 16, header.end()),
            bytes_of({crc & 0xFFu, (crc >> 8) & 0xFFu, (crc >> 16) & 0xFFu, crc >> 24}));
}

TEST(ProtocolFrame, RoundTrip) {
  const auto payload = bytes_of("payload bytes");
  const auto frame = encode_frame(MessageType::Step, payload);
  ASSERT_EQ(frame.size(), kHeaderSize + payload.size());
  const Frame decoded = decode_frame(frame);
  EXPECT_EQ(decoded.header.type, MessageType::Step);
  EXPECT_EQ(decoded.header.major, kMajorVersion);
  EXPECT_EQ(decoded.header.minor, kMinorVersion);
  EXPECT_EQ(decoded.header.flags, 0);
  EXPECT_EQ(decoded.header.payload_length, payload.size());
  EXPECT_EQ(decoded.payload, payload);
  EXPECT_NO_THROW(decode_frame(encode_frame(MessageType::Goodbye, {})));
}

TEST(ProtocolFrame, BadMagic) {
  auto frame = encode_frame(MessageType::Forces, bytes_of("0123456789"));
  frame[0] = std::byte{'G'};
  EXPECT_NE(frame_error(frame).find("bad frame magic"), std::string::npos);
}

TEST(ProtocolFrame, CrcMismatchNamesTypeAndBothValues) {
  const auto good = encode_frame(MessageType::Forces, bytes_of("0123456789"));
  for (std::size_t position : {std::size_t{4}, std::size_t{13}, std::size_t{17}, good.size() - 1}) {
    auto damaged = good;
    damaged[position] ^= std::byte{0x10};
    const std::string text = frame_error(damaged);
    // Byte 4 is in the major version, 13 in the length: those faults are caught first.
    if (position == 4) {
      EXPECT_NE(text.find("protocol 17." + std::to_string(kMinorVersion)), std::string::npos)
          << text;
    } else if (position == 13) {
      EXPECT_NE(text.find("truncated Forces frame"), std::string::npos) << text;
    } else {
      EXPECT_NE(text.find("CRC-32C mismatch in Forces frame: computed 0x"), std::string::npos)
          << text;
      EXPECT_NE(text.find(", received 0x"), std::string::npos) << text;
    }
  }
}

TEST(ProtocolFrame, UnknownType) {
  auto frame = encode_frame(MessageType::Forces, bytes_of("x"));
  frame[8] = std::byte{0x77};
  frame[9] = std::byte{0x00};
  const std::string text = frame_error(frame);
  EXPECT_NE(text.find("unknown type 0x0077"), std::string::npos) << text;
}

TEST(ProtocolFrame, NonzeroFlags) {
  auto frame = encode_frame(MessageType::Forces, bytes_of("x"));
  frame[11] = std::byte{0x80};
  const std::string text = frame_error(frame);
  EXPECT_NE(text.find("Forces frame has flags 0x8000"), std::string::npos) << text;
}

TEST(ProtocolFrame, OversizeLengthIsRefusedBeforeThePayload) {
  const auto frame = encode_frame(MessageType::Snapshot, std::vector<std::byte>(100));
  const std::string text = frame_error(std::span(frame).first(kHeaderSize), 99);
  EXPECT_NE(text.find("announces a payload of 100 bytes, more than the 99"), std::string::npos)
      << text;
  EXPECT_NO_THROW(decode_frame(frame, 100));
}

// A header announcing 4 GiB - 1 bytes with nothing behind it: the limit is reported (before any
// buffer for the payload could be made), not the missing bytes.
TEST(ProtocolFrame, OversizeLengthIsReportedBeforeTheMissingPayload) {
  auto frame = encode_frame(MessageType::Particles, {});
  for (std::size_t k = 12; k < 16; ++k)
    frame[k] = std::byte{0xFF};
  const std::string text = frame_error(frame);
  EXPECT_NE(text.find("Particles frame announces a payload of 4294967295 bytes, more than the "
                      "1073741824 bytes this side accepts"),
            std::string::npos)
      << text;
}

TEST(ProtocolFrame, TruncatedAndOverlongFrames) {
  const auto frame = encode_frame(MessageType::Forces, bytes_of("0123456789"));
  EXPECT_NE(frame_error(std::span(frame).first(10)).find("truncated frame: 10 bytes"),
            std::string::npos);
  EXPECT_NE(frame_error(std::span(frame).first(frame.size() - 1)).find("truncated Forces frame"),
            std::string::npos);
  auto longer = frame;
  longer.push_back(std::byte{0});
  EXPECT_NE(frame_error(longer).find("overlong Forces frame"), std::string::npos);
}

TEST(ProtocolFrame, MajorVersionIsCheckedExceptForHelloAndError) {
  const auto payload = bytes_of("x");
  const std::string text = frame_error(encode_frame(MessageType::Step, payload, 2, 3));
  EXPECT_NE(text.find("Step frame of protocol 2.3, but this side speaks " +
                      version_text(kMajorVersion, kMinorVersion)),
            std::string::npos)
      << text;
  for (MessageType type : {MessageType::Hello, MessageType::Error}) {
    auto frame = encode_frame(type, payload, 2, 3);
    const Frame decoded = decode_frame(frame);
    EXPECT_EQ(decoded.header.major, 2);
    EXPECT_EQ(decoded.header.minor, 3);
  }
}

TEST(ProtocolFrame, AnotherMajorVersionIsReportedBeforeItsUnknownTypesAndFlags) {
  auto frame = encode_frame(MessageType::Step, bytes_of("x"), 3, 0);
  frame[8] = std::byte{0x99};
  EXPECT_NE(frame_error(frame).find("of protocol 3.0"), std::string::npos);
  // Flags of another major belong to that version; its Hello still gets through to be answered.
  auto hello = encode_frame(MessageType::Hello, bytes_of("x"), 3, 0);
  hello[10] = std::byte{1};
  FrameHeader header;
  EXPECT_NO_THROW(header = decode_header(std::span(hello).first<kHeaderSize>()));
  EXPECT_EQ(header.major, 3);
}

TEST(ProtocolVersion, SameMajorIsCompatibleAndAgreesOnTheLowerMinor) {
  const VersionCheck newer_peer = check_peer_version(Role::Server, 1, 4, 1, 2);
  EXPECT_TRUE(newer_peer.compatible);
  EXPECT_EQ(newer_peer.agreed_minor, 2);
  EXPECT_TRUE(newer_peer.message.empty());
  EXPECT_EQ(check_peer_version(Role::Client, 1, 0, 1, 2).agreed_minor, 0);
}

TEST(ProtocolVersion, OtherMajorIsRefusedNamingBothVersions) {
  const VersionCheck at_server = check_peer_version(Role::Server, 2, 0, 1, 0);
  EXPECT_FALSE(at_server.compatible);
  EXPECT_NE(at_server.message.find("fsi-client speaks protocol 2.0, this fsi-server speaks 1.0"),
            std::string::npos)
      << at_server.message;
  EXPECT_NE(at_server.message.find("use matching releases"), std::string::npos);
  const VersionCheck at_client = check_peer_version(Role::Client, 0, 9, 1, 0);
  EXPECT_NE(at_client.message.find("fsi-server speaks protocol 0.9, this fsi-client speaks 1.0"),
            std::string::npos)
      << at_client.message;
}

TEST(ProtocolMessageType, NamesAndKnownTypes) {
  EXPECT_EQ(name(MessageType::SnapshotRequest), "SnapshotRequest");
  EXPECT_EQ(name(static_cast<MessageType>(0x1234)), "unknown type 0x1234");
  EXPECT_TRUE(is_known(MessageType::Goodbye));
  EXPECT_FALSE(is_known(static_cast<MessageType>(0x42)));
  EXPECT_TRUE(is_version_independent(MessageType::Hello));
  EXPECT_TRUE(is_version_independent(MessageType::Error));
  EXPECT_FALSE(is_version_independent(MessageType::Welcome));
}

}  // namespace
}  // namespace fsi::protocol
