#include "fsi/scene/problem.hpp"

#include "fsi/common/error.hpp"

namespace fsi::scene {

std::string SourceLocation::text() const {
  if (line <= 0) return file;
  return file + ":" + std::to_string(line) + ":" + std::to_string(column);
}

std::string Problem::text() const {
  return location.text() + ": " + message + (fix.empty() ? "" : "; " + fix);
}

void throw_if_any(const std::vector<Problem>& problems, const std::string& where) {
  if (problems.empty()) return;
  std::string listing = std::to_string(problems.size()) + " problem(s) in the scene:";
  for (const Problem& problem : problems)
    listing += "\n  " + problem.text();
  throw Error(listing, where,
              "correct each entry as its line says (fsi-server --help-params lists every "
              "parameter)");
}

}  // namespace fsi::scene
