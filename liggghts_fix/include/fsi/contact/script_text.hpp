#pragma once
// A LIGGGHTS input script read as LIGGGHTS reads it, without LIGGGHTS: the commands with their
// first line, and the variables a command references. fsi-client runs the scripts command by
// command with it; fsi-server's --check reads them with it, so both see the same commands.

#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace fsi::contact {

struct ScriptCommand {
  int line = 0;                    // 1-based line where the command starts
  std::string code;                // the command, continuation lines joined, comment removed
  std::vector<std::string> words;  // split at blanks; "..." and '...' group and lose the quotes
};

// LIGGGHTS' rules (LAMMPS Input::file and Input::parse): a line whose last non-blank character
// is '&' continues on the next line (a '&' before a '#' comment does not continue); '#' outside
// quotes starts a comment; blank commands are skipped.
std::vector<ScriptCommand> script_commands(std::string_view text);

// A command's words: split at blanks; "..." and '...' group and lose the quotes.
std::vector<std::string> command_words(std::string_view code);

// The variables a command references as ${name} or $x outside quotes, in order (LIGGGHTS
// substitutes those before it runs the command and stops the job at one it does not know).
std::vector<std::string> referenced_variables(std::string_view code);

// The value of a LIGGGHTS variable by name, or nullopt when it is not defined.
using VariableLookup = std::function<std::optional<std::string>(const std::string& name)>;

// A word with every ${name} and $x (one character) replaced by value_of(name), as LIGGGHTS'
// Input::substitute does before it runs a command (quotes are the caller's: `words` of a
// ScriptCommand have lost them); nullopt when a name is unknown or a "${" is not closed.
// fsi-server's --check reads the scripts with it (physics checks, viscosity_match).
std::optional<std::string> substitute_variables(std::string_view word,
                                                const VariableLookup& value_of);

}  // namespace fsi::contact
