#include <cstdio>
#include <cstring>

#include "fsi/protocol/frame.hpp"

namespace fsi::protocol {
namespace {

void put16(std::byte* out, std::uint16_t value) {
  out[0] = std::byte(value & 0xFF);
  out[1] = std::byte(value >> 8);
}
void put32(std::byte* out, std::uint32_t value) {
  for (int k = 0; k < 4; ++k)
    out[k] = std::byte((value >> (8 * k)) & 0xFF);
}
std::uint16_t get16(const std::byte* in) {
  return static_cast<std::uint16_t>(std::to_integer<unsigned>(in[0]) |
                                    (std::to_integer<unsigned>(in[1]) << 8));
}
std::uint32_t get32(const std::byte* in) {
  std::uint32_t value = 0;
  for (int k = 0; k < 4; ++k)
    value |= std::to_integer<std::uint32_t>(in[k]) << (8 * k);
  return value;
}
std::string hex(std::uint32_t value) {
  char text[16];
  std::snprintf(text, sizeof text, "0x%08x", value);
  return text;
}

}  // namespace

std::string name(MessageType type) {
  switch (type) {
    case MessageType::Hello:
      return "Hello";
    case MessageType::Welcome:
      return "Welcome";
    case MessageType::Error:
      return "Error";
    case MessageType::Setup:
      return "Setup";
    case MessageType::Mesh:
      return "Mesh";
    case MessageType::Particles:
      return "Particles";
    case MessageType::Ready:
      return "Ready";
    case MessageType::Step:
      return "Step";
    case MessageType::Forces:
      return "Forces";
    case MessageType::SnapshotRequest:
      return "SnapshotRequest";
    case MessageType::Snapshot:
      return "Snapshot";
    case MessageType::Shutdown:
      return "Shutdown";
    case MessageType::Goodbye:
      return "Goodbye";
  }
  char text[32];
  std::snprintf(text, sizeof text, "unknown type 0x%04x", static_cast<unsigned>(type));
  return text;
}

bool is_known(MessageType type) {
  return name(type).rfind("unknown", 0) != 0;
}

bool is_version_independent(MessageType type) {
  return type == MessageType::Hello || type == MessageType::Error;
}

std::string version_text(std::uint16_t major, std::uint16_t minor) {
  return "protocol " + std::to_string(major) + "." + std::to_string(minor);
}

std::array<std::byte, kHeaderSize> encode_header(MessageType type,
                                                 std::span<const std::byte> payload,
                                                 std::uint16_t major, std::uint16_t minor) {
  if (payload.size() > 0xFFFFFFFFu) {
    throw ProtocolError(name(type) + " payload of " + std::to_string(payload.size()) +
                            " bytes exceeds the 4 GiB frame limit",
                        "sending", "request smaller snapshots");
  }
  std::array<std::byte, kHeaderSize> header{};
  std::memcpy(header.data(), kMagic.data(), 4);
  put16(&header[4], major);
  put16(&header[6], minor);
  put16(&header[8], static_cast<std::uint16_t>(type));
  put16(&header[10], 0);
  put32(&header[12], static_cast<std::uint32_t>(payload.size()));
  const std::uint32_t crc = crc32c(payload, crc32c(std::span(header).first(16)));
  put32(&header[16], crc);
  return header;
}

std::vector<std::byte> encode_frame(MessageType type, std::span<const std::byte> payload,
                                    std::uint16_t major, std::uint16_t minor) {
  const auto header = encode_header(type, payload, major, minor);
  std::vector<std::byte> frame(kHeaderSize + payload.size());
  std::memcpy(frame.data(), header.data(), kHeaderSize);
  if (!payload.empty()) std::memcpy(frame.data() + kHeaderSize, payload.data(), payload.size());
  return frame;
}

FrameHeader decode_header(std::span<const std::byte, kHeaderSize> bytes, std::size_t max_payload,
                          std::uint16_t expected_major) {
  if (std::memcmp(bytes.data(), kMagic.data(), 4) != 0) {
    throw ProtocolError(
        "bad frame magic (expected \"FSIP\"): the peer does not speak the fsi "
        "protocol or the stream is out of step",
        "frame header", "connect fsi-client to fsi-server's port");
  }
  FrameHeader header;
  header.major = get16(&bytes[4]);
  header.minor = get16(&bytes[6]);
  header.type = static_cast<MessageType>(get16(&bytes[8]));
  header.flags = get16(&bytes[10]);
  header.payload_length = get32(&bytes[12]);
  header.crc = get32(&bytes[16]);
  if (!is_known(header.type)) {
    throw ProtocolError(
        name(header.type) + " (not in " + version_text(kMajorVersion, kMinorVersion) + ")",
        "frame header", "use matching fsi-server and fsi-client releases");
  }
  if (header.major != expected_major && !is_version_independent(header.type)) {
    throw ProtocolError(name(header.type) + " frame of " +
                            version_text(header.major, header.minor) + ", this side speaks " +
                            version_text(expected_major, kMinorVersion),
                        "frame header", "use matching fsi-server and fsi-client releases");
  }
  if (header.flags != 0) {
    throw ProtocolError(name(header.type) + " frame has flags " + hex(header.flags) +
                            "; no flags are defined in " +
                            version_text(kMajorVersion, kMinorVersion),
                        "frame header", "use matching fsi-server and fsi-client releases");
  }
  if (header.payload_length > max_payload) {
    throw ProtocolError(
        name(header.type) + " frame announces " + std::to_string(header.payload_length) +
            " payload bytes, more than the " + std::to_string(max_payload) + " allowed",
        "frame header", "the peer is faulty, or raise the payload limit");
  }
  return header;
}

void verify_crc(std::span<const std::byte, kHeaderSize> header_bytes, const FrameHeader& header,
                std::span<const std::byte> payload) {
  const std::uint32_t computed = crc32c(payload, crc32c(header_bytes.first(16)));
  if (computed != header.crc) {
    throw ProtocolError("CRC-32C mismatch in " + name(header.type) + " frame: computed " +
                            hex(computed) + ", received " + hex(header.crc),
                        "frame of " + std::to_string(payload.size()) + " payload bytes",
                        "the data was corrupted in transit; check the network");
  }
}

Frame decode_frame(std::span<const std::byte> bytes, std::size_t max_payload) {
  if (bytes.size() < kHeaderSize) {
    throw ProtocolError(
        "truncated frame: " + std::to_string(bytes.size()) + " bytes, a header alone has 20",
        "frame header", "the peer is faulty");
  }
  const auto header_bytes = bytes.first<kHeaderSize>();
  Frame frame;
  frame.header = decode_header(header_bytes, max_payload);
  const std::size_t available = bytes.size() - kHeaderSize;
  if (available != frame.header.payload_length) {
    throw ProtocolError((available < frame.header.payload_length ? "truncated " : "overlong ") +
                            name(frame.header.type) + " frame: header announces " +
                            std::to_string(frame.header.payload_length) + " payload bytes, " +
                            std::to_string(available) + " present",
                        "frame", "the peer is faulty");
  }
  const auto payload = bytes.subspan(kHeaderSize);
  verify_crc(header_bytes, frame.header, payload);
  frame.payload.assign(payload.begin(), payload.end());
  return frame;
}

}  // namespace fsi::protocol
