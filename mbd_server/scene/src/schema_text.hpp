#pragma once
// How declarations read in messages, --help-params and the reference page.

#include <string>
#include <vector>

#include "fsi/scene/schema.hpp"

namespace fsi::scene::detail {

// "> 0 s", ">= 1 and <= 3"; "" without bounds.
std::string range_text(const ParameterSpec& spec, bool with_unit);
// "\"a\", \"b\"".
std::string choices_text(const std::vector<std::string>& choices);
// A matrix's values per row: "2", "2 or 3".
std::string row_length_text(const ParameterSpec& spec);
// The default value, "(required)" or "(optional)".
std::string default_text(const ParameterSpec& spec);

}  // namespace fsi::scene::detail
