// Declarations, validation against them, and typed access with defaults.

#include "fsi/scene/schema.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>

#include "first_named.hpp"
#include "fsi/common/error.hpp"
#include "schema_text.hpp"

namespace fsi::scene {
namespace {

std::string in_quotes(std::string_view text) {
  return "'" + std::string(text) + "'";
}

bool kind_matches(Kind kind, const Value& value) {
  switch (kind) {
    case Kind::Number:
    case Kind::Integer:
      return value.kind == ValueKind::Number;
    case Kind::String:
      return value.kind == ValueKind::String;
    case Kind::Vector:
      return value.kind == ValueKind::Vector;
    case Kind::Matrix:
      // `[]` reads as an empty vector; as a matrix it has no rows.
      return value.kind == ValueKind::Matrix ||
             (value.kind == ValueKind::Vector && value.vector.empty());
  }
  return false;
}

std::string how_to_write(const ParameterSpec& spec) {
  switch (spec.kind) {
    case Kind::Number:
      return "write a number or an expression, e.g. " + spec.key + " = 0.5";
    case Kind::Integer:
      return "write a whole number, e.g. " + spec.key + " = 2";
    case Kind::String:
      return "write the text in double quotes, e.g. " + spec.key + " = \"...\"";
    case Kind::Vector:
      if (!spec.length) {  // one component per dimension of the scene
        return "write a bracketed list, e.g. " + spec.key + " = [x, y] (3D: [x, y, z])";
      }
      return "write a bracketed list, e.g. " + spec.key + " = [" +
             (spec.length == 2 ? "x, y" : "a, b, c") + "]";
    case Kind::Matrix:
      return "write one bracketed row per line, e.g. " + spec.key + " = [[x, y], [x, y]]" +
             (spec.other_length ? "; a row may also hold " + std::to_string(*spec.other_length) +
                                      " values (fsi-server --help-params says what they are)"
                                : "");
  }
  return "";
}

class Validator {
 public:
  explicit Validator(std::vector<Problem>& problems) : problems_(problems) {}

  // Problems come in textual order within a block, then what the block lacks. A second copy of a
  // block that may not repeat is one mistake, reported where it starts: what it lacks is not
  // reported again (merged into the first copy it may lack nothing), only its own wrong values.
  void block(const Block& block, const BlockSpec& spec, const std::string& path,
             bool report_missing = true) {
    std::vector<std::string> known;
    for (const ParameterSpec& parameter : spec.parameters)
      known.push_back(parameter.key);
    for (const BlockSpec& child : spec.blocks)
      known.push_back(child.name);
    const std::string where = spec.name.empty() ? "the top level" : "block " + in_quotes(spec.name);

    std::map<std::string, std::size_t> count;
    for (const Block& child : block.blocks)
      ++count[child.name];
    std::map<std::string, const Block*> first;
    std::map<std::string, std::size_t> seen;
    for (const BlockEntry& entry : block.entries) {
      if (entry.type == BlockEntry::Type::Parameter) {
        parameter(block, block.parameters[entry.index], spec, path, known, where);
        continue;
      }
      const Block& child = block.blocks[entry.index];
      const BlockSpec* declared = spec.block(child.name);
      if (!declared) {
        unknown_block(child, spec, path, known);
        continue;
      }
      const std::size_t index = seen[child.name]++;
      if (index == 0) first[child.name] = &child;
      const bool copy = !declared->repeated && index > 0;
      if (copy && index == 1) {
        add(child.location,
            "block " + in_quotes(path + child.name) + " is given twice (first at " +
                first[child.name]->location.text() + ")",
            "merge the two blocks; only element lists may repeat");
      }
      const std::string child_path =
          path + child.name + (count[child.name] > 1 ? "[" + std::to_string(index) + "]" : "") +
          ".";
      this->block(child, *declared, child_path, report_missing && !copy);
    }
    if (!report_missing) return;

    for (const ParameterSpec& declared : spec.parameters) {
      if (declared.is_required() && !block.find(declared.key)) {
        add(block.location,
            "required parameter " + in_quotes(path + declared.key) + " is missing (" +
                declared.doc + ")",
            "add " + declared.key + " = ..." +
                (declared.unit.empty() ? "" : " (in " + declared.unit + ")") + " to " + where);
      }
    }
    for (const BlockSpec& declared : spec.blocks) {
      if (declared.required && count[declared.name] == 0) {
        add(block.location,
            "required block " + in_quotes(path + declared.name) + " is missing (" + declared.doc +
                ")",
            "add " + declared.name + " { ... } to " + where +
                (declared.coupled_only
                     ? ", or run the structure alone with fsi-server --mbd-only (fsi-run always "
                       "couples), which needs no " +
                           declared.name + " block"
                     : ""));
      }
    }
  }

 private:
  void add(const SourceLocation& where, std::string message, std::string fix) {
    problems_.push_back({where, std::move(message), std::move(fix)});
  }

  void parameter(const Block& block, const Parameter& parameter, const BlockSpec& spec,
                 const std::string& path, const std::vector<std::string>& known,
                 const std::string& where) {
    const std::string full = path + parameter.key;
    if (const ParameterSpec* declared = spec.parameter(parameter.key)) {
      // Only the last assignment counts, as in every look-up.
      if (block.find(parameter.key) == &parameter) value(parameter, *declared, full);
      return;
    }
    if (spec.block(parameter.key)) {
      add(parameter.location, in_quotes(full) + " is a block, not a parameter",
          "write " + parameter.key + " { ... }");
      return;
    }
    const std::string suggestion = nearest(parameter.key, known);
    const bool typo = !suggestion.empty() && edit_distance(suggestion, parameter.key) <= 2;
    if (spec.open && !typo) return;  // the user's own key
    std::string fix;
    if (!suggestion.empty()) {
      fix = "did you mean " + in_quotes(suggestion) + "?";
      if (spec.open) fix += " If this is a key of your own, rename it";
    } else if (spec.user_blocks_allowed) {
      fix = "put parameters of your own into a block of your own, e.g. Geometry { " +
            parameter.key + " = ... }";
    } else {
      fix = "remove it; fsi-server --help-params lists the parameters of " + where;
    }
    add(parameter.location, "unknown parameter " + in_quotes(full), fix);
  }

  void unknown_block(const Block& child, const BlockSpec& spec, const std::string& path,
                     const std::vector<std::string>& known) {
    if (spec.parameter(child.name)) {
      add(child.location, in_quotes(path + child.name) + " is a parameter, not a block",
          "write " + child.name + " = ...");
      return;
    }
    const std::string suggestion = nearest(child.name, known);
    const bool typo = !suggestion.empty() && edit_distance(suggestion, child.name) <= 2;
    const bool own_blocks = spec.open || spec.user_blocks_allowed;
    if (own_blocks && !typo) return;  // the user's own block, like Geometry
    std::string fix;
    if (!suggestion.empty()) {
      fix = "did you mean " + in_quotes(suggestion) + "?";
      if (own_blocks) fix += " If this is your own parameter block, rename it";
    } else {
      fix = "remove it; fsi-server --help-params lists the blocks";
    }
    add(child.location, "unknown block " + in_quotes(path + child.name), fix);
  }

  void range(const ParameterSpec& spec, double x, const std::string& what,
             const SourceLocation& where) {
    const bool below =
        spec.minimum && (spec.minimum_exclusive ? x <= *spec.minimum : x < *spec.minimum);
    const bool above = spec.maximum && x > *spec.maximum;
    if (!below && !above) return;
    const std::string unit = spec.unit.empty() ? "" : " " + spec.unit;
    add(where,
        in_quotes(what) + " = " + format_value(number_value(x)) + unit + " is out of range (" +
            detail::range_text(spec, true) + ")",
        "choose a value " + detail::range_text(spec, true));
  }

  void value(const Parameter& parameter, const ParameterSpec& spec, const std::string& full) {
    if (parameter.failed) return;  // its evaluation problem is reported already
    const Value& value = parameter.value;
    const SourceLocation& where = parameter.location;
    if (!kind_matches(spec.kind, value)) {
      add(where,
          in_quotes(full) + " must be a" + (spec.kind == Kind::Integer ? "n " : " ") +
              std::string(name(spec.kind)) + ", not a " + std::string(name(value.kind)) + " (" +
              format_value(value) + ")",
          how_to_write(spec));
      return;
    }
    switch (spec.kind) {
      case Kind::Integer:
        if (value.number != std::floor(value.number) || std::fabs(value.number) > 9.0e15) {
          add(where, in_quotes(full) + " must be a whole number, not " + format_value(value),
              how_to_write(spec));
          return;
        }
        [[fallthrough]];
      case Kind::Number:
        range(spec, value.number, full, where);
        return;
      case Kind::String:
        if (!spec.choices.empty() &&
            std::find(spec.choices.begin(), spec.choices.end(), value.text) == spec.choices.end()) {
          const std::string suggestion = nearest(value.text, spec.choices);
          add(where,
              in_quotes(full) + " = \"" + value.text + "\" is not one of " +
                  detail::choices_text(spec.choices),
              suggestion.empty() ? "use one of the listed values"
                                 : "did you mean \"" + suggestion + "\"?");
        }
        return;
      case Kind::Vector:
        if (spec.length && value.vector.size() != *spec.length) {
          add(where,
              in_quotes(full) + " has " + std::to_string(value.vector.size()) +
                  " components, it needs " + std::to_string(*spec.length),
              how_to_write(spec));
          return;
        }
        for (std::size_t i = 0; i < value.vector.size(); ++i)
          range(spec, value.vector[i], full + "[" + std::to_string(i) + "]", where);
        return;
      case Kind::Matrix:
        for (std::size_t r = 0; r < value.matrix.size(); ++r) {
          const std::size_t values = value.matrix[r].size();
          if (spec.length && values != *spec.length && values != spec.other_length) {
            add(where,
                in_quotes(full) + " row " + std::to_string(r + 1) + " has " +
                    std::to_string(values) + (values == 1 ? " value" : " values") + ", it needs " +
                    detail::row_length_text(spec),
                how_to_write(spec));
            return;
          }
          for (std::size_t c = 0; c < value.matrix[r].size(); ++c) {
            range(spec, value.matrix[r][c],
                  full + "[" + std::to_string(r) + "][" + std::to_string(c) + "]", where);
          }
        }
        return;
    }
  }

  std::vector<Problem>& problems_;
};

// What an undeclared block of an open block is read with.
const BlockSpec& anything() {
  static const BlockSpec spec = [] {
    BlockSpec open;
    open.open = true;
    return open;
  }();
  return spec;
}

}  // namespace

std::string_view name(Kind kind) {
  // Indexed by the enumerators, which are declared in this order.
  constexpr std::array<std::string_view, 5> kNames{"number", "integer", "string", "vector",
                                                   "matrix"};
  const auto index = static_cast<std::size_t>(kind);
  return index < kNames.size() ? kNames[index] : "?";
}

// ---- declarations ----

ParameterSpec ParameterSpec::with_default(double value) const {
  return with_default(number_value(value));
}
ParameterSpec ParameterSpec::with_default(std::vector<double> value) const {
  return with_default(vector_value(std::move(value)));
}
ParameterSpec ParameterSpec::with_default(NumberMatrix value) const {
  return with_default(matrix_value(std::move(value)));
}
ParameterSpec ParameterSpec::with_default(Value value) const {
  ParameterSpec copy = *this;
  copy.default_value = std::move(value);
  return copy;
}
ParameterSpec ParameterSpec::optional() const {
  ParameterSpec copy = *this;
  copy.optional_without_default = true;
  return copy;
}
ParameterSpec ParameterSpec::positive() const {
  return above(0.0);
}
ParameterSpec ParameterSpec::above(double exclusive_minimum) const {
  ParameterSpec copy = *this;
  copy.minimum = exclusive_minimum;
  copy.minimum_exclusive = true;
  return copy;
}
ParameterSpec ParameterSpec::at_least(double inclusive_minimum) const {
  ParameterSpec copy = *this;
  copy.minimum = inclusive_minimum;
  copy.minimum_exclusive = false;
  return copy;
}
ParameterSpec ParameterSpec::at_most(double inclusive_maximum) const {
  ParameterSpec copy = *this;
  copy.maximum = inclusive_maximum;
  return copy;
}
ParameterSpec ParameterSpec::between(double inclusive_minimum, double inclusive_maximum) const {
  return at_least(inclusive_minimum).at_most(inclusive_maximum);
}
ParameterSpec ParameterSpec::one_of(std::vector<std::string> allowed) const {
  ParameterSpec copy = *this;
  copy.choices = std::move(allowed);
  return copy;
}
ParameterSpec ParameterSpec::with_length(std::size_t components) const {
  ParameterSpec copy = *this;
  copy.length = components;
  return copy;
}
ParameterSpec ParameterSpec::or_rows_of(std::size_t values) const {
  ParameterSpec copy = *this;
  copy.other_length = values;
  return copy;
}

ParameterSpec number(std::string key, std::string unit, std::string doc) {
  ParameterSpec spec;
  spec.key = std::move(key);
  spec.kind = Kind::Number;
  spec.unit = std::move(unit);
  spec.doc = std::move(doc);
  return spec;
}

ParameterSpec integer(std::string key, std::string doc) {
  ParameterSpec spec = number(std::move(key), "", std::move(doc));
  spec.kind = Kind::Integer;
  return spec;
}

ParameterSpec text(std::string key, std::string doc) {
  ParameterSpec spec = number(std::move(key), "", std::move(doc));
  spec.kind = Kind::String;
  return spec;
}

ParameterSpec vector(std::string key, std::size_t length, std::string unit, std::string doc) {
  ParameterSpec spec = number(std::move(key), std::move(unit), std::move(doc));
  spec.kind = Kind::Vector;
  spec.length = length;
  return spec;
}

ParameterSpec matrix(std::string key, std::size_t columns, std::string unit, std::string doc) {
  ParameterSpec spec = number(std::move(key), std::move(unit), std::move(doc));
  spec.kind = Kind::Matrix;
  spec.length = columns;
  return spec;
}

const ParameterSpec* BlockSpec::parameter(std::string_view key) const {
  return detail::first_named(parameters, key, &ParameterSpec::key);
}

const BlockSpec* BlockSpec::block(std::string_view block_name) const {
  return detail::first_named(blocks, block_name, &BlockSpec::name);
}

namespace {

// A copy of `spec` with one field changed: what every BlockSpec modifier returns.
template <class Field>
BlockSpec changed(const BlockSpec& spec, Field BlockSpec::*field, Field value) {
  BlockSpec copy = spec;
  copy.*field = value;
  return copy;
}

}  // namespace

BlockSpec BlockSpec::as_list() const {
  return changed(*this, &BlockSpec::repeated, true);
}
BlockSpec BlockSpec::as_required() const {
  return changed(*this, &BlockSpec::required, true);
}
BlockSpec BlockSpec::as_open() const {
  return changed(*this, &BlockSpec::open, true);
}
BlockSpec BlockSpec::planar() const {
  return changed(*this, &BlockSpec::dimension, 2);
}
BlockSpec BlockSpec::spatial() const {
  return changed(*this, &BlockSpec::dimension, 3);
}
BlockSpec BlockSpec::for_coupled_runs() const {
  return changed(*this, &BlockSpec::coupled_only, true);
}

BlockSpec block_spec(std::string name, std::string doc, std::vector<ParameterSpec> parameters,
                     std::vector<BlockSpec> blocks) {
  BlockSpec spec;
  spec.name = std::move(name);
  spec.doc = std::move(doc);
  spec.parameters = std::move(parameters);
  spec.blocks = std::move(blocks);
  return spec;
}

// ---- validation ----

std::vector<Problem> validate(const Block& root, const BlockSpec& root_spec) {
  std::vector<Problem> problems;
  Validator(problems).block(root, root_spec, "");
  return problems;
}

OverrideAdmission declared_parameters(const BlockSpec& root) {
  return [&root](const std::vector<std::string>& blocks, const std::string& key,
                 std::size_t missing_blocks) -> std::string {
    const std::string declared_only =
        "--set adds only parameters the scene schema declares (fsi-server --help-params)";
    const BlockSpec* spec = &root;
    std::string path;
    for (std::size_t i = 0; i < blocks.size(); ++i) {
      spec = spec->block(blocks[i]);
      path += (path.empty() ? "" : ".") + blocks[i];
      if (!spec) return declared_only + ", and it has no block " + in_quotes(path);
      if (spec->repeated && i + missing_blocks >= blocks.size()) {
        return in_quotes(blocks[i]) +
               " blocks form a list: --set cannot add one; add the block to the file";
      }
    }
    if (spec->parameter(key)) return "";
    return declared_only + ", and " + (path.empty() ? "the top level" : in_quotes(path)) +
           " has no parameter " + in_quotes(key);
  };
}

// ---- typed access ----

View::View(const Block& block, const BlockSpec& spec) : block_(&block), spec_(&spec) {}

bool View::has(std::string_view key) const {
  return block_->find(key) != nullptr;
}

const Value& View::value(std::string_view key) const {
  const ParameterSpec* declared = spec_->parameter(key);
  FSI_ASSERT(declared || spec_->open,
             "parameter '" + std::string(key) + "' is not declared in block '" + spec_->name + "'");
  if (const Parameter* given = block_->find(key)) {
    if (given->failed) throw AlreadyReported(given->location);
    return given->value;
  }
  if (declared && declared->default_value) return *declared->default_value;
  // A required block the scene leaves out: validate() reported the block, not each of its keys;
  // a required key a block leaves out: validate() reported it at the block.
  if (owned_ && spec_->required) throw AlreadyReported(block_->location);
  if (declared && declared->is_required()) throw AlreadyReported(block_->location);
  throw Error("'" + std::string(key) + "' is missing in " +
                  (block_->name.empty() ? std::string("the scene") : "block " + block_->name),
              block_->location.text(),
              "add " + std::string(key) + " = ..." +
                  (declared ? " (" + declared->doc + ")" : std::string()));
}

const Value& View::typed(std::string_view key, ValueKind kind) const {
  const Value& found = value(key);
  const bool empty_matrix =
      kind == ValueKind::Matrix && found.kind == ValueKind::Vector && found.vector.empty();
  if (found.kind != kind && !empty_matrix) {
    throw Error("'" + std::string(key) + "' must be a " + std::string(name(kind)) + ", not a " +
                    std::string(name(found.kind)),
                location(key).text(), "write a " + std::string(name(kind)));
  }
  return found;
}

double View::number(std::string_view key) const {
  return typed(key, ValueKind::Number).number;
}

long View::integer(std::string_view key) const {
  const double x = typed(key, ValueKind::Number).number;
  if (x != std::floor(x) || std::fabs(x) > 9.0e15) {
    throw Error(
        "'" + std::string(key) + "' must be a whole number, not " + format_value(number_value(x)),
        location(key).text(), "write a whole number");
  }
  return static_cast<long>(x);
}

const std::string& View::string(std::string_view key) const {
  return typed(key, ValueKind::String).text;
}

std::vector<double> View::vector(std::string_view key) const {
  return typed(key, ValueKind::Vector).vector;
}

NumberMatrix View::matrix(std::string_view key) const {
  return typed(key, ValueKind::Matrix).matrix;
}

SourceLocation View::location(std::string_view key) const {
  if (const Parameter* given = block_->find(key)) return given->location;
  return block_->location;
}

const BlockSpec& View::child_spec(std::string_view block_name) const {
  if (const BlockSpec* declared = spec_->block(block_name)) return *declared;
  FSI_ASSERT(
      spec_->open || spec_->user_blocks_allowed,
      "block '" + std::string(block_name) + "' is not declared in block '" + spec_->name + "'");
  return anything();
}

bool View::has_block(std::string_view block_name) const {
  return block_->child(block_name) != nullptr;
}

View View::block(std::string_view block_name) const {
  const BlockSpec& declared = child_spec(block_name);
  if (const Block* given = block_->child(block_name)) return View(*given, declared);
  auto empty = std::make_shared<Block>();
  empty->name = std::string(block_name);
  empty->location = block_->location;
  View view(*empty, declared);
  view.owned_ = std::move(empty);
  return view;
}

std::vector<View> View::blocks(std::string_view block_name) const {
  const BlockSpec& declared = child_spec(block_name);
  std::vector<View> views;
  for (const Block* given : block_->children(block_name))
    views.emplace_back(*given, declared);
  return views;
}

}  // namespace fsi::scene
