#pragma once
// Declare each parameter once: name, kind, unit, range, default, one line of doc. From that one
// declaration come validation (every problem at once), typed access with defaults, the
// `fsi-server --help-params` text and the reference page docs/parameters.md.
//
//   BlockSpec timeint = block_spec("Timeint", "time integration", {
//       number("step_size", "s", "fixed time step").positive(),
//       integer("stages", "Radau IIA stages").between(1, 3).with_default(3),
//       text("tableau", "scheme").one_of({"RadauIIA"}).with_default("RadauIIA")});
//   std::vector<Problem> problems = validate(root, root_spec);
//   throw_if_any(problems, file);
//   double h = View(root, root_spec).block("Timeint").number("step_size");

#include <concepts>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "fsi/scene/parameter_file.hpp"
#include "fsi/scene/problem.hpp"

namespace fsi::scene {

enum class Kind { Number, Integer, String, Vector, Matrix };
std::string_view name(Kind kind);

struct ParameterSpec {
  std::string key;
  Kind kind = Kind::Number;
  std::string unit;                    // "m", "s", "kg/m", "" for dimensionless
  std::string doc;                     // one line
  std::optional<Value> default_value;  // absent: required, unless `optional_without_default`
  bool optional_without_default = false;
  std::optional<double> minimum;      // inclusive unless `minimum_exclusive`; per component for
  bool minimum_exclusive = false;     // vectors and matrices
  std::optional<double> maximum;      // inclusive
  std::vector<std::string> choices;   // allowed strings; empty: any
  std::optional<std::size_t> length;  // vectors: components; matrices: values per row
  std::optional<std::size_t> other_length;  // matrices: rows may have this many values instead

  // Must the file give it? (no default and not optional)
  bool is_required() const { return !default_value && !optional_without_default; }

  // Chainable refinements; each returns a changed copy.
  ParameterSpec with_default(double value) const;
  // Any text; a template so that a braced list {0.0, 0.0} picks the vector overload.
  template <std::convertible_to<std::string_view> Text>
  ParameterSpec with_default(const Text& value) const {
    return with_default(text_value(std::string(std::string_view(value))));
  }
  ParameterSpec with_default(std::vector<double> value) const;
  ParameterSpec with_default(NumberMatrix value) const;
  ParameterSpec with_default(Value value) const;
  ParameterSpec optional() const;  // may be absent without a default (View::has tells)
  ParameterSpec positive() const;  // > 0
  ParameterSpec above(double exclusive_minimum) const;
  ParameterSpec at_least(double inclusive_minimum) const;
  ParameterSpec at_most(double inclusive_maximum) const;
  ParameterSpec between(double inclusive_minimum, double inclusive_maximum) const;
  ParameterSpec one_of(std::vector<std::string> allowed) const;
  ParameterSpec with_length(std::size_t components) const;
  ParameterSpec or_rows_of(std::size_t values) const;  // matrices: a second row length allowed
};

// Declarations by kind (the kind's natural unit argument where it has one).
ParameterSpec number(std::string key, std::string unit, std::string doc);
ParameterSpec integer(std::string key, std::string doc);
ParameterSpec text(std::string key, std::string doc);
ParameterSpec vector(std::string key, std::size_t length, std::string unit, std::string doc);
ParameterSpec matrix(std::string key, std::size_t columns, std::string unit, std::string doc);

struct BlockSpec {
  std::string name;  // "" for the root
  std::string doc;
  bool repeated = false;  // an element list: the block may appear any number of times
  bool required = false;
  bool open =
      false;  // also accepts keys and blocks of the user's own (declared ones still checked)
  std::vector<ParameterSpec> parameters;
  std::vector<BlockSpec> blocks;
  // Accepts blocks of the user's own (like Geometry) but not loose keys. An unknown block whose
  // name is within edit distance 2 of a declared one is still an error (a likely typo); the same
  // holds for unknown keys in an open block.
  bool user_blocks_allowed = false;
  // The scene dimension the block belongs to: 0 both, 2 planar scenes only, 3 spatial scenes
  // only. The scene builder refuses a block of the other dimension at its place.
  int dimension = 0;
  // Read by coupled runs only (the fluid's set-up): a run of the structure alone neither needs
  // nor reads it, and `required` then does not hold.
  bool coupled_only = false;

  const ParameterSpec* parameter(std::string_view key) const;  // nullptr if not declared
  const BlockSpec* block(std::string_view block_name) const;   // nullptr if not declared

  BlockSpec as_list() const;           // repeated = true
  BlockSpec as_required() const;       // required = true
  BlockSpec as_open() const;           // open = true
  BlockSpec planar() const;            // dimension = 2
  BlockSpec spatial() const;           // dimension = 3
  BlockSpec for_coupled_runs() const;  // coupled_only = true
};

BlockSpec block_spec(std::string name, std::string doc, std::vector<ParameterSpec> parameters = {},
                     std::vector<BlockSpec> blocks = {});

// Every problem of `root` against `root_spec`: unknown keys and blocks (with suggestions), wrong
// kinds, non-integers, values out of range, strings not among the choices, wrong lengths, missing
// required entries, non-repeatable blocks given twice.
std::vector<Problem> validate(const Block& root, const BlockSpec& root_spec);

// What `--set` may add to a file that lacks it: a parameter `root` declares, in blocks the file
// has or in blocks declared as not repeated (created then: an element of a list is not). `root`
// must outlive the result.
OverrideAdmission declared_parameters(const BlockSpec& root);

// Thrown by View when it is asked for a parameter marked `failed` (its problem is reported
// already): a scene builder skips the element that needs the value instead of reporting a
// consequence of the same mistake.
class AlreadyReported : public std::runtime_error {
 public:
  explicit AlreadyReported(const SourceLocation& where)
      : std::runtime_error("value at " + where.text() + " is in error (reported already)") {}
};

// Typed read access to a validated block; absent parameters read as their declared defaults,
// absent declared blocks as blocks of defaults. Asking for an undeclared key is a programming
// error (assertion), except in open blocks, where the user's own keys can be read.
class View {
 public:
  View(const Block& block, const BlockSpec& spec);

  bool has(std::string_view key) const;  // given in the file (not just by default)
  const Value& value(std::string_view key) const;
  double number(std::string_view key) const;
  long integer(std::string_view key) const;
  const std::string& string(std::string_view key) const;
  std::vector<double> vector(std::string_view key) const;
  NumberMatrix matrix(std::string_view key) const;
  // Where `key` is given, or where the block is when the key is absent.
  SourceLocation location(std::string_view key) const;
  SourceLocation location() const { return block_->location; }

  bool has_block(std::string_view name) const;
  View block(std::string_view name) const;  // the first one; defaults if absent
  std::vector<View> blocks(std::string_view name) const;

  const Block& raw() const { return *block_; }
  const BlockSpec& spec() const { return *spec_; }

 private:
  const Value& typed(std::string_view key, ValueKind kind) const;
  const BlockSpec& child_spec(std::string_view name) const;

  const Block* block_;
  const BlockSpec* spec_;
  std::shared_ptr<const Block> owned_;  // an absent block, read as defaults
};

// Plain text for `fsi-server --help-params`: path, kind, unit, default, range, doc.
std::string render_help(const BlockSpec& root);
// A reference page: one section with a table per block.
std::string render_markdown(const BlockSpec& root);

}  // namespace fsi::scene
