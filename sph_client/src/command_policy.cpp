#include "command_policy.hpp"

#include <string_view>

namespace fsi::client {
namespace {

std::string_view unquoted(std::string_view word) {
  while (!word.empty() && (word.front() == '"' || word.front() == '\''))
    word.remove_prefix(1);
  while (!word.empty() && (word.back() == '"' || word.back() == '\''))
    word.remove_suffix(1);
  return word;
}

bool leaves_run_directory(std::string_view word) {
  if (word.empty()) return false;
  if (word.front() == '/' || word.front() == '~' || word.front() == '\\') return true;
  // A ".." component anywhere: a/../../b, ../b, a/..
  std::size_t start = 0;
  while (start <= word.size()) {
    std::size_t end = word.find_first_of("/\\", start);
    if (end == std::string_view::npos) end = word.size();
    if (word.substr(start, end - start) == "..") return true;
    start = end + 1;
  }
  return false;
}

}  // namespace

std::optional<std::string> refused_command(std::span<const std::string> words) {
  for (const std::string& raw : words) {
    const std::string_view word = unquoted(raw);
    // `shell` as the command, or inside the command string of `run ... every ... "shell ..."`.
    if (word == "shell" || word.starts_with("shell ")) {
      return "'shell' starts programs on the client host";
    }
    if (leaves_run_directory(word)) {
      return "'" + std::string(word) +
             "' names a file outside the client's run directory (absolute path, ~ or ..)";
    }
  }
  return std::nullopt;
}

}  // namespace fsi::client
