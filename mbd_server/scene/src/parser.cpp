// Text -> raw tree: blocks, parameters with their unevaluated expressions, includes. Stops at the
// first syntax error, since everything after it would be guesswork.

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "fsi/common/error.hpp"
#include "raw_tree.hpp"

namespace fsi::scene::detail {
namespace {

namespace fs = std::filesystem;

constexpr const char* kLanguageKey = "scene_language";

bool is_continuation_byte(char c) {
  return (static_cast<unsigned char>(c) & 0xC0U) == 0x80U;
}

std::string in_quotes(std::string_view text) {
  return "'" + std::string(text) + "'";
}

// What identifies a file on the include stack (for cycles): its canonical path on the file
// system; for files from a reader, its normalized path, so that nothing on disk is looked at.
std::string identity_of(const std::string& path, const IncludeReader& read_include) {
  if (read_include) return fs::path(path).lexically_normal().string();
  std::error_code ignored;
  return fs::weakly_canonical(path, ignored).string();
}

class Parser {
 public:
  Parser(int& sequence, std::vector<std::string>& include_stack, std::string included_from,
         const IncludeReader& read_include)
      : sequence_(sequence),
        include_stack_(include_stack),
        included_from_(std::move(included_from)),
        read_include_(read_include) {}

  void parse_file(RawBlock& into, const std::string& text, const std::string& file) {
    text_ = &text;
    file_ = file;
    position_ = 0;
    line_ = 1;
    line_start_ = 0;
    entries_ = 0;
    parse_entries(into, nullptr);
  }

 private:
  // ---- scanning ----
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
  SourceLocation here() const {
    // Columns count characters, not bytes, so a UTF-8 comment earlier on the line is harmless.
    int column = 1;
    for (std::size_t i = line_start_; i < position_; ++i) {
      if (!is_continuation_byte((*text_)[i])) ++column;
    }
    return {file_, line_, column};
  }
  bool at_comment() const { return peek() == '%' || (peek() == '/' && peek(1) == '/'); }
  void skip_comment() {
    while (!at_end() && peek() != '\n')
      advance();
  }
  void skip_blanks() {
    while (peek() == ' ' || peek() == '\t' || peek() == '\r')
      advance();
  }
  // Between entries: blanks, line breaks, ';' and comments.
  void skip_separators() {
    while (!at_end()) {
      if (std::isspace(static_cast<unsigned char>(peek())) || peek() == ';') {
        advance();
      } else if (at_comment()) {
        skip_comment();
      } else {
        return;
      }
    }
  }
  // Between a name and its '{' or '=': the brace may sit on the next line, after a comment.
  void skip_layout() {
    while (!at_end()) {
      if (std::isspace(static_cast<unsigned char>(peek()))) {
        advance();
      } else if (at_comment()) {
        skip_comment();
      } else {
        return;
      }
    }
  }

  [[noreturn]] void fail(const SourceLocation& where, const std::string& what,
                         const std::string& fix) const {
    std::string place = where.text();
    if (!included_from_.empty()) place += " (included from " + included_from_ + ")";
    throw Error(what, place, fix);
  }

  // A key or block name: identifiers joined by '.', each optionally indexed as Name[3].
  std::string read_path(const SourceLocation& start) {
    std::string path;
    while (true) {
      while (is_identifier_char(peek())) {
        path += peek();
        advance();
      }
      if (peek() == '[') {
        path += '[';
        advance();
        while (std::isdigit(static_cast<unsigned char>(peek()))) {
          path += peek();
          advance();
        }
        if (peek() != ']' || path.back() == '[') {
          fail(here(), "'" + path + "' is not a valid name: an index is a whole number in [ ]",
               "write e.g. Body[1].mass (0-based)");
        }
        path += ']';
        advance();
      }
      if (peek() == '.' && is_identifier_start(peek(1))) {
        path += '.';
        advance();
        continue;
      }
      if (peek() == '.') {
        fail(start, in_quotes(path + ".") + " is not a valid name",
             "names are letters, digits and '_', joined by '.'");
      }
      return path;
    }
  }

  // ---- grammar ----
  void parse_entries(RawBlock& block, const SourceLocation* opened_at) {
    while (true) {
      skip_separators();
      if (at_end()) {
        if (opened_at) {
          fail(*opened_at,
               "block " + in_quotes(block.name) + " is not closed: the file ends inside it",
               "add the missing '}'");
        }
        return;
      }
      if (peek() == '}') {
        if (!opened_at) {
          fail(here(), "'}' without an open block", "remove it, or open a block above with Name {");
        }
        advance();
        return;
      }
      const SourceLocation start = here();
      if (!is_identifier_start(peek())) {
        fail(start, std::string("unexpected '") + peek() + "'",
             "an entry is 'key = expression', 'Block { ... }' or 'include \"file\"'");
      }
      const std::string path = read_path(start);
      ++entries_;
      if (path == kLanguageKey) {
        parse_language_version(block, start, opened_at != nullptr);
        continue;
      }
      if (path == "include") {
        parse_include(block, start);
        continue;
      }
      skip_layout();
      if (peek() == '{') {
        if (path.find_first_of(".[") != std::string::npos) {
          fail(start, "a block name cannot contain '.' or '[': " + in_quotes(path),
               "nest the blocks instead: A { B { ... } }");
        }
        advance();
        RawBlock& child = open_block(block, path, start);
        parse_entries(child, &start);
      } else if (peek() == '=') {
        advance();
        parse_parameter(block, path, start);
      } else {
        fail(start, in_quotes(path) + " is followed by neither '=' nor '{'",
             "write '" + path + " = expression' for a parameter or '" + path +
                 " { ... }' for a block");
      }
    }
  }

  RawBlock& open_block(RawBlock& parent, const std::string& name, const SourceLocation& where) {
    for (const auto& parameter : parent.parameters) {
      if (parameter->key == name) {
        fail(where,
             in_quotes(name) + " is already a parameter of this block (" +
                 parameter->location.text() + ")",
             "give the block and the parameter different names");
      }
    }
    // `Newton.max_iterations = 40` followed by `Newton { ... }` means one block, not a list.
    const std::vector<RawBlock*> existing = parent.children(name);
    if (!existing.empty() && existing.back()->implicit) {
      existing.back()->implicit = false;
      existing.back()->location = where;
      return *existing.back();
    }
    return parent.add_block(name, where);
  }

  // The block a dotted key assigns in; blocks it names are created if absent.
  RawBlock& target_of(RawBlock& block, const std::vector<PathPart>& parts,
                      const SourceLocation& start) {
    RawBlock* target = &block;
    for (std::size_t i = 0; i + 1 < parts.size(); ++i) {
      const PathPart& part = parts[i];
      const std::vector<RawBlock*> candidates = target->children(part.name);
      if (part.index >= 0) {
        if (part.index >= static_cast<int>(candidates.size())) {
          fail(start,
               in_quotes(to_string(parts, i + 1)) +
                   " does not exist: " + std::to_string(candidates.size()) + " block(s) " +
                   in_quotes(part.name) + " are defined above this line",
               candidates.empty() ? "define the block first"
                                  : "use an index from 0 to " +
                                        std::to_string(candidates.size() - 1) + " (0-based)");
        }
        target = candidates[static_cast<std::size_t>(part.index)];
      } else if (candidates.size() > 1) {
        fail(start,
             in_quotes(part.name) + " is a list of " + std::to_string(candidates.size()) +
                 " blocks, so " + in_quotes(to_string(parts, parts.size())) + " is ambiguous",
             "write " + part.name + "[0]." + parts[i + 1].name + " ... " + part.name + "[" +
                 std::to_string(candidates.size() - 1) + "]." + parts[i + 1].name +
                 ", or put the entry inside the block");
      } else if (candidates.size() == 1) {
        target = candidates.front();
      } else {
        for (const auto& parameter : target->parameters) {
          if (parameter->key == part.name) {
            fail(start,
                 in_quotes(part.name) + " is a parameter (" + parameter->location.text() +
                     "), not a block",
                 "rename one of them");
          }
        }
        target = &target->add_block(part.name, start);
        target->implicit = true;
      }
    }
    return *target;
  }

  void parse_parameter(RawBlock& block, const std::string& path, const SourceLocation& start) {
    std::vector<PathPart> parts;
    if (!parse_path(path, parts)) {
      fail(start, in_quotes(path) + " is not a valid key", "names are letters, digits and '_'");
    }
    if (parts.back().index >= 0) {
      fail(start, "only blocks take an index, not the parameter " + in_quotes(path),
           "write the key without [...]");
    }
    skip_blanks();
    const SourceLocation expression_start = here();
    std::string expression;
    struct OpenBracket {
      char symbol;
      SourceLocation where;
    };
    std::vector<OpenBracket> open;
    while (!at_end()) {
      const char c = peek();
      if (c == '"') {
        const SourceLocation string_start = here();
        expression += c;
        advance();
        while (!at_end() && peek() != '"' && peek() != '\n') {
          expression += peek();
          advance();
        }
        if (peek() != '"') {
          fail(string_start, "the string is not closed on its line", "add the closing '\"'");
        }
        expression += '"';
        advance();
        continue;
      }
      if (at_comment()) {
        if (open.empty()) break;
        // Inside brackets a comment is blanked, keeping every character's column.
        while (!at_end() && peek() != '\n') {
          expression += ' ';
          advance();
        }
        continue;
      }
      if (open.empty() && (c == '\n' || c == ';' || c == '}')) break;
      if (c == '{' || c == '}') {
        fail(open.empty() ? here() : open.back().where,
             open.empty()
                 ? "'{' inside an expression"
                 : std::string("'") + open.back().symbol + "' is not closed before '" + c + "'",
             open.empty() ? "a block is written Name { ... }, a parameter key = expression"
                          : std::string("add the missing '") +
                                (open.back().symbol == '[' ? ']' : ')') + "'");
      }
      if (c == '[' || c == '(') open.push_back({c, here()});
      if (c == ']' || c == ')') {
        const char expected = c == ']' ? '[' : '(';
        if (open.empty()) {
          fail(here(), std::string("'") + c + "' without a matching '" + expected + "'",
               "remove it, or add the opening bracket");
        }
        if (open.back().symbol != expected) {
          fail(here(),
               std::string("'") + c + "' does not match the '" + open.back().symbol +
                   "' opened at " + open.back().where.text(),
               "close '[' with ']' and '(' with ')'");
        }
        open.pop_back();
      }
      expression += c;
      advance();
    }
    if (!open.empty()) {
      fail(open.back().where,
           std::string("'") + open.back().symbol + "' is not closed: the file ends inside it",
           std::string("add the missing '") + (open.back().symbol == '[' ? ']' : ')') + "'");
    }
    while (!expression.empty() && std::isspace(static_cast<unsigned char>(expression.back())))
      expression.pop_back();
    if (expression.empty()) {
      fail(start, in_quotes(path) + " has no value after '='",
           "write " + path + " = expression (the expression starts on the same line)");
    }

    RawBlock& target = target_of(block, parts, start);
    const std::string& key = parts.back().name;
    if (!target.children(key).empty()) {
      fail(start,
           in_quotes(key) + " is already a block here (" +
               target.children(key).front()->location.text() + ")",
           "give the parameter and the block different names");
    }
    auto parameter = std::make_unique<RawParameter>();
    parameter->key = key;
    parameter->location = start;
    parameter->expression = std::move(expression);
    parameter->expression_location = expression_start;
    parameter->sequence = ++sequence_;
    parameter->block = &target;
    target.add_parameter(std::move(parameter));
  }

  // `scene_language = N`: read before anything else of the file, so that a file written for a
  // newer language is refused with that reason, not with a syntax error of the newer syntax.
  void parse_language_version(RawBlock& block, const SourceLocation& start, bool in_block) {
    const std::string line = "scene_language = " + std::to_string(kSceneLanguageVersion);
    if (in_block || entries_ != 1) {
      fail(start, "scene_language must be the first entry of its file, outside any block",
           "move '" + line + "' to the top of the file (comments may stand above it)");
    }
    skip_blanks();
    if (peek() != '=') fail(here(), "scene_language is followed by no '='", "write " + line);
    advance();
    skip_blanks();
    const SourceLocation number_at = here();
    std::string digits;
    while (std::isdigit(static_cast<unsigned char>(peek())) && digits.size() < 9) {
      digits += peek();
      advance();
    }
    skip_blanks();
    if (digits.empty() || !(at_end() || peek() == '\n' || peek() == ';' || at_comment())) {
      fail(number_at, "scene_language takes a whole number written out (no expression)",
           "write " + line);
    }
    const long version = std::stol(digits);
    if (version < 1) fail(number_at, "scene language versions start at 1", "write " + line);
    if (version > kSceneLanguageVersion) {
      fail(number_at,
           "the file is written for scene language version " + digits +
               ", this program reads version " + std::to_string(kSceneLanguageVersion) +
               (kSceneLanguageVersion > 1 ? " and older" : std::string()),
           "use an fsi-server that reads version " + digits + ", or rewrite the file for version " +
               std::to_string(kSceneLanguageVersion) +
               " (docs/user-guide.md, \"Scene language versions\")");
    }
    if (&block == root_of(block) && include_depth() == 0) {
      block.language_version = version;
      block.language_version_location = start;
    }
  }

  static const RawBlock* root_of(const RawBlock& block) {
    const RawBlock* root = &block;
    while (root->parent)
      root = root->parent;
    return root;
  }
  std::size_t include_depth() const { return include_stack_.size() - 1; }

  void parse_include(RawBlock& block, const SourceLocation& start) {
    skip_blanks();
    if (peek() != '"') {
      fail(here(), "include needs a file name in double quotes",
           "write include \"file.scene\" ('include' cannot be used as a key)");
    }
    advance();
    std::string name;
    while (!at_end() && peek() != '"' && peek() != '\n') {
      name += peek();
      advance();
    }
    if (peek() != '"') fail(start, "the include file name is not closed", "add the closing '\"'");
    advance();
    if (name.empty()) fail(start, "include names no file", "write include \"file.scene\"");

    fs::path path = name;
    if (path.is_relative()) path = fs::path(file_).parent_path() / path;
    path = path.lexically_normal();
    const std::string identity = identity_of(path.string(), read_include_);
    const auto repeat = std::find(include_stack_.begin(), include_stack_.end(), identity);
    if (repeat != include_stack_.end()) {
      std::string chain;
      for (auto it = repeat; it != include_stack_.end(); ++it)
        chain += fs::path(*it).filename().string() + " -> ";
      fail(start,
           "include cycle: " + chain + fs::path(identity).filename().string() +
               " (the file is already being read)",
           "remove the include that closes the cycle");
    }
    const std::optional<std::string> text =
        read_include_ ? read_include_(path.string()) : read_regular_file(path.string());
    if (!text) {
      fail(start, "cannot read the included file '" + path.string() + "'",
           "check the name (it must be a readable regular file, not a folder or a device); a "
           "relative path starts at the folder of the including file");
    }

    include_stack_.push_back(identity);
    std::string chain = start.text();
    if (!included_from_.empty()) chain += ", included from " + included_from_;
    Parser nested(sequence_, include_stack_, chain, read_include_);
    nested.parse_file(block, *text, path.string());
    include_stack_.pop_back();
  }

  int& sequence_;
  std::vector<std::string>& include_stack_;
  std::string included_from_;
  const IncludeReader& read_include_;
  const std::string* text_ = nullptr;
  std::string file_;
  std::size_t position_ = 0;
  int line_ = 1;
  std::size_t line_start_ = 0;
  int entries_ = 0;  // entries of this file so far (nested ones included)
};

}  // namespace

bool is_identifier_start(char c) {
  return std::isalpha(static_cast<unsigned char>(c)) || c == '_';
}

bool is_identifier_char(char c) {
  return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
}

std::vector<RawBlock*> RawBlock::children(std::string_view child_name) const {
  std::vector<RawBlock*> found;
  for (const auto& child : blocks) {
    if (child->name == child_name) found.push_back(child.get());
  }
  return found;
}

RawBlock& RawBlock::add_block(std::string child_name, SourceLocation where) {
  auto child = std::make_unique<RawBlock>();
  child->name = std::move(child_name);
  child->location = std::move(where);
  child->parent = this;
  blocks.push_back(std::move(child));
  entries.push_back({true, blocks.size() - 1});
  return *blocks.back();
}

RawParameter& RawBlock::add_parameter(std::unique_ptr<RawParameter> parameter) {
  parameters.push_back(std::move(parameter));
  entries.push_back({false, parameters.size() - 1});
  return *parameters.back();
}

SourceLocation RawParameter::location_at(std::size_t offset) const {
  if (!override_label.empty()) return {override_label, 0, 0};
  SourceLocation where = expression_location;
  for (std::size_t i = 0; i < offset && i < expression.size(); ++i) {
    if (expression[i] == '\n') {
      ++where.line;
      where.column = 1;
    } else if (!is_continuation_byte(expression[i])) {
      ++where.column;
    }
  }
  return where;
}

bool parse_path(std::string_view path, std::vector<PathPart>& parts) {
  parts.clear();
  std::size_t i = 0;
  while (true) {
    if (i >= path.size() || !is_identifier_start(path[i])) return false;
    PathPart part;
    while (i < path.size() && is_identifier_char(path[i]))
      part.name += path[i++];
    if (i < path.size() && path[i] == '[') {
      const std::size_t digits = ++i;
      int index = 0;
      while (i < path.size() && std::isdigit(static_cast<unsigned char>(path[i]))) {
        if (index > 1'000'000) return false;
        index = 10 * index + (path[i++] - '0');
      }
      if (i == digits || i >= path.size() || path[i] != ']') return false;
      ++i;
      part.index = index;
    }
    parts.push_back(std::move(part));
    if (i == path.size()) return true;
    if (path[i] != '.') return false;
    ++i;
  }
}

std::string to_string(const std::vector<PathPart>& parts, std::size_t count) {
  std::string text;
  for (std::size_t i = 0; i < count && i < parts.size(); ++i) {
    if (i > 0) text += '.';
    text += parts[i].name;
    if (parts[i].index >= 0) text += "[" + std::to_string(parts[i].index) + "]";
  }
  return text;
}

void collect_paths(const RawBlock& block, const std::string& prefix,
                   std::vector<std::string>& paths) {
  for (const auto& parameter : block.parameters) {
    const std::string path = prefix + parameter->key;
    if (std::find(paths.begin(), paths.end(), path) == paths.end()) paths.push_back(path);
  }
  std::vector<std::string> seen;
  for (const auto& child : block.blocks) {
    const std::size_t count = block.children(child->name).size();
    const auto index = static_cast<std::size_t>(std::count(seen.begin(), seen.end(), child->name));
    seen.push_back(child->name);
    const std::string name =
        count > 1 ? child->name + "[" + std::to_string(index) + "]" : child->name;
    collect_paths(*child, prefix + name + ".", paths);
  }
}

void parse_into(RawBlock& root, const std::string& text, const std::string& file_name,
                const IncludeReader& read_include) {
  int sequence = 0;
  std::vector<std::string> include_stack{identity_of(file_name, read_include)};
  Parser parser(sequence, include_stack, "", read_include);
  parser.parse_file(root, text, file_name);
}

std::optional<std::string> read_regular_file(const std::string& path) {
  std::error_code error;
  if (!fs::is_regular_file(path, error)) return std::nullopt;
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;
  std::stringstream content;
  content << in.rdbuf();
  return content.str();
}

}  // namespace fsi::scene::detail
