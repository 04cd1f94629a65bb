#pragma once
// The parameter-file language of thesis §5.6 (HOTINT-like), docs/parameters.md:
//
//   % comment            // comment
//   Block { key = expression; other = "text" }   nested blocks, ';' or newline between entries
//   Newton.max_iterations = 40                    dotted key: assigns inside block Newton
//   y = 0.75*height - 0.5*thickness               references to EARLIER parameters
//   x = Geometry.offset_x                         dotted references into other blocks
//   v = [0, -9.81]     m = [[0, 0], [1, 0]]       vectors and matrices (may span lines)
//   include "other.scene"                         textual include, relative to this file
//   Body { ... } Body { ... }                     repeated blocks form element lists
//
// Expressions are evaluated with muParser (sin, cos, sqrt, exp, ln, min, max, ^, pi, e, ...).
// A name resolves in the innermost enclosing block first, then outwards; only parameters defined
// earlier in the text are visible. `--set KEY=EXPR` overrides replace a parameter's expression at
// its original place, so later parameters that use it see the new value.

#include <nlohmann/json.hpp>

#include <map>
#include <string>
#include <string_view>
#include <vector>

namespace fsi::scene {

struct SourceLocation {
  std::string file;  // or "--set KEY=EXPR" for overrides
  int line = 0;
  int column = 0;
  std::string text() const;  // "file:line:column"
};

enum class ValueKind { Number, String, Vector, Matrix };
std::string_view name(ValueKind kind);

struct Value {
  ValueKind kind = ValueKind::Number;
  double number = 0.0;
  std::string text;
  std::vector<double> vector;
  std::vector<std::vector<double>> matrix;
};

struct Parameter {
  std::string key;
  Value value;
  std::string expression;  // as written (or as overridden)
  SourceLocation location;
};

struct Block {
  std::string name;
  SourceLocation location;
  std::vector<Parameter> parameters;
  std::vector<Block> blocks;
  // Textual order of entries: (true, index into blocks) or (false, index into parameters).
  std::vector<std::pair<bool, std::size_t>> order;

  const Parameter* find(std::string_view key) const;
  std::vector<const Block*> children(std::string_view name) const;
  const Block* child(std::string_view name) const;  // the first one, or nullptr
  // "A.B.c" or "Body[1].mass"; nullptr if absent.
  const Parameter* lookup(std::string_view path) const;
};

struct Override {
  std::string path;
  std::string expression;
};

// Parses "KEY=EXPR"; throws fsi::Error if there is no '='.
Override parse_override(std::string_view text);

// Reads, includes, overrides and evaluates a file. Throws fsi::Error: a syntax error stops at
// once; evaluation errors are collected and reported together, one per line.
Block load_parameter_file(const std::string& path, const std::vector<Override>& overrides = {});
// The same from text (file name used for messages and includes relative to its directory).
Block parse_parameter_text(const std::string& text, const std::string& file_name,
                           const std::vector<Override>& overrides = {});

// The evaluated tree in the same syntax, numbers with 17 significant digits.
std::string to_text(const Block& root);
// {"entries": [{"kind": "parameter", "key", "value"}, {"kind": "block", "name", "entries"}]}
nlohmann::json to_json(const Block& root);
// Every parameter by dotted path (repeated blocks as Name[i]); numbers only.
std::map<std::string, double> flatten_numbers(const Block& root);

std::size_t edit_distance(std::string_view a, std::string_view b);
// The candidate closest to `word` within distance max(2, |word|/3), or "".
std::string nearest(std::string_view word, const std::vector<std::string>& candidates);

}  // namespace fsi::scene
