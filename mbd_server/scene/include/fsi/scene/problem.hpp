#pragma once
// One mistake in a scene file, with where it is and what to do about it. Evaluation and schema
// validation both collect every Problem first and then throw one fsi::Error listing them all.

#include <string>
#include <vector>

namespace fsi::scene {

struct SourceLocation {
  std::string file;  // for a command-line override: "--set KEY=EXPR"
  int line = 0;      // 0: no position inside `file` (overrides, whole files)
  int column = 0;
  std::string text() const;  // "file:line:column", or just `file` without a line

  friend bool operator==(const SourceLocation&, const SourceLocation&) = default;
};

struct Problem {
  SourceLocation location;
  std::string message;       // what is wrong
  std::string fix;           // how to fix it
  std::string text() const;  // "file:line:column: message (fix)"
};

// Throws one fsi::Error whose message lists every problem on its own line; `where` names the file
// (or command) they belong to. Does nothing for an empty list.
void throw_if_any(const std::vector<Problem>& problems, const std::string& where);

}  // namespace fsi::scene
