#pragma once
// The parameter-file language of thesis §5.6 (HOTINT-like); the reference is docs/parameters.md.
//
//   % comment            // comment
//   Block { key = expression; other = "text" }   nested blocks; ';' or a new line between entries
//   Newton.max_iterations = 40                    dotted key: assigns inside block Newton
//   y = 0.75*height - 0.5*thickness               references to EARLIER parameters
//   x = Geometry.offset_x + Body[1].mass          dotted (and indexed) references
//   v = [0, -9.81]     m = [[0, 0], [1, 0]]       vectors and matrices (may span lines)
//   scene_language = 1                            first entry: the language version
//   include "other.scene"                         textual include, relative to this file
//   Body { ... } Body { ... }                     repeated blocks form element lists
//
// Expressions are evaluated with muParser (sin, cos, sqrt, exp, ln, log10, abs, min, max, ^, pi,
// e, ...). A name resolves in the innermost enclosing block first, then outwards, and only to
// parameters defined earlier in the text, so there are no cycles. `--set KEY=EXPR` overrides
// replace a parameter's expression at its original place: later parameters that use it follow.
// An override of a parameter the file lacks (where an OverrideAdmission allows it) is added after
// everything the file holds.

#include <nlohmann/json.hpp>

#include <cstddef>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "fsi/scene/problem.hpp"

namespace fsi::scene {

// The version of the language this program reads. A file states the version it is written for
// with `scene_language = N` as its first entry (comments may stand above); the parser reads it
// before the rest and refuses N > kSceneLanguageVersion at once. Included files may state it too
// (checked the same way). Whether a file must state it is the caller's decision (scenes must).
inline constexpr long kSceneLanguageVersion = 1;

enum class ValueKind { Number, String, Vector, Matrix };
std::string_view name(ValueKind kind);

using NumberMatrix = std::vector<std::vector<double>>;  // rows; the schema says how long

// An evaluated value; only the member named by `kind` is meaningful.
struct Value {
  ValueKind kind = ValueKind::Number;
  double number = 0.0;
  std::string text;
  std::vector<double> vector;
  NumberMatrix matrix;

  friend bool operator==(const Value&, const Value&) = default;
};

Value number_value(double value);
Value text_value(std::string value);
Value vector_value(std::vector<double> value);
Value matrix_value(NumberMatrix value);

// The value in the language's own syntax; numbers in the shortest form that reads back exactly.
std::string format_value(const Value& value);

struct Parameter {
  std::string key;
  Value value;
  std::string expression;   // as written (comments dropped, line breaks joined), or as overridden
  SourceLocation location;  // of the key; "--set KEY=EXPR" when overridden
  // The value could not be computed (its problem is reported); `value` is meaningless. Only
  // trees loaded with a `problems` list hold such parameters.
  bool failed = false;
};

struct Block;

// One entry of a block in textual order: an index into Block::parameters or Block::blocks.
struct BlockEntry {
  enum class Type { Parameter, Block };
  Type type = Type::Parameter;
  std::size_t index = 0;
};

struct Block {
  std::string name;  // "" for the root (the file itself)
  SourceLocation location;
  std::vector<Parameter> parameters;
  std::vector<Block> blocks;
  std::vector<BlockEntry> entries;  // parameters and blocks interleaved as in the text
  // Root only: the `scene_language = N` of the top file, if it states one, and where.
  std::optional<long> language_version;
  SourceLocation language_version_location;

  // The parameter `key` of this block (the last assignment if it is assigned twice), or nullptr.
  const Parameter* find(std::string_view key) const;
  // The child blocks named `name`, in textual order (several form an element list).
  std::vector<const Block*> children(std::string_view name) const;
  // The first child block named `name`, or nullptr.
  const Block* child(std::string_view name) const;
  // A parameter by path: "A.B.c", "Body[1].mass" (0-based; an index-less name means [0]).
  const Parameter* lookup(std::string_view path) const;
  // A block by path: "A.B", "Body[1]".
  const Block* lookup_block(std::string_view path) const;

  // Append an entry, keeping `entries` in step (for building trees in code).
  Parameter& add_parameter(Parameter parameter);
  Block& add_block(Block block);
};

// A command-line override `--set KEY=EXPR`.
struct Override {
  std::string path;        // "Geometry.width", "Body[1].mass"
  std::string expression;  // any expression the file could hold at that place
};

// Splits "KEY=EXPR"; throws fsi::Error if it is not of that form.
Override parse_override(std::string_view text);

// Whether `--set` may add a parameter the file lacks: asked with the names of the blocks on the
// override's path (indices dropped), its key, and how many of those blocks, the last ones, the
// file lacks (they are created). Returns "" to admit it, else why not (shown as the fix). The
// scene's schema admits what it declares (schema.hpp, declared_parameters). Without one, `--set`
// only replaces parameters the file defines.
using OverrideAdmission = std::function<std::string(
    const std::vector<std::string>& blocks, const std::string& key, std::size_t missing_blocks)>;

// Where `include "file"` reads from: given the path (the name joined to the including file's
// folder, normalized), the file's text, or nullopt if there is no readable regular file there.
// Empty (the default): the file system. The fuzzer gives files held in memory (in_memory_files),
// so that no input can make it read anything else.
using IncludeReader = std::function<std::optional<std::string>(const std::string& path)>;
// A reader serving exactly `files` (normalized path -> text) and nothing else.
IncludeReader in_memory_files(std::map<std::string, std::string> files);

// Reads `path` with its includes, applies the overrides and evaluates every expression. Throws
// fsi::Error: a syntax error stops at once; evaluation errors (undefined names, bad arithmetic,
// references to later parameters) are collected and reported together, one per line. A path that
// is not a regular file (a folder, a device, a pipe) is refused, never read.
Block load_parameter_file(const std::string& path, const std::vector<Override>& overrides = {});
// The same for text in memory; `file_name` appears in messages and anchors relative includes.
Block parse_parameter_text(const std::string& text, const std::string& file_name,
                           const std::vector<Override>& overrides = {},
                           const IncludeReader& read_include = {});
// The same, but evaluation problems are appended to `problems` instead of thrown, and the
// parameters they concern are kept with `failed` set, so that later checks (schema, scene) can
// report their own problems in the same run (`fsi-server --check` lists everything at once).
// Syntax errors, include errors and bad overrides still throw: nothing after them is reliable.
// `may_add` lets overrides add parameters the file lacks.
Block load_parameter_file(const std::string& path, const std::vector<Override>& overrides,
                          std::vector<Problem>& problems, const OverrideAdmission& may_add = {});
Block parse_parameter_text(const std::string& text, const std::string& file_name,
                           const std::vector<Override>& overrides, std::vector<Problem>& problems,
                           const OverrideAdmission& may_add = {});

// The evaluated tree in the language's syntax (for `fsi-server --print-params`); parsing it again
// gives the same values. Each entry whose expression differs from its value carries the
// expression as a comment.
std::string to_text(const Block& root);
// Blocks as objects, parameters as numbers/strings/arrays, repeated blocks as arrays of objects
// (for the run manifest).
nlohmann::json to_json(const Block& root);
// Every number parameter by dotted path (repeated blocks as Name[i]).
std::map<std::string, double> flatten_numbers(const Block& root);

// Case-insensitive Levenshtein distance, for "did you mean ...?".
std::size_t edit_distance(std::string_view a, std::string_view b);
// The candidate closest to `word` within distance max(2, |word|/3), or "".
std::string nearest(std::string_view word, const std::vector<std::string>& candidates);

}  // namespace fsi::scene
