#include "fsi/scene/parameter_file.hpp"

#include <muParser.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <regex>
#include <sstream>

#include "fsi/common/error.hpp"

namespace fsi::scene {
namespace {

namespace fs = std::filesystem;

// ---------- raw tree (unevaluated) ----------

struct RawBlock;

struct RawParameter {
  std::string key;
  std::string expression;
  SourceLocation location;             // of the key
  SourceLocation expression_location;  // of the expression
  int sequence = 0;                    // textual order across all files
  RawBlock* parent = nullptr;
  Value value;
  bool evaluated = false;
  bool failed = false;
};

struct RawBlock {
  std::string name;
  SourceLocation location;
  RawBlock* parent = nullptr;
  std::vector<std::unique_ptr<RawParameter>> parameters;
  std::vector<std::unique_ptr<RawBlock>> blocks;
  std::vector<std::pair<bool, std::size_t>> order;

  RawParameter* find_parameter(std::string_view key) {
    RawParameter* found = nullptr;
    for (auto& p : parameters) {
      if (p->key == key) found = p.get();  // the last assignment wins
    }
    return found;
  }
  std::vector<RawBlock*> find_blocks(std::string_view block_name) {
    std::vector<RawBlock*> found;
    for (auto& b : blocks) {
      if (b->name == block_name) found.push_back(b.get());
    }
    return found;
  }
  RawBlock* add_block(std::string block_name, SourceLocation where) {
    auto block = std::make_unique<RawBlock>();
    block->name = std::move(block_name);
    block->location = std::move(where);
    block->parent = this;
    blocks.push_back(std::move(block));
    order.emplace_back(true, blocks.size() - 1);
    return blocks.back().get();
  }
};

// A path component "Name" or "Name[3]".
struct PathPart {
  std::string name;
  int index = -1;
};

bool parse_path(std::string_view path, std::vector<PathPart>& parts) {
  static const std::regex part(R"(^([A-Za-z_][A-Za-z0-9_]*)(\[([0-9]+)\])?$)");
  parts.clear();
  std::size_t start = 0;
  while (true) {
    const std::size_t dot = path.find('.', start);
    const std::string piece(
        path.substr(start, dot == std::string_view::npos ? std::string_view::npos : dot - start));
    std::smatch match;
    if (!std::regex_match(piece, match, part)) return false;
    parts.push_back({match[1].str(), match[3].matched ? std::stoi(match[3].str()) : -1});
    if (dot == std::string_view::npos) return true;
    start = dot + 1;
  }
}

// ---------- parser ----------

class Parser {
 public:
  Parser(int& sequence, std::vector<std::string>& include_stack)
      : sequence_(sequence), include_stack_(include_stack) {}

  void parse(const std::string& text, const std::string& file, RawBlock& root) {
    text_ = &text;
    file_ = file;
    position_ = 0;
    line_ = 1;
    line_start_ = 0;
    parse_entries(root, /*top_level=*/true);
  }

 private:
  SourceLocation here() const {
    return {file_, line_, static_cast<int>(position_ - line_start_) + 1};
  }
  [[noreturn]] void fail(const std::string& what, const std::string& fix,
                         const SourceLocation& where) const {
    throw Error(what, where.text(), fix);
  }
  bool at_end() const { return position_ >= text_->size(); }
  char peek(std::size_t ahead = 0) const {
    return position_ + ahead < text_->size() ? (*text_)[position_ + ahead] : '\0';
  }
  void advance() {
    if (peek() == '\n') {
      ++line_;
      line_start_ = position_ + 1;
    }
    ++position_;
  }
  bool comment_starts() const { return peek() == '%' || (peek() == '/' && peek(1) == '/'); }
  void skip_comment() {
    while (!at_end() && peek() != '\n')
      advance();
  }
  // Skips blanks, newlines, ';' separators and comments.
  void skip_space() {
    while (!at_end()) {
      if (std::isspace(static_cast<unsigned char>(peek())) || peek() == ';') {
        advance();
      } else if (comment_starts()) {
        skip_comment();
      } else {
        break;
      }
    }
  }
  void skip_blanks() {
    while (peek() == ' ' || peek() == '\t' || peek() == '\r')
      advance();
  }
  std::string read_name() {
    std::string out;
    while (std::isalnum(static_cast<unsigned char>(peek())) || peek() == '_' || peek() == '.') {
      out += peek();
      advance();
    }
    return out;
  }

  void parse_entries(RawBlock& block, bool top_level) {
    while (true) {
      skip_space();
      if (at_end()) {
        if (!top_level) {
          fail("block '" + block.name + "' opened here is not closed", "add the missing '}'",
               block.location);
        }
        return;
      }
      if (peek() == '}') {
        if (top_level) fail("'}' without an open block", "remove it or open a block", here());
        advance();
        return;
      }
      const SourceLocation start = here();
      if (!(std::isalpha(static_cast<unsigned char>(peek())) || peek() == '_')) {
        fail(std::string("unexpected '") + peek() + "'",
             "an entry starts with a name: 'key = expression' or 'Block { ... }'", start);
      }
      const std::string name = read_name();
      if (name.empty() || name.back() == '.' || name.find("..") != std::string::npos) {
        fail("'" + name + "' is not a valid name",
             "names are letters, digits and '_', joined by '.'", start);
      }
      if (name == "include") {
        parse_include(block, start);
        continue;
      }
      skip_space();
      if (peek() == '{') {
        if (name.find('.') != std::string::npos) {
          fail("block name '" + name + "' contains '.'", "nest blocks instead", start);
        }
        advance();
        RawBlock* child = block.add_block(name, start);
        parse_entries(*child, false);
      } else if (peek() == '=') {
        advance();
        parse_parameter(block, name, start);
      } else {
        fail("expected '=' or '{' after '" + name + "'",
             "write 'key = expression' or 'Block { ... }'", here());
      }
    }
  }

  void parse_parameter(RawBlock& block, const std::string& dotted, const SourceLocation& start) {
    skip_blanks();
    const SourceLocation expression_start = here();
    std::string expression;
    int depth = 0;
    bool in_string = false;
    while (!at_end()) {
      const char c = peek();
      if (in_string) {
        if (c == '\n')
          fail("string not closed before the end of the line", "add the closing '\"'",
               expression_start);
        if (c == '"') in_string = false;
      } else {
        if (c == '"') in_string = true;
        if (c == '[') ++depth;
        if (c == ']') --depth;
        if (depth < 0) fail("']' without '['", "balance the brackets", here());
        if (depth == 0 && (c == '\n' || c == ';' || c == '}')) break;
        if (comment_starts()) {
          if (depth == 0) break;
          skip_comment();
          continue;
        }
      }
      if (c == '\n' || c == '\r' || c == '\t') {
        if (!expression.empty() && expression.back() != ' ') expression += ' ';
      } else {
        expression += c;
      }
      advance();
    }
    if (depth > 0) fail("'[' is not closed", "add the missing ']'", expression_start);
    while (!expression.empty() && std::isspace(static_cast<unsigned char>(expression.back())))
      expression.pop_back();
    if (expression.empty())
      fail("'" + dotted + "' has no value after '='", "write key = expression", start);

    // Dotted key: assign inside the (first) block of that name, creating it if absent.
    RawBlock* target = &block;
    std::string key = dotted;
    std::size_t dot;
    while ((dot = key.find('.')) != std::string::npos) {
      const std::string head = key.substr(0, dot);
      auto existing = target->find_blocks(head);
      target = existing.empty() ? target->add_block(head, start) : existing.front();
      key = key.substr(dot + 1);
    }
    auto parameter = std::make_unique<RawParameter>();
    parameter->key = key;
    parameter->expression = expression;
    parameter->location = start;
    parameter->expression_location = expression_start;
    parameter->sequence = ++sequence_;
    parameter->parent = target;
    target->parameters.push_back(std::move(parameter));
    target->order.emplace_back(false, target->parameters.size() - 1);
  }

  void parse_include(RawBlock& block, const SourceLocation& start) {
    skip_blanks();
    if (peek() != '"')
      fail("include needs a file name in quotes", "write include \"file.scene\"", here());
    advance();
    std::string name;
    while (!at_end() && peek() != '"' && peek() != '\n') {
      name += peek();
      advance();
    }
    if (peek() != '"') fail("include file name is not closed", "add the closing '\"'", start);
    advance();
    fs::path path = name;
    if (path.is_relative()) path = fs::path(file_).parent_path() / path;
    const std::string canonical = fs::weakly_canonical(path).string();
    if (std::find(include_stack_.begin(), include_stack_.end(), canonical) !=
        include_stack_.end()) {
      fail("include cycle: '" + name + "' is already being read", "remove the cyclic include",
           start);
    }
    std::ifstream in(path);
    if (!in)
      fail("cannot read included file '" + path.string() + "'",
           "check the path (relative to this file)", start);
    std::stringstream content;
    content << in.rdbuf();
    const std::string text = content.str();
    include_stack_.push_back(canonical);
    Parser nested(sequence_, include_stack_);
    nested.parse(text, path.string(), block);
    include_stack_.pop_back();
  }

  int& sequence_;
  std::vector<std::string>& include_stack_;
  const std::string* text_ = nullptr;
  std::string file_;
  std::size_t position_ = 0;
  int line_ = 1;
  std::size_t line_start_ = 0;
};

// ---------- evaluation ----------

std::string trim(std::string_view text) {
  std::size_t a = 0, b = text.size();
  while (a < b && std::isspace(static_cast<unsigned char>(text[a])))
    ++a;
  while (b > a && std::isspace(static_cast<unsigned char>(text[b - 1])))
    --b;
  return std::string(text.substr(a, b - a));
}

// Splits "a, [b, c], d" at top-level commas.
std::vector<std::string> split_top_level(std::string_view text) {
  std::vector<std::string> parts;
  int depth = 0;
  std::size_t start = 0;
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (text[i] == '[' || text[i] == '(') ++depth;
    if (text[i] == ']' || text[i] == ')') --depth;
    if (text[i] == ',' && depth == 0) {
      parts.push_back(trim(text.substr(start, i - start)));
      start = i + 1;
    }
  }
  parts.push_back(trim(text.substr(start)));
  return parts;
}

class Evaluator {
 public:
  explicit Evaluator(RawBlock& root) : root_(root) {}

  void collect(RawBlock& block, std::vector<RawParameter*>& all) {
    for (auto& p : block.parameters)
      all.push_back(p.get());
    for (auto& b : block.blocks)
      collect(*b, all);
  }

  std::vector<std::string> run() {
    std::vector<RawParameter*> all;
    collect(root_, all);
    std::sort(all.begin(), all.end(), [](auto* a, auto* b) { return a->sequence < b->sequence; });
    for (RawParameter* p : all)
      evaluate(*p);
    return problems_;
  }

 private:
  // Finds what `path` names, seen from `from`.
  struct Found {
    RawParameter* parameter = nullptr;
    std::string problem;
  };

  Found resolve(std::string_view path, const RawParameter& from) {
    std::vector<PathPart> parts;
    if (!parse_path(path, parts))
      return {nullptr, "'" + std::string(path) + "' is not a valid name"};
    for (RawBlock* scope = from.parent; scope; scope = scope->parent) {
      Found found = resolve_in(*scope, parts, from);
      if (found.parameter || !found.problem.empty()) return found;
    }
    std::vector<std::string> known;
    gather_names(from.parent, known);
    const std::string suggestion = nearest(path, known);
    return {nullptr,
            "'" + std::string(path) + "' is not defined" +
                (suggestion.empty() ? std::string() : "; did you mean '" + suggestion + "'?")};
  }

  Found resolve_in(RawBlock& scope, const std::vector<PathPart>& parts, const RawParameter& from) {
    RawBlock* block = &scope;
    for (std::size_t i = 0; i + 1 < parts.size(); ++i) {
      auto candidates = block->find_blocks(parts[i].name);
      if (candidates.empty()) {
        if (block == &scope) return {};  // not in this scope: look further out
        return {nullptr, "block '" + block->name + "' has no block '" + parts[i].name + "'"};
      }
      if (parts[i].index >= static_cast<int>(candidates.size())) {
        return {nullptr, "'" + parts[i].name + "[" + std::to_string(parts[i].index) +
                             "]' does not exist (" + std::to_string(candidates.size()) +
                             " blocks)"};
      }
      if (parts[i].index < 0 && candidates.size() > 1) {
        return {nullptr, "'" + parts[i].name + "' is a list of " +
                             std::to_string(candidates.size()) + " blocks; write " + parts[i].name +
                             "[0]." + parts[i + 1].name + " etc."};
      }
      block = candidates[parts[i].index < 0 ? 0 : parts[i].index];
    }
    // The last assignment before `from` counts (a key may be assigned twice).
    RawParameter* hit = nullptr;
    RawParameter* later = nullptr;
    for (auto& p : block->parameters) {
      if (p->key != parts.back().name || p.get() == &from) continue;
      if (p->sequence < from.sequence) {
        hit = p.get();
      } else if (!later) {
        later = p.get();
      }
    }
    if (hit) return {hit, ""};
    if (later) {
      return {nullptr, "'" + parts.back().name + "' is defined later at " + later->location.text() +
                           "; move it above line " + std::to_string(from.location.line)};
    }
    if (block != &scope)
      return {nullptr, "block '" + block->name + "' has no parameter '" + parts.back().name + "'"};
    return {};
  }

  void gather_names(RawBlock* scope, std::vector<std::string>& names) {
    for (RawBlock* s = scope; s; s = s->parent) {
      for (auto& p : s->parameters)
        names.push_back(p->key);
      for (auto& b : s->blocks) {
        for (auto& p : b->parameters)
          names.push_back(b->name + "." + p->key);
      }
    }
  }

  void report(const RawParameter& p, const std::string& what) {
    problems_.push_back(p.expression_location.text() + ": '" + p.key + "': " + what);
  }

  static double* variable_factory(const char* name, void* self) {
    auto* evaluator = static_cast<Evaluator*>(self);
    evaluator->storage_.push_back(std::make_unique<double>(std::nan("")));
    double* slot = evaluator->storage_.back().get();
    Found found = evaluator->resolve(name, *evaluator->current_);
    if (!found.parameter) {
      evaluator->reference_problems_.push_back(found.problem);
    } else if (found.parameter->failed || !found.parameter->evaluated) {
      evaluator->reference_problems_.push_back("'" + std::string(name) +
                                               "' has no value (see its own error)");
    } else if (found.parameter->value.kind != ValueKind::Number) {
      evaluator->reference_problems_.push_back(
          "'" + std::string(name) + "' is a " +
          std::string(fsi::scene::name(found.parameter->value.kind)) +
          ", arithmetic needs numbers");
    } else {
      *slot = found.parameter->value.number;
    }
    return slot;
  }

  bool number(const std::string& text, RawParameter& p, double& out) {
    reference_problems_.clear();
    current_ = &p;
    try {
      mu::Parser parser;
      parser.DefineNameChars("0123456789_abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ.");
      parser.DefineConst("pi", M_PI);
      parser.DefineConst("e", M_E);
      parser.SetVarFactory(&Evaluator::variable_factory, this);
      parser.SetExpr(text);
      out = parser.Eval();
    } catch (const mu::Parser::exception_type& error) {
      if (reference_problems_.empty()) {
        report(p, "cannot evaluate '" + text + "': " + error.GetMsg());
        return false;
      }
    }
    if (!reference_problems_.empty()) {
      for (const auto& problem : reference_problems_)
        report(p, problem);
      return false;
    }
    if (!std::isfinite(out)) {
      report(p, "'" + text + "' evaluates to " + std::to_string(out));
      return false;
    }
    return true;
  }

  bool row(const std::string& text, RawParameter& p, std::vector<double>& out) {
    if (text.size() < 2 || text.front() != '[' || text.back() != ']') {
      report(p, "'" + text + "' is not a bracketed list");
      return false;
    }
    const std::string inner = trim(std::string_view(text).substr(1, text.size() - 2));
    if (inner.empty()) return true;
    bool ok = true;
    for (const std::string& element : split_top_level(inner)) {
      double value = 0.0;
      if (element.empty()) {
        report(p, "empty element in '" + text + "'");
        ok = false;
      } else if (element.front() == '[') {
        report(p, "a vector element is a list; matrices are [[...], [...]]");
        ok = false;
      } else if (number(element, p, value)) {
        out.push_back(value);
      } else {
        ok = false;
      }
    }
    return ok;
  }

  void evaluate(RawParameter& p) {
    const std::string text = trim(p.expression);
    Value value;
    bool ok = true;
    static const std::regex reference(
        R"(^[A-Za-z_][A-Za-z0-9_]*(\[[0-9]+\])?(\.[A-Za-z_][A-Za-z0-9_]*(\[[0-9]+\])?)*$)");
    if (text.front() == '"') {
      if (text.size() < 2 || text.back() != '"' || text.find('"', 1) != text.size() - 1) {
        report(p, "a string is one \"...\" with no further text");
        ok = false;
      } else {
        value.kind = ValueKind::String;
        value.text = text.substr(1, text.size() - 2);
      }
    } else if (text.front() == '[') {
      const std::string inner = trim(std::string_view(text).substr(1, text.size() - 2));
      if (!inner.empty() && inner.front() == '[') {
        value.kind = ValueKind::Matrix;
        for (const std::string& row_text : split_top_level(inner)) {
          std::vector<double> values;
          ok = row(row_text, p, values) && ok;
          value.matrix.push_back(std::move(values));
        }
        if (ok) {
          for (const auto& r : value.matrix) {
            if (r.size() != value.matrix.front().size()) {
              report(p, "matrix rows have different lengths");
              ok = false;
              break;
            }
          }
        }
      } else {
        value.kind = ValueKind::Vector;
        ok = row(text, p, value.vector);
      }
    } else if (std::regex_match(text, reference) && text.find('[') != std::string::npos) {
      // Indexed references (Body[1].mass) only as a whole expression.
      Found found = resolve(text, p);
      if (!found.parameter || found.parameter->failed) {
        report(p, found.parameter ? "'" + text + "' has no value" : found.problem);
        ok = false;
      } else {
        value = found.parameter->value;
      }
    } else if (std::regex_match(text, reference)) {
      Found found = resolve(text, p);
      if (found.parameter && !found.parameter->failed && found.parameter->evaluated &&
          found.parameter->value.kind != ValueKind::Number) {
        value = found.parameter->value;  // copy of a string, vector or matrix
      } else {
        value.kind = ValueKind::Number;
        ok = number(text, p, value.number);
      }
    } else {
      value.kind = ValueKind::Number;
      ok = number(text, p, value.number);
    }
    p.value = std::move(value);
    p.evaluated = ok;
    p.failed = !ok;
  }

  RawBlock& root_;
  const RawParameter* current_ = nullptr;
  std::vector<std::unique_ptr<double>> storage_;
  std::vector<std::string> reference_problems_;
  std::vector<std::string> problems_;
};

void gather_paths(RawBlock& block, const std::string& prefix, std::vector<std::string>& out) {
  for (auto& p : block.parameters)
    out.push_back(prefix + p->key);
  std::map<std::string, int> seen;
  for (auto& b : block.blocks) {
    const int count = static_cast<int>(block.find_blocks(b->name).size());
    const int index = seen[b->name]++;
    gather_paths(*b, prefix + b->name + (count > 1 ? "[" + std::to_string(index) + "]" : "") + ".",
                 out);
  }
}

void apply_override(RawBlock& root, const Override& item) {
  const std::string where = "--set " + item.path + "=" + item.expression;
  std::vector<PathPart> parts;
  if (!parse_path(item.path, parts)) {
    throw Error("'" + item.path + "' is not a parameter path", where,
                "write e.g. Geometry.width=0.06 or Body[1].mass=2");
  }
  RawBlock* block = &root;
  RawParameter* target = nullptr;
  for (std::size_t i = 0; i < parts.size() && block; ++i) {
    if (i + 1 == parts.size()) {
      target = block->find_parameter(parts[i].name);
      break;
    }
    auto candidates = block->find_blocks(parts[i].name);
    if (parts[i].index < 0 && candidates.size() > 1) {
      throw Error(
          "'" + parts[i].name + "' is a list of " + std::to_string(candidates.size()) + " blocks",
          where,
          "pick one: " + parts[i].name + "[0] ... " + parts[i].name + "[" +
              std::to_string(candidates.size() - 1) + "]");
    }
    const int index = parts[i].index < 0 ? 0 : parts[i].index;
    block = index < static_cast<int>(candidates.size()) ? candidates[index] : nullptr;
  }
  if (!target) {
    std::vector<std::string> paths;
    gather_paths(root, "", paths);
    const std::string suggestion = nearest(item.path, paths);
    throw Error("the scene has no parameter '" + item.path + "'", where,
                suggestion.empty() ? "--set can only change parameters the file defines"
                                   : "did you mean '" + suggestion + "'?");
  }
  if (trim(item.expression).empty()) throw Error("empty value", where, "write KEY=EXPR");
  target->expression = item.expression;
  target->location = {where, 0, 0};
  target->expression_location = target->location;
}

void convert(const RawBlock& raw, Block& out) {
  out.name = raw.name;
  out.location = raw.location;
  for (const auto& [is_block, index] : raw.order) {
    if (is_block) {
      Block child;
      convert(*raw.blocks[index], child);
      out.blocks.push_back(std::move(child));
      out.order.emplace_back(true, out.blocks.size() - 1);
    } else {
      const RawParameter& p = *raw.parameters[index];
      out.parameters.push_back({p.key, p.value, p.expression, p.location});
      out.order.emplace_back(false, out.parameters.size() - 1);
    }
  }
}

std::string format_number(double value) {
  // Shortest text that reads back to the same double.
  char text[40];
  const auto end = std::to_chars(text, text + sizeof text, value).ptr;
  return std::string(text, end);
}

std::string format_value(const Value& value) {
  switch (value.kind) {
    case ValueKind::Number:
      return format_number(value.number);
    case ValueKind::String:
      return "\"" + value.text + "\"";
    case ValueKind::Vector: {
      std::string out = "[";
      for (std::size_t i = 0; i < value.vector.size(); ++i)
        out += (i ? ", " : "") + format_number(value.vector[i]);
      return out + "]";
    }
    case ValueKind::Matrix: {
      std::string out = "[";
      for (std::size_t r = 0; r < value.matrix.size(); ++r) {
        out += r ? ", [" : "[";
        for (std::size_t i = 0; i < value.matrix[r].size(); ++i)
          out += (i ? ", " : "") + format_number(value.matrix[r][i]);
        out += "]";
      }
      return out + "]";
    }
  }
  return "";
}

void print(const Block& block, int depth, std::string& out) {
  const std::string indent(2 * depth, ' ');
  for (const auto& [is_block, index] : block.order) {
    if (is_block) {
      out += indent + block.blocks[index].name + "\n" + indent + "{\n";
      print(block.blocks[index], depth + 1, out);
      out += indent + "}\n";
    } else {
      const Parameter& p = block.parameters[index];
      out += indent + p.key + " = " + format_value(p.value) + "\n";
    }
  }
}

nlohmann::json value_json(const Value& value) {
  switch (value.kind) {
    case ValueKind::Number:
      return value.number;
    case ValueKind::String:
      return value.text;
    case ValueKind::Vector:
      return value.vector;
    case ValueKind::Matrix:
      return value.matrix;
  }
  return nullptr;
}

void flatten(const Block& block, const std::string& prefix, std::map<std::string, double>& out) {
  for (const auto& p : block.parameters) {
    if (p.value.kind == ValueKind::Number) out[prefix + p.key] = p.value.number;
  }
  std::map<std::string, int> seen;
  for (const auto& b : block.blocks) {
    const std::size_t count = block.children(b.name).size();
    const int index = seen[b.name]++;
    flatten(b, prefix + b.name + (count > 1 ? "[" + std::to_string(index) + "]" : "") + ".", out);
  }
}

Block evaluate_tree(RawBlock& root, const std::vector<Override>& overrides,
                    const std::string& file) {
  for (const auto& item : overrides)
    apply_override(root, item);
  Evaluator evaluator(root);
  const std::vector<std::string> problems = evaluator.run();
  if (!problems.empty()) {
    std::string text = std::to_string(problems.size()) + " problem(s) in the scene:";
    for (const auto& problem : problems)
      text += "\n  " + problem;
    throw Error(text, file, "correct the parameters named above");
  }
  Block result;
  convert(root, result);
  return result;
}

}  // namespace

std::string SourceLocation::text() const {
  if (line == 0) return file;
  return file + ":" + std::to_string(line) + ":" + std::to_string(column);
}

std::string_view name(ValueKind kind) {
  switch (kind) {
    case ValueKind::Number:
      return "number";
    case ValueKind::String:
      return "string";
    case ValueKind::Vector:
      return "vector";
    case ValueKind::Matrix:
      return "matrix";
  }
  return "?";
}

const Parameter* Block::find(std::string_view key) const {
  const Parameter* found = nullptr;
  for (const auto& p : parameters) {
    if (p.key == key) found = &p;
  }
  return found;
}

std::vector<const Block*> Block::children(std::string_view block_name) const {
  std::vector<const Block*> found;
  for (const auto& b : blocks) {
    if (b.name == block_name) found.push_back(&b);
  }
  return found;
}

const Block* Block::child(std::string_view block_name) const {
  for (const auto& b : blocks) {
    if (b.name == block_name) return &b;
  }
  return nullptr;
}

const Parameter* Block::lookup(std::string_view path) const {
  std::vector<PathPart> parts;
  if (!parse_path(path, parts)) return nullptr;
  const Block* block = this;
  for (std::size_t i = 0; i + 1 < parts.size(); ++i) {
    const auto candidates = block->children(parts[i].name);
    const int index = parts[i].index < 0 ? 0 : parts[i].index;
    if (index >= static_cast<int>(candidates.size())) return nullptr;
    block = candidates[index];
  }
  return block->find(parts.back().name);
}

Override parse_override(std::string_view text) {
  const std::size_t equals = text.find('=');
  if (equals == std::string_view::npos || equals == 0) {
    throw Error("'" + std::string(text) + "' is not KEY=EXPR", "--set",
                "write e.g. --set SolverOptions.end_time=0.05");
  }
  return {trim(text.substr(0, equals)), trim(text.substr(equals + 1))};
}

Block parse_parameter_text(const std::string& text, const std::string& file_name,
                           const std::vector<Override>& overrides) {
  RawBlock root;
  int sequence = 0;
  std::vector<std::string> include_stack{fs::weakly_canonical(file_name).string()};
  Parser parser(sequence, include_stack);
  parser.parse(text, file_name, root);
  return evaluate_tree(root, overrides, file_name);
}

Block load_parameter_file(const std::string& path, const std::vector<Override>& overrides) {
  std::ifstream in(path);
  if (!in) throw Error("cannot read scene file '" + path + "'", path, "check the path");
  std::stringstream content;
  content << in.rdbuf();
  return parse_parameter_text(content.str(), path, overrides);
}

std::string to_text(const Block& root) {
  std::string out;
  print(root, 0, out);
  return out;
}

nlohmann::json to_json(const Block& root) {
  nlohmann::json entries = nlohmann::json::array();
  for (const auto& [is_block, index] : root.order) {
    if (is_block) {
      nlohmann::json child = to_json(root.blocks[index]);
      child["kind"] = "block";
      child["name"] = root.blocks[index].name;
      entries.push_back(std::move(child));
    } else {
      const Parameter& p = root.parameters[index];
      entries.push_back({{"kind", "parameter"}, {"key", p.key}, {"value", value_json(p.value)}});
    }
  }
  return {{"entries", entries}};
}

std::map<std::string, double> flatten_numbers(const Block& root) {
  std::map<std::string, double> out;
  flatten(root, "", out);
  return out;
}

std::size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j)
    row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t above = row[j];
      const bool same = std::tolower(static_cast<unsigned char>(a[i - 1])) ==
                        std::tolower(static_cast<unsigned char>(b[j - 1]));
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (same ? 0 : 1)});
      diagonal = above;
    }
  }
  return row[b.size()];
}

std::string nearest(std::string_view word, const std::vector<std::string>& candidates) {
  const std::size_t limit = std::max<std::size_t>(2, word.size() / 3);
  std::string best;
  std::size_t best_distance = limit + 1;
  for (const auto& candidate : candidates) {
    const std::size_t d = edit_distance(word, candidate);
    if (d < best_distance) {
      best_distance = d;
      best = candidate;
    }
  }
  return best;
}

}  // namespace fsi::scene
