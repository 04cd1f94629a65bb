// --help-params text and the markdown reference page, both read off the declarations.

#include "fsi/scene/schema.hpp"
#include "schema_text.hpp"

namespace fsi::scene {
namespace detail {

std::string range_text(const ParameterSpec& spec, bool with_unit) {
  const std::string unit = with_unit && !spec.unit.empty() ? " " + spec.unit : "";
  std::string text;
  if (spec.minimum) {
    text +=
        (spec.minimum_exclusive ? "> " : ">= ") + format_value(number_value(*spec.minimum)) + unit;
  }
  if (spec.maximum) {
    text += (text.empty() ? "" : " and ") + std::string("<= ") +
            format_value(number_value(*spec.maximum)) + unit;
  }
  return text;
}

std::string choices_text(const std::vector<std::string>& choices) {
  std::string text;
  for (std::size_t i = 0; i < choices.size(); ++i)
    text += (i > 0 ? ", \"" : "\"") + choices[i] + "\"";
  return text;
}

std::string row_length_text(const ParameterSpec& spec) {
  std::string text = spec.length ? std::to_string(*spec.length) : "";
  if (spec.other_length) text += " or " + std::to_string(*spec.other_length);
  return text;
}

std::string default_text(const ParameterSpec& spec) {
  if (spec.default_value) return format_value(*spec.default_value);
  return spec.optional_without_default ? "(optional)" : "(required)";
}

}  // namespace detail

namespace {

// Everything a value may be: bounds, choices, length.
std::string allowed_text(const ParameterSpec& spec) {
  std::vector<std::string> parts;
  const std::string range = detail::range_text(spec, false);
  if (!range.empty()) {
    const bool per_element = spec.kind == Kind::Vector || spec.kind == Kind::Matrix;
    parts.push_back(per_element ? "each " + range : range);
  }
  if (!spec.choices.empty()) parts.push_back(detail::choices_text(spec.choices));
  if (spec.length) {
    parts.push_back(detail::row_length_text(spec) +
                    (spec.kind == Kind::Matrix ? " values per row" : " components"));
  }
  std::string text;
  for (std::size_t i = 0; i < parts.size(); ++i)
    text += (i > 0 ? "; " : "") + parts[i];
  return text;
}

std::string flags_text(const BlockSpec& spec) {
  std::string text;
  if (spec.required) text += " (required)";
  if (spec.repeated) text += " (element list: may appear several times)";
  if (spec.dimension != 0) text += " (dimension = " + std::to_string(spec.dimension) + " only)";
  if (spec.coupled_only) text += " (coupled runs only; --mbd-only does not read it)";
  return text;
}

std::string child_path(const std::string& path, const BlockSpec& child) {
  return path.empty() ? child.name : path + "." + child.name;
}

void help_block(const BlockSpec& spec, const std::string& path, std::string& out) {
  if (!path.empty()) {
    out += "\n" + path + flags_text(spec) + "\n";
    if (!spec.doc.empty()) out += "  " + spec.doc + "\n";
  }
  if (spec.open) out += "  (also takes keys and blocks of your own)\n";
  for (const ParameterSpec& parameter : spec.parameters) {
    std::string line = "  " + (path.empty() ? "" : path + ".") + parameter.key + "  " +
                       std::string(name(parameter.kind)) +
                       (parameter.unit.empty() ? "" : " [" + parameter.unit + "]");
    line += parameter.default_value ? "  default " + detail::default_text(parameter)
                                    : "  " + detail::default_text(parameter);
    const std::string allowed = allowed_text(parameter);
    if (!allowed.empty()) line += "  allowed: " + allowed;
    out += line + "\n      " + parameter.doc + "\n";
  }
  for (const BlockSpec& child : spec.blocks)
    help_block(child, child_path(path, child), out);
}

// A table cell: '|' would end the cell, a line break the row.
std::string cell(const std::string& text) {
  std::string out;
  for (const char c : text) {
    if (c == '|') {
      out += "\\|";
    } else if (c == '\n') {
      out += ' ';
    } else {
      out += c;
    }
  }
  return out.empty() ? "–" : out;
}

void markdown_block(const BlockSpec& spec, const std::string& path, std::string& out) {
  if (!path.empty()) {
    out += "\n## `" + path + "`" + flags_text(spec) + "\n\n";
    if (!spec.doc.empty()) out += spec.doc + "\n\n";
  } else if (!spec.parameters.empty()) {
    out += "\n## Top level\n\n";
  }
  if (spec.open) out += "Also takes keys and blocks of your own.\n\n";
  if (!spec.parameters.empty()) {
    out += "| key | kind | unit | default | allowed | meaning |\n|---|---|---|---|---|---|\n";
    for (const ParameterSpec& parameter : spec.parameters) {
      out += "| `" + parameter.key + "` | " + std::string(name(parameter.kind)) + " | " +
             cell(parameter.unit) + " | " + cell(detail::default_text(parameter)) + " | " +
             cell(allowed_text(parameter)) + " | " + cell(parameter.doc) + " |\n";
    }
  }
  for (const BlockSpec& child : spec.blocks)
    markdown_block(child, child_path(path, child), out);
}

}  // namespace

std::string render_help(const BlockSpec& root) {
  std::string out =
      "Scene parameters: path, kind [unit], default, allowed values, then what it means.\n"
      "An element list may appear several times; parameters without a default are required "
      "unless marked (optional).\n";
  help_block(root, "", out);
  return out;
}

std::string render_markdown(const BlockSpec& root) {
  std::string out;
  markdown_block(root, "", out);
  return out;
}

}  // namespace fsi::scene
