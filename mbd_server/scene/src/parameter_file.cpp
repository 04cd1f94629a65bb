// The public face of the language: loading, the evaluated tree's look-ups, and printing it back.

#include "fsi/scene/parameter_file.hpp"

#include <array>
#include <charconv>
#include <cmath>
#include <optional>
#include <utility>

#include "first_named.hpp"
#include "fsi/common/error.hpp"
#include "raw_tree.hpp"

namespace fsi::scene {
namespace {

std::string format_number(double value) {
  // The shortest text that reads back to the same double (what %.17g guarantees, minus the noise).
  char text[64];
  const auto end = std::to_chars(text, text + sizeof text, value).ptr;
  return std::string(text, end);
}

std::string format_row(const std::vector<double>& row) {
  std::string out = "[";
  for (std::size_t i = 0; i < row.size(); ++i)
    out += (i > 0 ? ", " : "") + format_number(row[i]);
  return out + "]";
}

// The expression as one line: comments are blanked already, so only blank runs remain to join.
std::string one_line(const std::string& expression) {
  std::string out;
  for (const char c : expression) {
    const bool blank = c == ' ' || c == '\t' || c == '\n' || c == '\r';
    if (blank) {
      if (!out.empty() && out.back() != ' ') out += ' ';
    } else {
      out += c;
    }
  }
  while (!out.empty() && out.back() == ' ')
    out.pop_back();
  return out;
}

Block convert(const detail::RawBlock& raw) {
  Block block;
  block.name = raw.name;
  block.location = raw.location;
  block.language_version = raw.language_version;
  block.language_version_location = raw.language_version_location;
  for (const detail::RawEntry& entry : raw.entries) {
    if (entry.is_block) {
      block.add_block(convert(*raw.blocks[entry.index]));
    } else {
      const detail::RawParameter& source = *raw.parameters[entry.index];
      Parameter parameter;
      parameter.key = source.key;
      parameter.value = source.value;
      parameter.expression = one_line(source.expression);
      parameter.location =
          source.override_label.empty() ? source.location : SourceLocation{source.override_label};
      parameter.failed = source.state != detail::RawParameter::State::Done;
      block.add_parameter(std::move(parameter));
    }
  }
  return block;
}

// Whether `expression` is just the value written out ("1e-5" for 1e-05), so a comment repeating
// it would be noise.
bool spells(const std::string& expression, const Value& value) {
  if (expression == format_value(value)) return true;
  if (value.kind != ValueKind::Number) return false;
  double literal = 0.0;
  const auto [end, error] =
      std::from_chars(expression.data(), expression.data() + expression.size(), literal);
  return error == std::errc() && end == expression.data() + expression.size() &&
         literal == value.number;
}

void print(const Block& block, int depth, std::string& out) {
  const std::string indent(static_cast<std::size_t>(2 * depth), ' ');
  for (const BlockEntry& entry : block.entries) {
    if (entry.type == BlockEntry::Type::Block) {
      const Block& child = block.blocks[entry.index];
      out += indent + child.name + "\n" + indent + "{\n";
      print(child, depth + 1, out);
      out += indent + "}\n";
      continue;
    }
    const Parameter& parameter = block.parameters[entry.index];
    const std::string head = indent + parameter.key + " = ";
    std::string value = format_value(parameter.value);
    if (parameter.value.kind == ValueKind::Matrix && parameter.value.matrix.size() > 1) {
      // One row per line, aligned under the first.
      value = "[";
      for (std::size_t r = 0; r < parameter.value.matrix.size(); ++r) {
        if (r > 0) value += ",\n" + std::string(head.size() + 1, ' ');
        value += format_row(parameter.value.matrix[r]);
      }
      value += "]";
    }
    out += head + value;
    const bool overridden =
        parameter.location.line == 0 && parameter.location.file.rfind("--set", 0) == 0;
    if (overridden) {
      out += "  % " + parameter.location.file;
    } else if (!parameter.expression.empty() && !spells(parameter.expression, parameter.value)) {
      out += "  % " + parameter.expression;
    }
    out += "\n";
  }
}

nlohmann::json value_json(const Value& value) {
  switch (value.kind) {
    case ValueKind::Number:
      return value.number;
    case ValueKind::String:
      // JSON text is UTF-8: a string with other bytes (found by fuzz_scene_parser) made dump()
      // throw a json::type_error; each invalid byte becomes U+FFFD instead.
      return nlohmann::json::parse(
          nlohmann::json(value.text)
              .dump(-1, ' ', false, nlohmann::json::error_handler_t::replace));
    case ValueKind::Vector:
      return value.vector;
    case ValueKind::Matrix:
      return value.matrix;
  }
  return nullptr;
}

void flatten(const Block& block, const std::string& prefix, std::map<std::string, double>& out) {
  for (const Parameter& parameter : block.parameters) {
    if (parameter.value.kind == ValueKind::Number)
      out[prefix + parameter.key] = parameter.value.number;
  }
  std::map<std::string, std::size_t> seen;
  for (const Block& child : block.blocks) {
    const std::size_t count = block.children(child.name).size();
    const std::size_t index = seen[child.name]++;
    flatten(child, prefix + child.name + (count > 1 ? "[" + std::to_string(index) + "]" : "") + ".",
            out);
  }
}

std::string read_file(const std::string& path) {
  std::optional<std::string> text = detail::read_regular_file(path);
  if (!text) {
    throw Error("cannot read the scene file '" + path + "'", path,
                "check the path and the file's permissions (it must be a regular file, not a "
                "folder or a device)");
  }
  return std::move(*text);
}

// Text -> evaluated tree; evaluation problems are appended to `problems`.
Block load_text(const std::string& text, const std::string& file_name,
                const std::vector<Override>& overrides, const IncludeReader& read_include,
                const OverrideAdmission& may_add, std::vector<Problem>& problems) {
  detail::RawBlock root;
  root.location = {file_name};
  detail::parse_into(root, text, file_name, read_include);
  detail::apply_overrides(root, overrides, may_add);
  std::vector<Problem> found = detail::evaluate(root);
  problems.insert(problems.end(), found.begin(), found.end());
  return convert(root);
}

}  // namespace

std::string_view name(ValueKind kind) {
  // Indexed by the enumerators, which are declared in this order.
  constexpr std::array<std::string_view, 4> kNames{"number", "string", "vector", "matrix"};
  const auto index = static_cast<std::size_t>(kind);
  return index < kNames.size() ? kNames[index] : "?";
}

Value number_value(double value) {
  Value result;
  result.number = value;
  return result;
}

Value text_value(std::string value) {
  Value result;
  result.kind = ValueKind::String;
  result.text = std::move(value);
  return result;
}

Value vector_value(std::vector<double> value) {
  Value result;
  result.kind = ValueKind::Vector;
  result.vector = std::move(value);
  return result;
}

Value matrix_value(NumberMatrix value) {
  Value result;
  result.kind = ValueKind::Matrix;
  result.matrix = std::move(value);
  return result;
}

std::string format_value(const Value& value) {
  switch (value.kind) {
    case ValueKind::Number:
      return format_number(value.number);
    case ValueKind::String:
      return "\"" + value.text + "\"";
    case ValueKind::Vector:
      return format_row(value.vector);
    case ValueKind::Matrix: {
      std::string out = "[";
      for (std::size_t r = 0; r < value.matrix.size(); ++r)
        out += (r > 0 ? ", " : "") + format_row(value.matrix[r]);
      return out + "]";
    }
  }
  return "";
}

const Parameter* Block::find(std::string_view key) const {
  const Parameter* found = nullptr;
  for (const Parameter& parameter : parameters) {
    if (parameter.key == key) found = &parameter;
  }
  return found;
}

std::vector<const Block*> Block::children(std::string_view child_name) const {
  std::vector<const Block*> found;
  for (const Block& block : blocks) {
    if (block.name == child_name) found.push_back(&block);
  }
  return found;
}

const Block* Block::child(std::string_view child_name) const {
  return detail::first_named(blocks, child_name, &Block::name);
}

const Block* Block::lookup_block(std::string_view path) const {
  std::vector<detail::PathPart> parts;
  if (!detail::parse_path(path, parts)) return nullptr;
  const Block* block = this;
  for (const detail::PathPart& part : parts) {
    const std::vector<const Block*> candidates = block->children(part.name);
    const std::size_t index = part.index < 0 ? 0 : static_cast<std::size_t>(part.index);
    if (index >= candidates.size()) return nullptr;
    block = candidates[index];
  }
  return block;
}

const Parameter* Block::lookup(std::string_view path) const {
  const std::size_t dot = path.rfind('.');
  if (dot == std::string_view::npos) return find(path);
  const Block* block = lookup_block(path.substr(0, dot));
  return block ? block->find(path.substr(dot + 1)) : nullptr;
}

Parameter& Block::add_parameter(Parameter parameter) {
  parameters.push_back(std::move(parameter));
  entries.push_back({BlockEntry::Type::Parameter, parameters.size() - 1});
  return parameters.back();
}

Block& Block::add_block(Block block) {
  blocks.push_back(std::move(block));
  entries.push_back({BlockEntry::Type::Block, blocks.size() - 1});
  return blocks.back();
}

Override parse_override(std::string_view text) {
  const std::size_t equals = text.find('=');
  const auto trim = [](std::string_view part) {
    const std::size_t first = part.find_first_not_of(" \t");
    if (first == std::string_view::npos) return std::string();
    return std::string(part.substr(first, part.find_last_not_of(" \t") - first + 1));
  };
  if (equals == std::string_view::npos || trim(text.substr(0, equals)).empty()) {
    throw Error("'" + std::string(text) + "' is not KEY=EXPR", "--set " + std::string(text),
                "write e.g. --set SolverOptions.end_time=0.05");
  }
  return {trim(text.substr(0, equals)), trim(text.substr(equals + 1))};
}

IncludeReader in_memory_files(std::map<std::string, std::string> files) {
  return [files = std::move(files)](const std::string& path) -> std::optional<std::string> {
    const auto found = files.find(path);
    if (found == files.end()) return std::nullopt;
    return found->second;
  };
}

Block parse_parameter_text(const std::string& text, const std::string& file_name,
                           const std::vector<Override>& overrides,
                           const IncludeReader& read_include) {
  std::vector<Problem> problems;
  Block root = load_text(text, file_name, overrides, read_include, {}, problems);
  throw_if_any(problems, file_name);
  return root;
}

Block load_parameter_file(const std::string& path, const std::vector<Override>& overrides) {
  return parse_parameter_text(read_file(path), path, overrides);
}

Block parse_parameter_text(const std::string& text, const std::string& file_name,
                           const std::vector<Override>& overrides, std::vector<Problem>& problems,
                           const OverrideAdmission& may_add) {
  return load_text(text, file_name, overrides, {}, may_add, problems);
}

Block load_parameter_file(const std::string& path, const std::vector<Override>& overrides,
                          std::vector<Problem>& problems, const OverrideAdmission& may_add) {
  return parse_parameter_text(read_file(path), path, overrides, problems, may_add);
}

std::string to_text(const Block& root) {
  std::string out;
  if (root.language_version)
    out += "scene_language = " + std::to_string(*root.language_version) + "\n";
  print(root, 0, out);
  return out;
}

nlohmann::json to_json(const Block& root) {
  nlohmann::json out = nlohmann::json::object();
  if (root.language_version) out["scene_language"] = *root.language_version;
  for (const BlockEntry& entry : root.entries) {
    if (entry.type == BlockEntry::Type::Parameter) {
      const Parameter& parameter = root.parameters[entry.index];
      out[parameter.key] = value_json(parameter.value);  // a later assignment wins, as in look-ups
      continue;
    }
    const Block& child = root.blocks[entry.index];
    if (root.children(child.name).size() > 1) {
      out[child.name].push_back(to_json(child));
    } else {
      out[child.name] = to_json(child);
    }
  }
  return out;
}

std::map<std::string, double> flatten_numbers(const Block& root) {
  std::map<std::string, double> out;
  flatten(root, "", out);
  return out;
}

}  // namespace fsi::scene
