#pragma once
// The parsed but not yet evaluated tree, shared by the parser, the override step and the
// evaluator. Nodes are heap-allocated so that parent pointers stay valid while the tree grows.

#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "fsi/scene/parameter_file.hpp"

namespace fsi::scene::detail {

struct RawBlock;

struct RawParameter {
  std::string key;
  SourceLocation location;  // of the key in the file (kept when overridden: it fixes the order)
  // The expression's source text with comments blanked out; same length as in the file, line
  // breaks kept, so an offset into it maps back to a line and column.
  std::string expression;
  SourceLocation expression_location;  // of its first character
  int sequence = 0;                    // textual order over all files
  RawBlock* block = nullptr;           // the block it is assigned in
  std::string override_label;          // "--set KEY=EXPR" once overridden, else ""

  enum class State { Pending, Done, Failed };
  State state = State::Pending;
  Value value;

  // Where the character at `offset` of `expression` is.
  SourceLocation location_at(std::size_t offset) const;
};

struct RawEntry {
  bool is_block = false;
  std::size_t index = 0;
};

struct RawBlock {
  std::string name;
  SourceLocation location;
  RawBlock* parent = nullptr;
  bool implicit = false;  // created by a dotted key; a later `Name { ... }` continues it
  // Root only: `scene_language = N` of the top file, and where it is.
  std::optional<long> language_version;
  SourceLocation language_version_location;
  std::vector<std::unique_ptr<RawParameter>> parameters;
  std::vector<std::unique_ptr<RawBlock>> blocks;
  std::vector<RawEntry> entries;

  std::vector<RawBlock*> children(std::string_view child_name) const;
  RawBlock& add_block(std::string child_name, SourceLocation where);
  RawParameter& add_parameter(std::unique_ptr<RawParameter> parameter);
};

// A path component "Name" or "Name[3]".
struct PathPart {
  std::string name;
  int index = -1;  // -1: no index given
};

// Splits "A.B[2].c"; false if it is not a valid path.
bool parse_path(std::string_view path, std::vector<PathPart>& parts);
std::string to_string(const std::vector<PathPart>& parts, std::size_t count);

// Every parameter below `block` as a path (Name[i] for blocks that repeat), for suggestions.
void collect_paths(const RawBlock& block, const std::string& prefix,
                   std::vector<std::string>& paths);

// Parses `text` (read from `file_name`) into `root`, following includes through `read_include`
// (the file system if empty). Throws fsi::Error at the first syntax error.
void parse_into(RawBlock& root, const std::string& text, const std::string& file_name,
                const IncludeReader& read_include);

// The text of the regular file at `path`, or nullopt (missing, unreadable, a folder, a device or
// a pipe: nothing that could block or never end is opened).
std::optional<std::string> read_regular_file(const std::string& path);

// Replaces the expressions the overrides name, and adds the parameters the file lacks where
// `may_add` admits them. Throws fsi::Error for a key that is neither.
void apply_overrides(RawBlock& root, const std::vector<Override>& overrides,
                     const OverrideAdmission& may_add = {});

// Evaluates every parameter in textual order; returns every problem found.
std::vector<Problem> evaluate(RawBlock& root);

// The evaluated public tree.
Block to_block(const RawBlock& raw);

bool is_identifier_start(char c);
bool is_identifier_char(char c);

}  // namespace fsi::scene::detail
