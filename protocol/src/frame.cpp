#include "fsi/protocol/frame.hpp"

#include <cstdio>
#include <cstring>
#include <limits>

namespace fsi::protocol {
namespace {

// Header fields are written byte by byte, so the header is little-endian on any host.
void store_u16(std::byte* out, std::uint16_t value) {
  out[0] = static_cast<std::byte>(value & 0xFFu);
  out[1] = static_cast<std::byte>(value >> 8);
}
void store_u32(std::byte* out, std::uint32_t value) {
  for (int k = 0; k < 4; ++k)
    out[k] = static_cast<std::byte>((value >> (8 * k)) & 0xFFu);
}
std::uint16_t load_u16(const std::byte* in) {
  return static_cast<std::uint16_t>(std::to_integer<unsigned>(in[0]) |
                                    (std::to_integer<unsigned>(in[1]) << 8));
}
std::uint32_t load_u32(const std::byte* in) {
  std::uint32_t value = 0;
  for (int k = 0; k < 4; ++k)
    value |= std::to_integer<std::uint32_t>(in[k]) << (8 * k);
  return value;
}

std::string hex32(std::uint32_t value) {
  char text[16];
  std::snprintf(text, sizeof text, "0x%08x", static_cast<unsigned>(value));
  return text;
}

std::string hex16(std::uint16_t value) {
  char text[16];
  std::snprintf(text, sizeof text, "0x%04x", static_cast<unsigned>(value));
  return text;
}

constexpr const char* kMatchingReleases = "use matching releases of fsi-server and fsi-client";

}  // namespace

std::string name(MessageType type) {
  switch (type) {
#define FSI_PROTOCOL_NAME_CASE(enumerator, message, id) \
  case MessageType::enumerator:                         \
    return #enumerator;
    FSI_PROTOCOL_MESSAGES(FSI_PROTOCOL_NAME_CASE)
#undef FSI_PROTOCOL_NAME_CASE
  }
  return "unknown type " + hex16(static_cast<std::uint16_t>(type));
}

bool is_known(MessageType type) {
  switch (type) {
#define FSI_PROTOCOL_KNOWN_CASE(enumerator, message, id) case MessageType::enumerator:
    FSI_PROTOCOL_MESSAGES(FSI_PROTOCOL_KNOWN_CASE)
#undef FSI_PROTOCOL_KNOWN_CASE
    return true;
  }
  return false;
}

bool is_version_independent(MessageType type) {
  return type == MessageType::Hello || type == MessageType::Error;
}

std::array<std::byte, kHeaderSize> encode_header(MessageType type,
                                                 std::span<const std::byte> payload,
                                                 std::uint16_t major, std::uint16_t minor) {
  return encode_header_for_pieces(type, std::span(&payload, 1), major, minor);
}

std::array<std::byte, kHeaderSize> encode_header_for_pieces(
    MessageType type, std::span<const std::span<const std::byte>> payload_pieces,
    std::uint16_t major, std::uint16_t minor) {
  std::size_t size = 0;
  for (const auto& piece : payload_pieces)
    size += piece.size();
  if (size > std::numeric_limits<std::uint32_t>::max()) {
    throw ProtocolError("cannot send a " + name(type) + " payload of " + std::to_string(size) +
                            " bytes: a frame carries less than 4 GiB",
                        "encoding a " + name(type) + " frame",
                        "send less data per message (e.g. snapshots of fewer particles)");
  }
  std::array<std::byte, kHeaderSize> header{};
  std::memcpy(header.data(), kMagic.data(), kMagic.size());
  store_u16(&header[4], major);
  store_u16(&header[6], minor);
  store_u16(&header[8], static_cast<std::uint16_t>(type));
  store_u16(&header[10], 0);
  store_u32(&header[12], static_cast<std::uint32_t>(size));
  std::uint32_t crc = crc32c(std::span(header).first(16));
  for (const auto& piece : payload_pieces)
    crc = crc32c(piece, crc);
  store_u32(&header[16], crc);
  return header;
}

std::vector<std::byte> encode_frame(MessageType type, std::span<const std::byte> payload,
                                    std::uint16_t major, std::uint16_t minor) {
  const auto header = encode_header(type, payload, major, minor);
  // Sized once and filled by memcpy: GCC 12 warns falsely (-Wstringop-overflow) on inserts here.
  std::vector<std::byte> frame(kHeaderSize + payload.size());
  std::memcpy(frame.data(), header.data(), kHeaderSize);
  if (!payload.empty()) std::memcpy(frame.data() + kHeaderSize, payload.data(), payload.size());
  return frame;
}

FrameHeader decode_header(std::span<const std::byte, kHeaderSize> bytes, std::size_t max_payload,
                          std::uint16_t expected_major) {
  if (std::memcmp(bytes.data(), kMagic.data(), kMagic.size()) != 0) {
    throw ProtocolError(
        "bad frame magic " + hex32(load_u32(bytes.data())) +
            " (expected \"FSIP\"): the peer does not speak the fsi protocol, or the byte "
            "stream lost its place",
        "frame header",
        "make sure fsi-client connects to fsi-server's port and nothing else talks to it");
  }
  FrameHeader header;
  header.major = load_u16(&bytes[4]);
  header.minor = load_u16(&bytes[6]);
  header.type = static_cast<MessageType>(load_u16(&bytes[8]));
  header.flags = load_u16(&bytes[10]);
  header.payload_length = load_u32(&bytes[12]);
  header.crc = load_u32(&bytes[16]);
  const bool same_major = header.major == expected_major;
  // A peer of another major version may use types and flags we do not know; its version is the
  // fault worth reporting, so it is checked first.
  if (!same_major && !is_version_independent(header.type)) {
    throw VersionMismatchError(
        name(header.type) + " frame of protocol " + version_text(header.major, header.minor) +
            ", but this side speaks " + version_text(expected_major, kMinorVersion),
        "frame header", kMatchingReleases);
  }
  if (!is_known(header.type)) {
    throw ProtocolError("frame of " + name(header.type) + ", which protocol " +
                            version_text(kMajorVersion, kMinorVersion) + " does not define",
                        "frame header", kMatchingReleases);
  }
  if (same_major && header.flags != 0) {
    throw ProtocolError(name(header.type) + " frame has flags " + hex16(header.flags) +
                            "; protocol " + version_text(kMajorVersion, kMinorVersion) +
                            " defines none, so they must be 0",
                        "frame header", kMatchingReleases);
  }
  if (header.payload_length > max_payload) {
    throw ProtocolError(name(header.type) + " frame announces a payload of " +
                            std::to_string(header.payload_length) + " bytes, more than the " +
                            std::to_string(max_payload) + " bytes this side accepts",
                        "frame header",
                        "if the peer is genuine, raise the payload limit (ChannelOptions::"
                        "max_payload) or send smaller messages; otherwise the peer is faulty");
  }
  return header;
}

void verify_crc(std::span<const std::byte, kHeaderSize> header_bytes, const FrameHeader& header,
                std::span<const std::byte> payload) {
  check_crc(header, crc32c(payload, crc32c(header_bytes.first(16))), payload.size());
}

void check_crc(const FrameHeader& header, std::uint32_t computed, std::size_t payload_size) {
  if (computed != header.crc) {
    throw ProtocolError(
        "CRC-32C mismatch in " + name(header.type) + " frame: computed " + hex32(computed) +
            ", received " + hex32(header.crc),
        name(header.type) + " frame with " + std::to_string(payload_size) + " payload bytes",
        "the data was damaged on the way or the peer is faulty; check the "
        "network and the peer's version");
  }
}

Frame decode_frame(std::span<const std::byte> bytes, std::size_t max_payload,
                   std::uint16_t expected_major) {
  if (bytes.size() < kHeaderSize) {
    throw ProtocolError("truncated frame: " + std::to_string(bytes.size()) +
                            " bytes, fewer than the 20 of a header",
                        "frame header", "the sender is faulty");
  }
  const auto header_bytes = bytes.first<kHeaderSize>();
  Frame frame;
  frame.header = decode_header(header_bytes, max_payload, expected_major);
  const auto payload = bytes.subspan(kHeaderSize);
  if (payload.size() != frame.header.payload_length) {
    throw ProtocolError(
        std::string(payload.size() < frame.header.payload_length ? "truncated " : "overlong ") +
            name(frame.header.type) + " frame: the header announces " +
            std::to_string(frame.header.payload_length) + " payload bytes, " +
            std::to_string(payload.size()) + " are present",
        name(frame.header.type) + " frame", "the sender is faulty");
  }
  verify_crc(header_bytes, frame.header, payload);
  frame.payload.assign(payload.begin(), payload.end());
  return frame;
}

}  // namespace fsi::protocol
