// Raw tree -> values. Parameters are evaluated in textual order, so every reference either finds
// an earlier, already evaluated parameter or is an error; all errors are collected. Numbers go
// through muParser, whose variable factory resolves names against the tree.

#include <muParser.h>

#include <algorithm>
#include <cmath>
#include <deque>
#include <numbers>

#include "fsi/common/error.hpp"
#include "raw_tree.hpp"
#include "runtime_expression.hpp"

namespace fsi::scene::detail {
namespace {

constexpr const char* kFunctionsHint =
    "check operators, parentheses and function names (sin, cos, tan, asin, acos, atan, sqrt, exp, "
    "ln, log10, abs, min, max, ...)";

std::string in_quotes(std::string_view text) {
  return "'" + std::string(text) + "'";
}

bool is_blank(char c) {
  return c == ' ' || c == '\t' || c == '\n' || c == '\r';
}

// Characters muParser accepts in a variable name once '.' and indices are allowed.
bool is_name_char(char c) {
  return is_identifier_char(c) || c == '.' || c == '[' || c == ']';
}

// The end of a reference path starting at `begin` (Name, Name[2], A.B.c), or `begin` if none.
std::size_t reference_end(const std::string& text, std::size_t begin, std::size_t end) {
  std::size_t i = begin;
  while (i < end && is_identifier_start(text[i])) {
    while (i < end && is_identifier_char(text[i]))
      ++i;
    if (i < end && text[i] == '[') {
      std::size_t j = i + 1;
      while (j < end && std::isdigit(static_cast<unsigned char>(text[j])))
        ++j;
      if (j == i + 1 || j >= end || text[j] != ']') return begin;
      i = j + 1;
    }
    if (i + 1 < end && text[i] == '.' && is_identifier_start(text[i + 1])) {
      ++i;
      continue;
    }
    return i;
  }
  return begin;
}

// The index of the bracket closing the one at `open`, or npos.
std::size_t matching_bracket(const std::string& text, std::size_t open, std::size_t end) {
  int depth = 0;
  bool in_string = false;
  for (std::size_t i = open; i < end; ++i) {
    const char c = text[i];
    if (c == '"') in_string = !in_string;
    if (in_string) continue;
    if (c == '[' || c == '(') ++depth;
    if (c == ']' || c == ')') {
      if (--depth == 0) return i;
    }
  }
  return std::string::npos;
}

struct Range {
  std::size_t begin = 0;
  std::size_t end = 0;
  bool empty() const { return begin == end; }
};

Range trimmed(const std::string& text, std::size_t begin, std::size_t end) {
  while (begin < end && is_blank(text[begin]))
    ++begin;
  while (end > begin && is_blank(text[end - 1]))
    --end;
  return {begin, end};
}

// The comma-separated items between the brackets at `open` and `close`.
std::vector<Range> split_items(const std::string& text, std::size_t open, std::size_t close) {
  std::vector<Range> items;
  int depth = 0;
  std::size_t start = open + 1;
  for (std::size_t i = open + 1; i < close; ++i) {
    if (text[i] == '[' || text[i] == '(') ++depth;
    if (text[i] == ']' || text[i] == ')') --depth;
    if (text[i] == ',' && depth == 0) {
      items.push_back(trimmed(text, start, i));
      start = i + 1;
    }
  }
  items.push_back(trimmed(text, start, close));
  return items;
}

// Dotted path of a parameter for messages, with [i] for blocks that repeat.
std::string path_of(const RawParameter& parameter) {
  std::string path = parameter.key;
  for (const RawBlock* block = parameter.block; block && block->parent; block = block->parent) {
    const std::vector<RawBlock*> siblings = block->parent->children(block->name);
    std::string name = block->name;
    if (siblings.size() > 1) {
      const auto index = std::find(siblings.begin(), siblings.end(), block) - siblings.begin();
      name += "[" + std::to_string(index) + "]";
    }
    path = name + "." + path;
  }
  return path;
}

// The "pick one: Name[0].x ... Name[n-1].x" of a path through a block list without an index.
std::string pick_one(const std::vector<PathPart>& parts, std::size_t at, std::size_t count) {
  const std::string rest = to_string(parts, parts.size()).substr(to_string(parts, at + 1).size());
  return "pick one: " + parts[at].name + "[0]" + rest + " ... " + parts[at].name + "[" +
         std::to_string(count - 1) + "]" + rest;
}

// The known path nearest to `path`, else one that ends in the same name ("offset_x" when only
// "Geometry.offset_x" exists), else "".
std::string suggestion_for(std::string_view path, const std::string& name,
                           const std::vector<std::string>& known) {
  std::string suggestion = nearest(path, known);
  if (!suggestion.empty()) return suggestion;
  for (const std::string& candidate : known) {
    const std::size_t dot = candidate.rfind('.');
    if (candidate.substr(dot == std::string::npos ? 0 : dot + 1) == name) return candidate;
  }
  return "";
}

class Evaluator {
 public:
  explicit Evaluator(RawBlock& root) : root_(root) {
    parser_.DefineNameChars("0123456789_abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ.[]");
    parser_.DefineConst("pi", std::numbers::pi);
    parser_.DefineConst("e", std::numbers::e);
    parser_.SetVarFactory(&Evaluator::on_variable, this);
  }

  std::vector<Problem> run() {
    std::vector<RawParameter*> all;
    collect(root_, all);
    std::sort(all.begin(), all.end(), [](const RawParameter* a, const RawParameter* b) {
      return a->sequence < b->sequence;
    });
    for (RawParameter* parameter : all)
      evaluate(*parameter);
    report_stale_uses();
    return std::move(problems_);
  }

 private:
  struct Resolution {
    RawParameter* parameter = nullptr;  // set when found
    std::string message;                // otherwise why not
    std::string fix;
    bool silent = false;  // part of a cycle reported already: fail without a second report
  };

  static void collect(RawBlock& block, std::vector<RawParameter*>& all) {
    for (auto& parameter : block.parameters)
      all.push_back(parameter.get());
    for (auto& child : block.blocks)
      collect(*child, all);
  }

  void report(const RawParameter& parameter, std::size_t offset, const std::string& message,
              const std::string& fix) {
    problems_.push_back({parameter.location_at(offset),
                         "in " + in_quotes(path_of(parameter)) + ": " + message, fix});
  }

  // ---- name resolution ----

  // What `parts` names when seen from `scope`; an empty Resolution means "not in this scope".
  Resolution resolve_in(RawBlock& scope, const std::vector<PathPart>& parts,
                        const RawParameter& from, const RawParameter*& later) {
    RawBlock* block = &scope;
    for (std::size_t i = 0; i + 1 < parts.size(); ++i) {
      const std::vector<RawBlock*> candidates = block->children(parts[i].name);
      const std::string prefix = to_string(parts, i + 1);
      if (candidates.empty()) {
        if (i == 0) return {};
        std::vector<std::string> names;
        for (const auto& child : block->blocks)
          names.push_back(child->name);
        const std::string suggestion = nearest(parts[i].name, names);
        return {
            nullptr,
            "block " + in_quotes(to_string(parts, i)) + " has no block " + in_quotes(parts[i].name),
            suggestion.empty() ? "check the path" : "did you mean " + in_quotes(suggestion) + "?"};
      }
      if (parts[i].index >= static_cast<int>(candidates.size())) {
        return {nullptr,
                in_quotes(prefix) + " does not exist: there are " +
                    std::to_string(candidates.size()) + " " + in_quotes(parts[i].name) + " blocks",
                "use an index from 0 to " + std::to_string(candidates.size() - 1) + " (0-based)"};
      }
      if (parts[i].index < 0 && candidates.size() > 1) {
        return {nullptr,
                in_quotes(parts[i].name) + " is a list of " + std::to_string(candidates.size()) +
                    " blocks",
                pick_one(parts, i, candidates.size())};
      }
      block = candidates[parts[i].index < 0 ? 0 : static_cast<std::size_t>(parts[i].index)];
    }
    const PathPart& last = parts.back();
    if (last.index >= 0) {
      return {nullptr,
              "only blocks take an index, not " + in_quotes(to_string(parts, parts.size())),
              "remove the [...] after " + in_quotes(last.name)};
    }
    RawParameter* found = nullptr;
    const RawParameter* after_use = nullptr;  // the first assignment after the reference
    for (auto& candidate : block->parameters) {
      if (candidate->key != last.name || candidate.get() == &from) continue;
      if (candidate->sequence < from.sequence) {
        found = candidate.get();  // the latest assignment before the reference counts
      } else {
        if (!later) later = candidate.get();
        if (!after_use) after_use = candidate.get();
      }
    }
    if (found) {
      if (after_use) note_stale_use(from, *found, *after_use);
      return {found, "", ""};
    }
    if (parts.size() == 1) {
      if (!block->children(last.name).empty()) {
        return {nullptr, in_quotes(last.name) + " is a block, not a number",
                "reference one of its parameters, e.g. " + last.name + ".key"};
      }
      return {};
    }
    if (later) return {};
    std::vector<std::string> keys;
    for (const auto& candidate : block->parameters) {
      if (candidate->sequence < from.sequence) keys.push_back(candidate->key);
    }
    const std::string suggestion = nearest(last.name, keys);
    return {nullptr,
            "block " + in_quotes(to_string(parts, parts.size() - 1)) + " has no parameter " +
                in_quotes(last.name) + " defined before this line",
            suggestion.empty()
                ? "check the name"
                : "did you mean " +
                      in_quotes(to_string(parts, parts.size() - 1) + "." + suggestion) + "?"};
  }

  // Whether `from`'s key has an earlier assignment in `block` (then suggesting it makes sense).
  static bool assigned_before(const RawBlock& block, const RawParameter& from) {
    return std::any_of(block.parameters.begin(), block.parameters.end(), [&](const auto& other) {
      return other->key == from.key && other->sequence < from.sequence;
    });
  }

  // Parameters visible from `from`, as the paths one would write there, for suggestions.
  std::vector<std::string> visible_names(const RawParameter& from) const {
    std::vector<std::string> names;
    for (const RawBlock* scope = from.block; scope; scope = scope->parent) {
      std::vector<std::string> paths;
      collect_paths(*scope, "", paths);
      for (std::string& path : paths) {
        if (scope == from.block && path == from.key && !assigned_before(*scope, from)) continue;
        names.push_back(std::move(path));
      }
    }
    return names;
  }

  Resolution resolve(std::string_view path, const RawParameter& from) {
    std::vector<PathPart> parts;
    if (!parse_path(path, parts)) {
      return {nullptr, in_quotes(path) + " is not a parameter name",
              "vectors and matrices cannot take part in arithmetic; names are letters, digits, "
              "'_' and '.'"};
    }
    const RawParameter* later = nullptr;
    Resolution first_problem;
    for (RawBlock* scope = from.block; scope; scope = scope->parent) {
      Resolution found = resolve_in(*scope, parts, from, later);
      if (found.parameter) return found;
      if (first_problem.message.empty()) first_problem = std::move(found);
    }
    if (later) {
      std::vector<const RawParameter*> chain{&from};
      std::vector<const RawParameter*> visited;
      if (leads_back(*later, from, chain, visited)) {
        if (std::find(cycle_members_.begin(), cycle_members_.end(), &from) !=
            cycle_members_.end()) {
          return {nullptr, "", "", true};
        }
        cycle_members_.insert(cycle_members_.end(), chain.begin(), chain.end());
        std::string text;
        for (const RawParameter* step : chain)
          text += path_of(*step) + " -> ";
        text += path_of(from);
        return {nullptr,
                in_quotes(path) + " is defined later (" + later->location.text() +
                    ") and depends on " + in_quotes(from.key) + " itself: a cycle " + text,
                "break the cycle: give one of them a value that does not depend on the other"};
      }
      const bool same_file = later->location.file == from.location.file;
      const std::string use =
          same_file ? "line " + std::to_string(from.location.line) : from.location.text();
      return {nullptr, in_quotes(path) + " is defined later, at " + later->location.text(),
              from.override_label.empty()
                  ? "move it above " + use + ": a reference sees only parameters defined earlier"
                  : "an override sees only parameters defined above the overridden one (" +
                        from.location.text() + ")"};
    }
    if (!first_problem.message.empty()) return first_problem;
    const std::string suggestion = suggestion_for(path, parts.back().name, visible_names(from));
    std::string remedy = suggestion.empty()
                             ? "define it above this line (a name is looked up in its block, "
                               "then in the blocks around it)"
                             : "did you mean " + in_quotes(suggestion) + "?";
    // `--set Block.key=word`: the shell ate the quotes of a text value.
    if (!from.override_label.empty() && parts.size() == 1)
      remedy += "; a text value keeps its quotes through the shell: --set '" + path_of(from) +
                "=\"" + std::string(path) + "\"'";
    return {nullptr, in_quotes(path) + " is not defined", remedy};
  }

  // ---- uses of a value assigned again later ----

  // A reference sees the value assigned before it; an assignment after it (e.g. `Geometry.x = 2`
  // below an `include` that used Geometry.x) does not reach it, while the run records the last
  // value: the scene would silently run with another value than it lists.
  struct StaleUse {
    const RawParameter* use;
    const RawParameter* seen;
    const RawParameter* reassigned;
  };

  void note_stale_use(const RawParameter& use, const RawParameter& seen,
                      const RawParameter& reassigned) {
    const bool known = std::any_of(stale_uses_.begin(), stale_uses_.end(), [&](const StaleUse& s) {
      return s.use == &use && s.seen == &seen;
    });
    if (!known) stale_uses_.push_back({&use, &seen, &reassigned});
  }

  void report_stale_uses() {
    for (const StaleUse& stale : stale_uses_) {
      // The same value assigned again changes nothing the run uses.
      if (stale.seen->state == RawParameter::State::Done &&
          stale.reassigned->state == RawParameter::State::Done &&
          stale.seen->value == stale.reassigned->value) {
        continue;
      }
      const std::string name = path_of(*stale.seen);
      problems_.push_back({stale.use->location,
                           "in " + in_quotes(path_of(*stale.use)) + ": " + in_quotes(name) +
                               " is assigned again at " + stale.reassigned->location.text() +
                               ", after this use: the use takes the value of " +
                               stale.seen->location.text() +
                               ", while the scene records the later one",
                           "assign " + name +
                               " once, before its first use; to change a value of an included "
                               "file, give it with --set " +
                               name + "=... (it replaces the value everywhere)"});
    }
  }

  // ---- cycles ----

  // The parameter `path` names when seen from `from`, ignoring textual order (the last
  // assignment in the first scope that has it), or nullptr.
  static const RawParameter* resolve_any(std::string_view path, const RawParameter& from) {
    std::vector<PathPart> parts;
    if (!parse_path(path, parts)) return nullptr;
    for (const RawBlock* scope = from.block; scope; scope = scope->parent) {
      const RawBlock* block = scope;
      for (std::size_t i = 0; block && i + 1 < parts.size(); ++i) {
        const std::vector<RawBlock*> candidates = block->children(parts[i].name);
        const std::size_t index = parts[i].index < 0 ? 0 : static_cast<std::size_t>(parts[i].index);
        block = index < candidates.size() ? candidates[index] : nullptr;
      }
      if (!block) continue;
      const RawParameter* found = nullptr;
      for (const auto& candidate : block->parameters) {
        if (candidate->key == parts.back().name && candidate.get() != &from)
          found = candidate.get();
      }
      if (found) return found;
    }
    return nullptr;
  }

  // The names `parameter` refers to (outside strings; function names excluded).
  static std::vector<std::string> references_of(const RawParameter& parameter) {
    const std::string& text = parameter.expression;
    std::vector<std::string> names;
    bool in_string = false;
    for (std::size_t i = 0; i < text.size();) {
      if (text[i] == '"') in_string = !in_string;
      const bool starts =
          !in_string && is_identifier_start(text[i]) && (i == 0 || !is_name_char(text[i - 1]));
      if (!starts) {
        ++i;
        continue;
      }
      std::size_t end = reference_end(text, i, text.size());
      if (end == i) {
        ++i;
        continue;
      }
      std::size_t next = end;
      while (next < text.size() && is_blank(text[next]))
        ++next;
      if (next >= text.size() || text[next] != '(') names.push_back(text.substr(i, end - i));
      i = end;
    }
    return names;
  }

  // Whether `at` depends (through references, in any order) on `target`; `chain` collects the
  // way there.
  static bool leads_back(const RawParameter& at, const RawParameter& target,
                         std::vector<const RawParameter*>& chain,
                         std::vector<const RawParameter*>& visited) {
    if (&at == &target) return true;
    if (std::find(visited.begin(), visited.end(), &at) != visited.end()) return false;
    visited.push_back(&at);
    chain.push_back(&at);
    for (const std::string& name : references_of(at)) {
      const RawParameter* next = resolve_any(name, at);
      if (next && leads_back(*next, target, chain, visited)) return true;
    }
    chain.pop_back();
    return false;
  }

  // ---- numbers through muParser ----

  // Calls visit(begin, end) for each name as muParser splits names in the scalar being
  // evaluated, from `from` on, until visit returns true; whether it did.
  template <class Visit>
  bool scan_names(std::size_t from, Visit visit) const {
    const std::string& text = *text_;
    for (std::size_t i = from; i < scalar_.end;) {
      if (!is_name_char(text[i])) {
        ++i;
        continue;
      }
      std::size_t j = i;
      while (j < scalar_.end && is_name_char(text[j]))
        ++j;
      if (visit(i, j)) return true;
      i = j;
    }
    return false;
  }

  // Where the name `name` occurs in the expression being evaluated: muParser asks for names in
  // their order, so the search goes on after the last one found, then from the start.
  std::size_t locate(std::string_view name) {
    std::size_t found = scalar_.begin;
    auto match = [&](std::size_t begin, std::size_t end) {
      if (std::string_view(*text_).substr(begin, end - begin) != name) return false;
      cursor_ = end;
      found = begin;
      return true;
    };
    if (!scan_names(cursor_, match)) scan_names(scalar_.begin, match);
    return found;
  }

  static double* on_variable(const char* name, void* self) {
    return static_cast<Evaluator*>(self)->variable(name);
  }

  double* variable(std::string_view name) {
    slots_.push_back(std::nan(""));
    double* slot = &slots_.back();
    const std::size_t offset = locate(name);
    const Resolution found = resolve(name, *current_);
    if (found.silent) {
      dependency_failed_ = true;
    } else if (!found.parameter) {
      // A name before "(" is a call: muParser asked for it as a variable because it knows no
      // function of that name.
      std::size_t next = offset + name.size();
      while (next < scalar_.end && is_blank((*text_)[next]))
        ++next;
      const std::string functions = std::string(" ") + kFunctionList + " ";
      const bool known = functions.find(" " + std::string(name) + " ") != std::string::npos;
      if (next < scalar_.end && (*text_)[next] == '(' && known) {
        pending_.push_back({offset, in_quotes(name) + " is followed by a blank before its '('",
                            "write " + std::string(name) + "(...) without the blank"});
      } else if (next < scalar_.end && (*text_)[next] == '(') {
        pending_.push_back({offset, in_quotes(name) + " is not a function of the scene language",
                            std::string("use one of ") + kFunctionList +
                                (name == "round" ? "; round(x) is rint(x)" : "")});
      } else {
        pending_.push_back({offset, found.message, found.fix});
      }
    } else if (found.parameter->state != RawParameter::State::Done) {
      dependency_failed_ = true;  // its own error is reported already
    } else if (found.parameter->value.kind != ValueKind::Number) {
      const std::string kind(fsi::scene::name(found.parameter->value.kind));
      pending_.push_back({offset, in_quotes(name) + " is a " + kind + ": arithmetic needs numbers",
                          "reference a number here; to copy the " + kind +
                              ", make the reference the whole expression"});
    } else {
      *slot = found.parameter->value.number;
    }
    return slot;
  }

  // `e` and `pi` are muParser constants and never reach the factory: a parameter of that name
  // would be ignored silently.
  void check_constant_names(RawParameter& parameter) {
    const std::string& text = *text_;
    scan_names(scalar_.begin, [&](std::size_t begin, std::size_t end) {
      const std::string token = text.substr(begin, end - begin);
      std::size_t next = end;
      while (next < scalar_.end && is_blank(text[next]))
        ++next;
      const bool call = next < scalar_.end && text[next] == '(';
      if ((token == "e" || token == "pi") && !call) {
        const Resolution found = resolve(token, parameter);
        if (found.parameter) {
          pending_.push_back({begin,
                              in_quotes(token) +
                                  " is the built-in constant and also a parameter (" +
                                  found.parameter->location.text() + ")",
                              "rename the parameter, e.g. " + token + "_value"});
        }
      }
      return false;
    });
  }

  bool number(RawParameter& parameter, Range range, double& out) {
    text_ = &normalized_;
    scalar_ = range;
    cursor_ = range.begin;
    current_ = &parameter;
    pending_.clear();
    dependency_failed_ = false;
    check_constant_names(parameter);
    const std::string expression = normalized_.substr(range.begin, range.end - range.begin);
    bool parsed = true;
    std::size_t error_offset = range.begin;
    std::string error_message;
    try {
      parser_.ClearVar();
      parser_.SetExpr(expression);
      out = parser_.Eval();
    } catch (const mu::Parser::exception_type& error) {
      parsed = false;
      error_offset =
          range.begin + std::min<std::size_t>(static_cast<std::size_t>(std::max(error.GetPos(), 0)),
                                              expression.size());
      error_message = error.GetMsg();
    }
    for (const auto& problem : pending_)
      report(parameter, problem.offset, problem.message, problem.fix);
    if (!pending_.empty() || dependency_failed_) return false;
    if (!parsed) {
      report(parameter, error_offset,
             "cannot evaluate " + in_quotes(expression) + ": " + error_message, kFunctionsHint);
      return false;
    }
    if (!std::isfinite(out)) {
      report(parameter, range.begin,
             in_quotes(expression) + " evaluates to " + (std::isnan(out) ? "nan" : "infinity"),
             "check for a division by zero, or sqrt/ln/asin of a value outside their domain");
      return false;
    }
    return true;
  }

  // ---- vectors and matrices ----

  bool items_of(RawParameter& parameter, Range range, std::vector<Range>& items) {
    const std::string& text = normalized_;
    const std::size_t close = matching_bracket(text, range.begin, range.end);
    if (close == std::string::npos) {
      report(parameter, range.begin, "'[' is not closed", "add the missing ']'");
      return false;
    }
    if (close + 1 != range.end) {
      report(parameter, close + 1, "unexpected text after the closing ']'",
             "a vector is [a, b, c] and a matrix [[a, b], [c, d]], each alone as the value; "
             "arithmetic on vectors is not supported");
      return false;
    }
    items = split_items(text, range.begin, close);
    if (items.size() == 1 && items.front().empty()) {
      items.clear();  // []
      return true;
    }
    bool ok = true;
    for (const Range& item : items) {
      if (item.empty()) {
        report(parameter, item.begin, "empty element", "remove the extra ',' or add the value");
        ok = false;
      }
    }
    return ok;
  }

  bool numbers_of(RawParameter& parameter, const std::vector<Range>& items,
                  std::vector<double>& out) {
    bool ok = true;
    for (const Range& item : items) {
      if (normalized_[item.begin] == '[') {
        report(parameter, item.begin, "a bracket inside a matrix row",
               "a matrix has exactly two levels of brackets: [[a, b], [c, d]]");
        ok = false;
        continue;
      }
      double value = 0.0;
      if (number(parameter, item, value)) {
        out.push_back(value);
      } else {
        ok = false;
      }
    }
    return ok;
  }

  bool list(RawParameter& parameter, Range range, Value& value) {
    std::vector<Range> items;
    if (!items_of(parameter, range, items)) return false;
    const auto rows =
        static_cast<std::size_t>(std::count_if(items.begin(), items.end(), [&](const Range& item) {
          return normalized_[item.begin] == '[';
        }));
    if (rows == 0) {
      value.kind = ValueKind::Vector;
      return numbers_of(parameter, items, value.vector);
    }
    if (rows != items.size()) {
      const auto odd = std::find_if(items.begin(), items.end(), [&](const Range& item) {
        return (normalized_[item.begin] == '[') != (normalized_[items.front().begin] == '[');
      });
      report(parameter, odd->begin, "the list mixes numbers and bracketed rows",
             "a vector is [a, b, c]; a matrix is [[a, b], [c, d]]");
      return false;
    }
    value.kind = ValueKind::Matrix;
    bool ok = true;
    for (std::size_t r = 0; r < items.size(); ++r) {
      std::vector<Range> row_items;
      std::vector<double> row;
      if (!items_of(parameter, items[r], row_items) || !numbers_of(parameter, row_items, row)) {
        ok = false;
        continue;
      }
      value.matrix.push_back(std::move(row));
    }
    return ok;
  }

  // ---- one parameter ----

  void evaluate(RawParameter& parameter) {
    normalized_ = parameter.expression;
    for (char& c : normalized_) {
      if (is_blank(c)) c = ' ';
    }
    const Range whole = trimmed(normalized_, 0, normalized_.size());
    Value value;
    bool ok = true;
    if (whole.empty()) {
      report(parameter, 0, "no value", "write KEY=EXPR");
      ok = false;
    } else if (normalized_[whole.begin] == '"') {
      const std::size_t close = normalized_.find('"', whole.begin + 1);
      if (close == std::string::npos) {
        report(parameter, whole.begin, "the string is not closed", "add the closing '\"'");
        ok = false;
      } else if (close + 1 != whole.end) {
        report(parameter, close + 1, "unexpected text after the string",
               "a string value is one \"...\" and nothing else");
        ok = false;
      } else {
        value = text_value(normalized_.substr(whole.begin + 1, close - whole.begin - 1));
      }
    } else if (normalized_[whole.begin] == '[') {
      ok = list(parameter, whole, value);
    } else {
      const std::string name = normalized_.substr(whole.begin, whole.end - whole.begin);
      const bool is_reference = reference_end(normalized_, whole.begin, whole.end) == whole.end &&
                                name != "e" && name != "pi";
      Resolution found;
      if (is_reference) found = resolve(name, parameter);
      if (found.parameter && found.parameter->state == RawParameter::State::Failed) {
        ok = false;  // the referenced parameter's error says it all
      } else if (found.parameter) {
        value = found.parameter->value;  // numbers, strings, vectors and matrices alike
      } else if (is_reference && found.silent) {
        ok = false;  // the cycle it belongs to is reported already
      } else if (is_reference) {
        report(parameter, whole.begin, found.message, found.fix);
        ok = false;
      } else {
        ok = number(parameter, whole, value.number);
      }
    }
    parameter.value = std::move(value);
    parameter.state = ok ? RawParameter::State::Done : RawParameter::State::Failed;
  }

  struct Pending {
    std::size_t offset;
    std::string message;
    std::string fix;
  };

  RawBlock& root_;
  mu::Parser parser_;
  std::string normalized_;  // the current expression, every blank turned into ' '
  // State of the expression muParser is parsing, for the variable factory.
  const std::string* text_ = nullptr;
  Range scalar_;
  std::size_t cursor_ = 0;
  RawParameter* current_ = nullptr;
  std::deque<double> slots_;  // stable addresses for muParser's variables
  std::vector<Pending> pending_;
  bool dependency_failed_ = false;
  std::vector<const RawParameter*> cycle_members_;  // of cycles reported already
  std::vector<StaleUse> stale_uses_;
  std::vector<Problem> problems_;
};

}  // namespace

namespace {

// The blocks of the file along an override's path; stops at the first one the file lacks.
struct OverridePath {
  RawBlock* block = nullptr;  // the deepest block found
  std::size_t found = 0;      // how many of the path's blocks the file has
};

OverridePath follow(RawBlock& root, const std::vector<PathPart>& parts, const std::string& label) {
  OverridePath path{&root, 0};
  for (; path.found + 1 < parts.size(); ++path.found) {
    const PathPart& part = parts[path.found];
    const std::vector<RawBlock*> candidates = path.block->children(part.name);
    if (candidates.empty()) break;
    if (part.index < 0 && candidates.size() > 1) {
      throw Error(
          in_quotes(part.name) + " is a list of " + std::to_string(candidates.size()) + " blocks",
          label, pick_one(parts, path.found, candidates.size()));
    }
    if (part.index >= static_cast<int>(candidates.size())) {
      throw Error("there are only " + std::to_string(candidates.size()) + " " +
                      in_quotes(part.name) + " blocks",
                  label,
                  "use an index from 0 to " + std::to_string(candidates.size() - 1) + " (0-based)");
    }
    path.block = candidates[part.index < 0 ? 0 : static_cast<std::size_t>(part.index)];
  }
  return path;
}

int last_sequence(const RawBlock& block) {
  int last = 0;
  for (const auto& parameter : block.parameters)
    last = std::max(last, parameter->sequence);
  for (const auto& child : block.blocks)
    last = std::max(last, last_sequence(*child));
  return last;
}

// Why `--set` cannot add the parameter `parts` names ("" if it can): asks `may_add` about the
// blocks the file lacks on the way.
std::string refusal(const std::vector<PathPart>& parts, const OverridePath& path,
                    const OverrideAdmission& may_add) {
  if (!may_add) return "--set changes parameters the file defines; add it to the file first";
  for (std::size_t i = path.found; i + 1 < parts.size(); ++i) {
    if (parts[i].index > 0) {
      return "the file has no " + in_quotes(to_string(parts, i + 1)) +
             " block to add it to; add the block to the file";
    }
  }
  std::vector<std::string> blocks;
  for (std::size_t i = 0; i + 1 < parts.size(); ++i)
    blocks.push_back(parts[i].name);
  return may_add(blocks, parts.back().name, parts.size() - 1 - path.found);
}

// The parameter an admitted override adds, after everything the file holds (it may refer to any
// of it), in the blocks of its path, created where the file lacks them.
RawParameter& add_parameter(RawBlock& root, const std::vector<PathPart>& parts, OverridePath path,
                            const std::string& label) {
  const SourceLocation where{label, 0, 0};
  for (std::size_t i = path.found; i + 1 < parts.size(); ++i)
    path.block = &path.block->add_block(parts[i].name, where);
  auto parameter = std::make_unique<RawParameter>();
  parameter->key = parts.back().name;
  parameter->location = where;
  parameter->sequence = last_sequence(root) + 1;
  parameter->block = path.block;
  return path.block->add_parameter(std::move(parameter));
}

}  // namespace

void apply_overrides(RawBlock& root, const std::vector<Override>& overrides,
                     const OverrideAdmission& may_add) {
  for (const Override& item : overrides) {
    const std::string label = "--set " + item.path + "=" + item.expression;
    std::vector<PathPart> parts;
    if (!parse_path(item.path, parts)) {
      throw Error(in_quotes(item.path) + " is not a parameter path", label,
                  "write e.g. --set Geometry.width=0.06 or --set Body[1].mass=2");
    }
    const OverridePath path = follow(root, parts, label);
    const bool in_file = path.found + 1 == parts.size();
    RawParameter* target = nullptr;
    if (in_file && parts.back().index < 0) {
      for (auto& parameter : path.block->parameters) {
        if (parameter->key == parts.back().name) target = parameter.get();  // the last one counts
      }
      if (!target && !path.block->children(parts.back().name).empty()) {
        throw Error(in_quotes(item.path) + " is a block, not a parameter", label,
                    "set one of its parameters, e.g. --set " + item.path + ".key=...");
      }
    }
    if (!target) {
      const std::string why_not = parts.back().index >= 0
                                      ? "remove the [...] after " + in_quotes(parts.back().name) +
                                            ": only blocks take an index"
                                      : refusal(parts, path, may_add);
      if (!why_not.empty()) {
        std::vector<std::string> paths;
        collect_paths(root, "", paths);
        const std::string suggestion = suggestion_for(item.path, parts.back().name, paths);
        throw Error("the scene file has no parameter " + in_quotes(item.path), label,
                    suggestion.empty() ? why_not : "did you mean " + in_quotes(suggestion) + "?");
      }
    }
    if (trimmed(item.expression, 0, item.expression.size()).empty()) {
      throw Error("the override has no value", label, "write --set KEY=EXPR");
    }
    if (!target) target = &add_parameter(root, parts, path, label);
    target->expression = item.expression;
    target->override_label = label;
    target->expression_location = {label, 0, 0};
  }
}

std::vector<Problem> evaluate(RawBlock& root) {
  Evaluator evaluator(root);
  return evaluator.run();
}

}  // namespace fsi::scene::detail
