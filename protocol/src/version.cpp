#include "fsi/protocol/version.hpp"

#include <algorithm>

namespace fsi::protocol {

std::string version_text(std::uint16_t major, std::uint16_t minor) {
  return std::to_string(major) + "." + std::to_string(minor);
}

VersionCheck check_peer_version(Role own_role, std::uint16_t peer_major, std::uint16_t peer_minor,
                                std::uint16_t own_major, std::uint16_t own_minor) {
  VersionCheck check;
  if (peer_major == own_major) {
    check.compatible = true;
    check.agreed_minor = std::min(peer_minor, own_minor);
    return check;
  }
  const char* own = own_role == Role::Server ? "fsi-server" : "fsi-client";
  const char* peer = own_role == Role::Server ? "fsi-client" : "fsi-server";
  check.message = std::string(peer) + " speaks protocol " + version_text(peer_major, peer_minor) +
                  ", this " + own + " speaks " + version_text(own_major, own_minor) +
                  "; use matching releases of fsi-server and fsi-client (the major versions " +
                  "must be equal)";
  return check;
}

}  // namespace fsi::protocol
