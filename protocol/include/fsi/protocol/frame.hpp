#pragma once
// Frames of the fsi protocol (docs/protocol.md, "Frame"). A frame is a fixed 20-byte header and a
// payload; all integers little-endian:
//   0  magic "FSIP"   4  u16 major   6  u16 minor   8  u16 message type   10  u16 flags
//   12 u32 payload length            16 u32 CRC-32C over header bytes 0..15, then the payload
// The header layout and the Hello and Error messages are frozen across major versions, so a
// version mismatch can always be reported.

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "fsi/common/error.hpp"
#include "fsi/protocol/message_list.hpp"
#include "fsi/protocol/version.hpp"

namespace fsi::protocol {

inline constexpr std::size_t kHeaderSize = 20;
inline constexpr std::array<std::byte, 4> kMagic{std::byte{'F'}, std::byte{'S'}, std::byte{'I'},
                                                 std::byte{'P'}};
inline constexpr std::size_t kDefaultMaxPayload = std::size_t{1} << 30;  // 1 GiB

// The type ids of message_list.hpp (Hello = 0x01, ..., Goodbye = 0x41). A value outside the list
// can arrive from a peer; is_known tells.
enum class MessageType : std::uint16_t {
#define FSI_PROTOCOL_ENUMERATOR(enumerator, message, id) enumerator = id,
  FSI_PROTOCOL_MESSAGES(FSI_PROTOCOL_ENUMERATOR)
#undef FSI_PROTOCOL_ENUMERATOR
};

// "Step", "Forces", ... or "unknown type 0x0077".
std::string name(MessageType type);
bool is_known(MessageType type);
// Hello and Error keep their layout in every major version.
bool is_version_independent(MessageType type);

// A fault in what a peer sent or in the connection to it. The message says what was wrong and
// where (message type, field, byte offset, peer address).
class ProtocolError : public fsi::Error {
 public:
  using fsi::Error::Error;
};

// The faults that docs/protocol.md §7 answers with an Error code of their own (error_code_for in
// messages.hpp); every other ProtocolError is answered with MalformedMessage.
class VersionMismatchError : public ProtocolError {  // a frame of another major version
 public:
  using ProtocolError::ProtocolError;
};
class UnexpectedMessageError : public ProtocolError {  // a well-formed message out of turn
 public:
  using ProtocolError::ProtocolError;
};
class PeerTimeoutError : public ProtocolError {  // a bounded wait for the peer ran out
 public:
  using ProtocolError::ProtocolError;
};

struct FrameHeader {
  std::uint16_t major = kMajorVersion;
  std::uint16_t minor = kMinorVersion;
  MessageType type = MessageType::Hello;
  std::uint16_t flags = 0;
  std::uint32_t payload_length = 0;
  std::uint32_t crc = 0;
};

struct Frame {
  FrameHeader header;
  std::vector<std::byte> payload;
};

// CRC-32C (Castagnoli, reflected, initial value and final xor 0xFFFFFFFF): crc32c("123456789") is
// 0xE3069283. Pass the previous result to continue over data that arrives in pieces.
std::uint32_t crc32c(std::span<const std::byte> data, std::uint32_t previous = 0);

// The header for a payload, CRC included. Throws ProtocolError for payloads of 4 GiB or more.
std::array<std::byte, kHeaderSize> encode_header(MessageType type,
                                                 std::span<const std::byte> payload,
                                                 std::uint16_t major = kMajorVersion,
                                                 std::uint16_t minor = kMinorVersion);
// The same for a payload that is the concatenation of pieces (sent by scatter-gather).
std::array<std::byte, kHeaderSize> encode_header_for_pieces(
    MessageType type, std::span<const std::span<const std::byte>> payload_pieces,
    std::uint16_t major = kMajorVersion, std::uint16_t minor = kMinorVersion);
// Header and payload in one buffer (tests, fuzzing, fake peers).
std::vector<std::byte> encode_frame(MessageType type, std::span<const std::byte> payload,
                                    std::uint16_t major = kMajorVersion,
                                    std::uint16_t minor = kMinorVersion);

// Parses and checks a header in this order: magic; major version (skipped for Hello and Error,
// whose layout never changes); known type; flags zero; payload length <= max_payload. Throws
// ProtocolError naming the fault. The CRC is checked by verify_crc once the payload is in.
FrameHeader decode_header(std::span<const std::byte, kHeaderSize> bytes,
                          std::size_t max_payload = kDefaultMaxPayload,
                          std::uint16_t expected_major = kMajorVersion);
// Throws ProtocolError "CRC-32C mismatch in <type> frame: computed 0x..., received 0x...".
void verify_crc(std::span<const std::byte, kHeaderSize> header_bytes, const FrameHeader& header,
                std::span<const std::byte> payload);
// The same check for a CRC the caller computed itself (e.g. piece by piece while receiving):
// computed = crc32c(payload, crc32c(first 16 header bytes)). Throws ProtocolError on mismatch.
void check_crc(const FrameHeader& header, std::uint32_t computed, std::size_t payload_size);
// Decodes and verifies one complete frame held in one buffer; extra or missing bytes are errors.
Frame decode_frame(std::span<const std::byte> bytes, std::size_t max_payload = kDefaultMaxPayload,
                   std::uint16_t expected_major = kMajorVersion);

}  // namespace fsi::protocol
