#pragma once
// Which LIGGGHTS commands fsi-client runs from the scripts fsi-server sends. The client executes
// text that arrives over the network, so by default it refuses what could harm the client host:
// commands that start programs (`shell`) and file names outside the run directory (absolute
// paths, `~`, or `..` components). `fsi-client --allow-unsafe-commands` lifts the policy.

#include <optional>
#include <span>
#include <string>

namespace fsi::client {

// words: one command after variable substitution. Returns why it is refused, or nothing.
std::optional<std::string> refused_command(std::span<const std::string> words);

}  // namespace fsi::client
