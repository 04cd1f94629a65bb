#pragma once
// Declare each parameter once: name, kind, unit, range, default, one line of doc. From the
// declaration come validation (all problems at once), typed access with defaults, the
// `fsi-server --help-params` text and the reference page docs/parameters.md.

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "fsi/scene/parameter_file.hpp"

namespace fsi::scene {

enum class Kind { Number, Integer, String, Vector, Matrix };
std::string_view name(Kind kind);

struct ParameterSpec {
  std::string key;
  Kind kind = Kind::Number;
  std::string unit;  // "m", "s", "kg/m", "" for dimensionless
  std::string doc;
  std::optional<Value> default_value;  // absent: required unless `optional_without_default`
  bool optional_without_default = false;
  std::optional<double> minimum;
  bool minimum_exclusive = false;
  std::optional<double> maximum;
  std::vector<std::string> choices;   // for strings
  std::optional<std::size_t> length;  // for vectors; for matrices the row length
};

struct BlockSpec {
  std::string name;
  std::string doc;
  bool repeated = false;  // element list: the block may appear several times
  bool required = false;
  bool open = false;  // accepts any keys and blocks (user parameter blocks)
  std::vector<ParameterSpec> parameters;
  std::vector<BlockSpec> blocks;
  // Root only: unknown top-level blocks are the user's own (like Geometry), unless their name is
  // within edit distance 2 of a declared block.
  bool user_blocks_allowed = false;
};

// Helpers to write declarations compactly.
ParameterSpec number(std::string key, std::string unit, std::string doc);
ParameterSpec integer(std::string key, std::string doc);
ParameterSpec text(std::string key, std::string doc);
ParameterSpec vector(std::string key, std::size_t length, std::string unit, std::string doc);
ParameterSpec matrix(std::string key, std::size_t columns, std::string unit, std::string doc);
Value number_value(double value);
Value text_value(std::string value);
Value vector_value(std::vector<double> value);

struct Problem {
  SourceLocation location;
  std::string message;
  std::string fix;
  std::string text() const;
};

std::vector<Problem> validate(const Block& root, const BlockSpec& spec);
// Throws one fsi::Error listing every problem (does nothing for an empty list).
void throw_if_any(const std::vector<Problem>& problems, const std::string& file);

// Typed read access to a validated block; defaults come from the spec.
class View {
 public:
  View(const Block& block, const BlockSpec& spec);

  bool has(const std::string& key) const;  // given in the file (not only by default)
  double number(const std::string& key) const;
  long integer(const std::string& key) const;
  const std::string& string(const std::string& key) const;
  std::vector<double> vector(const std::string& key) const;
  std::vector<std::vector<double>> matrix(const std::string& key) const;
  SourceLocation location(const std::string& key) const;  // of the key, or of the block

  bool has_block(const std::string& name) const;
  View block(const std::string& name) const;  // a declared block; defaults if absent
  std::vector<View> blocks(const std::string& name) const;

  const Block& raw() const { return *block_; }
  const BlockSpec& spec() const { return *spec_; }

 private:
  const Value& value(const std::string& key) const;
  const ParameterSpec& parameter_spec(const std::string& key) const;
  const BlockSpec& block_spec(const std::string& name) const;
  const Block* block_;
  const BlockSpec* spec_;
  std::shared_ptr<const Block> owned_;  // an absent block, read as defaults
};

std::string render_help(const BlockSpec& root);
std::string render_markdown(const BlockSpec& root);

}  // namespace fsi::scene
