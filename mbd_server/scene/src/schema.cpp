#include "fsi/scene/schema.hpp"

#include <cmath>
#include <cstdio>
#include <set>

#include "fsi/common/error.hpp"

namespace fsi::scene {
namespace {

std::string format(double value) {
  char text[40];
  std::snprintf(text, sizeof text, "%.10g", value);
  return text;
}

std::string range_text(const ParameterSpec& p) {
  std::string text;
  if (p.minimum) text += (p.minimum_exclusive ? "> " : ">= ") + format(*p.minimum);
  if (p.maximum) text += (text.empty() ? "" : ", ") + std::string("<= ") + format(*p.maximum);
  if (!p.choices.empty()) {
    for (std::size_t i = 0; i < p.choices.size(); ++i)
      text += (i ? " | " : "") + ("\"" + p.choices[i] + "\"");
  }
  if (p.length)
    text += (text.empty() ? "" : ", ") + std::to_string(*p.length) +
            (p.kind == Kind::Matrix ? " columns" : " components");
  return text;
}

std::string default_text(const ParameterSpec& p) {
  if (!p.default_value) return p.optional_without_default ? "(optional)" : "(required)";
  const Value& v = *p.default_value;
  switch (v.kind) {
    case ValueKind::Number:
      return format(v.number);
    case ValueKind::String:
      return "\"" + v.text + "\"";
    case ValueKind::Vector: {
      std::string out = "[";
      for (std::size_t i = 0; i < v.vector.size(); ++i)
        out += (i ? ", " : "") + format(v.vector[i]);
      return out + "]";
    }
    case ValueKind::Matrix:
      return "[[...]]";
  }
  return "";
}

bool kind_matches(Kind kind, ValueKind value) {
  switch (kind) {
    case Kind::Number:
    case Kind::Integer:
      return value == ValueKind::Number;
    case Kind::String:
      return value == ValueKind::String;
    case Kind::Vector:
      return value == ValueKind::Vector;
    case Kind::Matrix:
      return value == ValueKind::Matrix;
  }
  return false;
}

void check_number(const ParameterSpec& spec, double x, const std::string& what, const Parameter& p,
                  std::vector<Problem>& problems) {
  if (spec.kind == Kind::Integer && x != std::floor(x)) {
    problems.push_back(
        {p.location, what + " must be an integer, got " + format(x), "write a whole number"});
    return;
  }
  const bool below =
      spec.minimum && (spec.minimum_exclusive ? x <= *spec.minimum : x < *spec.minimum);
  const bool above = spec.maximum && x > *spec.maximum;
  if (below || above) {
    problems.push_back({p.location,
                        what + " = " + format(x) + (spec.unit.empty() ? "" : " " + spec.unit) +
                            " is out of range (" + range_text(spec) + ")",
                        "choose a value in the range; check the unit (" +
                            (spec.unit.empty() ? std::string("dimensionless") : spec.unit) + ")"});
  }
}

void validate_block(const Block& block, const BlockSpec& spec, const std::string& path,
                    std::vector<Problem>& problems) {
  if (spec.open) return;
  std::vector<std::string> known;
  for (const auto& p : spec.parameters)
    known.push_back(p.key);
  for (const auto& b : spec.blocks)
    known.push_back(b.name);

  std::set<std::string> seen_keys;
  for (const Parameter& p : block.parameters) {
    const std::string full = path + p.key;
    const ParameterSpec* declared = nullptr;
    for (const auto& candidate : spec.parameters) {
      if (candidate.key == p.key) declared = &candidate;
    }
    if (!declared) {
      const std::string suggestion = nearest(p.key, known);
      problems.push_back({p.location, "unknown parameter '" + full + "'",
                          suggestion.empty()
                              ? "see fsi-server --help-params for the parameters of " +
                                    (spec.name.empty() ? std::string("the scene") : spec.name)
                              : "did you mean '" + suggestion + "'?"});
      continue;
    }
    if (!seen_keys.insert(p.key).second) continue;  // a later assignment overrides an earlier one
    if (!kind_matches(declared->kind, p.value.kind)) {
      problems.push_back({p.location,
                          "'" + full + "' must be a " + std::string(name(declared->kind)) +
                              ", got a " + std::string(name(p.value.kind)),
                          declared->kind == Kind::String
                              ? "write the value in double quotes"
                              : "write a " + std::string(name(declared->kind))});
      continue;
    }
    if (declared->kind == Kind::Number || declared->kind == Kind::Integer) {
      check_number(*declared, p.value.number, "'" + full + "'", p, problems);
    } else if (declared->kind == Kind::String && !declared->choices.empty()) {
      bool allowed = false;
      for (const auto& choice : declared->choices)
        allowed = allowed || choice == p.value.text;
      if (!allowed) {
        problems.push_back(
            {p.location,
             "'" + full + "' = \"" + p.value.text + "\" is not one of " + range_text(*declared),
             "use one of the listed values"});
      }
    } else if (declared->kind == Kind::Vector && declared->length &&
               p.value.vector.size() != *declared->length) {
      problems.push_back({p.location,
                          "'" + full + "' needs " + std::to_string(*declared->length) +
                              " components, got " + std::to_string(p.value.vector.size()),
                          "write [" + std::string(*declared->length == 2 ? "x, y" : "...") + "]"});
    } else if (declared->kind == Kind::Matrix && declared->length && !p.value.matrix.empty() &&
               p.value.matrix.front().size() != *declared->length) {
      problems.push_back(
          {p.location,
           "'" + full + "' needs rows of " + std::to_string(*declared->length) + " values",
           "write [[x, y], [x, y], ...]"});
    }
  }
  for (const auto& declared : spec.parameters) {
    if (!declared.default_value && !declared.optional_without_default &&
        !block.find(declared.key)) {
      problems.push_back(
          {block.location, "'" + path + declared.key + "' is missing (" + declared.doc + ")",
           "add " + declared.key + " = ... to " + (spec.name.empty() ? "the scene" : spec.name)});
    }
  }

  std::map<std::string, int> counts;
  for (const Block& child : block.blocks)
    ++counts[child.name];
  std::map<std::string, int> seen;
  for (const Block& child : block.blocks) {
    const BlockSpec* declared = nullptr;
    for (const auto& candidate : spec.blocks) {
      if (candidate.name == child.name) declared = &candidate;
    }
    if (!declared) {
      const std::string suggestion = nearest(child.name, known);
      if (spec.user_blocks_allowed &&
          (suggestion.empty() || edit_distance(suggestion, child.name) > 2)) {
        continue;  // the user's own parameter block
      }
      problems.push_back(
          {child.location, "unknown block '" + path + child.name + "'",
           suggestion.empty()
               ? "see fsi-server --help-params"
               : "did you mean '" + suggestion + "'?" +
                     (spec.user_blocks_allowed ? " If this is your own parameter block, rename it."
                                               : "")});
      continue;
    }
    const int index = seen[child.name]++;
    if (!declared->repeated && index == 1) {
      problems.push_back({child.location, "block '" + path + child.name + "' is given twice",
                          "merge the two blocks; only element lists may repeat"});
    }
    const std::string child_path =
        path + child.name + (counts[child.name] > 1 ? "[" + std::to_string(index) + "]" : "") + ".";
    validate_block(child, *declared, child_path, problems);
  }
  for (const auto& declared : spec.blocks) {
    if (declared.required && counts[declared.name] == 0) {
      problems.push_back({block.location,
                          "block '" + path + declared.name + "' is missing (" + declared.doc + ")",
                          "add " + declared.name + " { ... }"});
    }
  }
}

void help_block(const BlockSpec& spec, const std::string& path, std::string& out) {
  if (!path.empty()) {
    out += "\n" + path + (spec.repeated ? "  (may be repeated)" : "") +
           (spec.required ? "  (required)" : "") + "\n";
    out += "  " + spec.doc + "\n";
  }
  for (const auto& p : spec.parameters) {
    std::string line = "  " + (path.empty() ? "" : path + ".") + p.key + "  [" +
                       std::string(name(p.kind)) + (p.unit.empty() ? "" : ", " + p.unit) +
                       "]  default " + default_text(p);
    const std::string range = range_text(p);
    if (!range.empty()) line += "  range " + range;
    out += line + "\n      " + p.doc + "\n";
  }
  for (const auto& b : spec.blocks)
    help_block(b, path.empty() ? b.name : path + "." + b.name, out);
}

void markdown_block(const BlockSpec& spec, const std::string& path, std::string& out) {
  if (!path.empty()) {
    out += "\n## `" + path + "`" + (spec.repeated ? " (element list)" : "") +
           (spec.required ? " (required)" : "") + "\n\n" + spec.doc + "\n\n";
  }
  if (spec.open) out += "Any keys and blocks: every entry is passed on as described above.\n";
  if (!spec.parameters.empty()) {
    out += "| key | kind | unit | default | range | meaning |\n|---|---|---|---|---|---|\n";
    for (const auto& p : spec.parameters) {
      out += "| `" + p.key + "` | " + std::string(name(p.kind)) + " | " +
             (p.unit.empty() ? "–" : p.unit) + " | " + default_text(p) + " | " + range_text(p) +
             " | " + p.doc + " |\n";
    }
  }
  for (const auto& b : spec.blocks)
    markdown_block(b, path.empty() ? b.name : path + "." + b.name, out);
}

}  // namespace

std::string_view name(Kind kind) {
  switch (kind) {
    case Kind::Number:
      return "number";
    case Kind::Integer:
      return "integer";
    case Kind::String:
      return "string";
    case Kind::Vector:
      return "vector";
    case Kind::Matrix:
      return "matrix";
  }
  return "?";
}

ParameterSpec number(std::string key, std::string unit, std::string doc) {
  ParameterSpec p;
  p.key = std::move(key);
  p.kind = Kind::Number;
  p.unit = std::move(unit);
  p.doc = std::move(doc);
  return p;
}
ParameterSpec integer(std::string key, std::string doc) {
  ParameterSpec p = number(std::move(key), "", std::move(doc));
  p.kind = Kind::Integer;
  return p;
}
ParameterSpec text(std::string key, std::string doc) {
  ParameterSpec p = number(std::move(key), "", std::move(doc));
  p.kind = Kind::String;
  return p;
}
ParameterSpec vector(std::string key, std::size_t length, std::string unit, std::string doc) {
  ParameterSpec p = number(std::move(key), std::move(unit), std::move(doc));
  p.kind = Kind::Vector;
  p.length = length;
  return p;
}
ParameterSpec matrix(std::string key, std::size_t columns, std::string unit, std::string doc) {
  ParameterSpec p = number(std::move(key), std::move(unit), std::move(doc));
  p.kind = Kind::Matrix;
  p.length = columns;
  return p;
}
Value number_value(double value) {
  Value v;
  v.number = value;
  return v;
}
Value text_value(std::string value) {
  Value v;
  v.kind = ValueKind::String;
  v.text = std::move(value);
  return v;
}
Value vector_value(std::vector<double> value) {
  Value v;
  v.kind = ValueKind::Vector;
  v.vector = std::move(value);
  return v;
}

std::string Problem::text() const {
  return location.text() + ": " + message + (fix.empty() ? "" : " (" + fix + ")");
}

std::vector<Problem> validate(const Block& root, const BlockSpec& spec) {
  std::vector<Problem> problems;
  validate_block(root, spec, "", problems);
  return problems;
}

void throw_if_any(const std::vector<Problem>& problems, const std::string& file) {
  if (problems.empty()) return;
  std::string text = std::to_string(problems.size()) + " problem(s) in the scene:";
  for (const auto& problem : problems)
    text += "\n  " + problem.text();
  throw Error(text, file,
              "correct the entries listed above (fsi-server --help-params lists them all)");
}

View::View(const Block& block, const BlockSpec& spec) : block_(&block), spec_(&spec) {}

const ParameterSpec& View::parameter_spec(const std::string& key) const {
  for (const auto& p : spec_->parameters) {
    if (p.key == key) return p;
  }
  FSI_ASSERT(false, "parameter '" + key + "' is not declared in block '" + spec_->name + "'");
  std::abort();
}

const BlockSpec& View::block_spec(const std::string& block_name) const {
  for (const auto& b : spec_->blocks) {
    if (b.name == block_name) return b;
  }
  FSI_ASSERT(false, "block '" + block_name + "' is not declared in block '" + spec_->name + "'");
  std::abort();
}

bool View::has(const std::string& key) const {
  return block_->find(key) != nullptr;
}

const Value& View::value(const std::string& key) const {
  const ParameterSpec& declared = parameter_spec(key);
  if (const Parameter* p = block_->find(key)) return p->value;
  if (!declared.default_value) {
    throw Error("'" + key + "' is missing", block_->location.text(),
                "add " + key + " = ... (" + declared.doc + ")");
  }
  return *declared.default_value;
}

double View::number(const std::string& key) const {
  return value(key).number;
}
long View::integer(const std::string& key) const {
  return std::lround(value(key).number);
}
const std::string& View::string(const std::string& key) const {
  return value(key).text;
}
std::vector<double> View::vector(const std::string& key) const {
  return value(key).vector;
}
std::vector<std::vector<double>> View::matrix(const std::string& key) const {
  return value(key).matrix;
}

SourceLocation View::location(const std::string& key) const {
  if (const Parameter* p = block_->find(key)) return p->location;
  return block_->location;
}

bool View::has_block(const std::string& block_name) const {
  return block_->child(block_name) != nullptr;
}

View View::block(const std::string& block_name) const {
  const BlockSpec& declared = block_spec(block_name);
  if (const Block* child = block_->child(block_name)) return View(*child, declared);
  // An absent block reads as all defaults.
  auto empty = std::make_shared<Block>();
  empty->name = block_name;
  empty->location = block_->location;
  View view(*empty, declared);
  view.owned_ = std::move(empty);
  return view;
}

std::vector<View> View::blocks(const std::string& block_name) const {
  const BlockSpec& declared = block_spec(block_name);
  std::vector<View> views;
  for (const Block* child : block_->children(block_name))
    views.emplace_back(*child, declared);
  return views;
}

std::string render_help(const BlockSpec& root) {
  std::string out = "Parameters of a scene file (kind, unit, default, range, meaning):\n";
  help_block(root, "", out);
  return out;
}

std::string render_markdown(const BlockSpec& root) {
  std::string out;
  markdown_block(root, "", out);
  return out;
}

}  // namespace fsi::scene
