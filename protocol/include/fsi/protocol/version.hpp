#pragma once
// Protocol version and the handshake rule (docs/protocol.md, "Versions"): peers must speak the
// same major version; a newer minor only adds optional capabilities, so both sides use the lower
// of the two minors.

#include <cstdint>
#include <string>

namespace fsi::protocol {

inline constexpr std::uint16_t kMajorVersion = 1;
inline constexpr std::uint16_t kMinorVersion = 6;

// "1.0"
std::string version_text(std::uint16_t major, std::uint16_t minor);

// Which program is speaking; used to word version messages.
enum class Role { Server, Client };

struct VersionCheck {
  bool compatible = false;
  std::uint16_t agreed_minor = 0;  // lower of the two minors; meaningful when compatible
  std::string message;             // names both versions when not compatible, else empty
};

// Decides whether a peer that wrote peer_major.peer_minor into its headers can talk to this side
// (own_role, speaking own_major.own_minor). The message reads e.g. "fsi-client speaks protocol
// 2.0, this fsi-server speaks 1.0; use matching releases of fsi-server and fsi-client".
VersionCheck check_peer_version(Role own_role, std::uint16_t peer_major, std::uint16_t peer_minor,
                                std::uint16_t own_major = kMajorVersion,
                                std::uint16_t own_minor = kMinorVersion);

}  // namespace fsi::protocol
