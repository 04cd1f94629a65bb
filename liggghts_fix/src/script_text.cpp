#include "fsi/contact/script_text.hpp"

#include <cctype>

namespace fsi::contact {
namespace {

std::string_view trim_right(std::string_view line) {
  const auto last = line.find_last_not_of(" \t\r");
  return last == std::string_view::npos ? std::string_view{} : line.substr(0, last + 1);
}

std::string strip_comment(std::string_view line) {
  bool in_single = false, in_double = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (c == '"' && !in_single) in_double = !in_double;
    if (c == '\'' && !in_double) in_single = !in_single;
    if (c == '#' && !in_single && !in_double) return std::string(line.substr(0, i));
  }
  return std::string(line);
}

}  // namespace

std::vector<std::string> command_words(std::string_view line) {
  std::vector<std::string> words;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && std::isspace(static_cast<unsigned char>(line[i])))
      ++i;
    if (i >= line.size()) break;
    if (line[i] == '"' || line[i] == '\'') {
      const char quote = line[i];
      const std::size_t end = line.find(quote, i + 1);
      words.emplace_back(
          line.substr(i + 1, end == std::string_view::npos ? std::string_view::npos : end - i - 1));
      i = end == std::string_view::npos ? line.size() : end + 1;
    } else {
      const std::size_t start = i;
      while (i < line.size() && !std::isspace(static_cast<unsigned char>(line[i])))
        ++i;
      words.emplace_back(line.substr(start, i - start));
    }
  }
  return words;
}

std::vector<ScriptCommand> script_commands(std::string_view text) {
  std::vector<std::string_view> lines;
  for (std::size_t start = 0; start <= text.size();) {
    std::size_t end = text.find('\n', start);
    if (end == std::string_view::npos) end = text.size();
    lines.push_back(text.substr(start, end - start));
    start = end + 1;
  }
  std::vector<ScriptCommand> commands;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const int first_line = static_cast<int>(i) + 1;
    std::string line(trim_right(lines[i]));
    while (!line.empty() && line.back() == '&' && i + 1 < lines.size()) {
      line.pop_back();
      line += " ";
      line += trim_right(lines[++i]);
    }
    ScriptCommand command{first_line, strip_comment(line), {}};
    command.words = command_words(command.code);
    if (!command.words.empty()) commands.push_back(std::move(command));
  }
  return commands;
}

std::vector<std::string> referenced_variables(std::string_view code) {
  std::vector<std::string> names;
  bool in_single = false, in_double = false;
  for (std::size_t i = 0; i + 1 < code.size(); ++i) {
    const char c = code[i];
    if (c == '"' && !in_single) in_double = !in_double;
    if (c == '\'' && !in_double) in_single = !in_single;
    if (c != '$' || in_single || in_double) continue;
    if (code[i + 1] == '{') {
      const std::size_t end = code.find('}', i + 2);
      if (end != std::string_view::npos) names.emplace_back(code.substr(i + 2, end - i - 2));
    } else if (code[i + 1] != '(') {
      names.emplace_back(1, code[i + 1]);
    }
  }
  return names;
}

std::optional<std::string> substitute_variables(std::string_view word,
                                                const VariableLookup& value_of) {
  std::string result;
  for (std::size_t i = 0; i < word.size(); ++i) {
    if (word[i] != '$' || i + 1 == word.size()) {
      result += word[i];
      continue;
    }
    std::string name;
    if (word[i + 1] == '{') {
      const std::size_t close = word.find('}', i + 2);
      if (close == std::string_view::npos) return std::nullopt;
      name = std::string(word.substr(i + 2, close - i - 2));
      i = close;
    } else {
      name = std::string(1, word[i + 1]);
      ++i;
    }
    const std::optional<std::string> value = value_of(name);
    if (!value) return std::nullopt;
    result += *value;
  }
  return result;
}

}  // namespace fsi::contact
