#pragma once
// The argument syntax of `fix ID group fsi/sph keyword value ...` (docs/fix_fsi_sph.md), parsed
// without LIGGGHTS so it can be tested and reported precisely.

#include <span>
#include <string>

#include "fsi/contact/force_law.hpp"

namespace fsi::contact {

struct FixFsiSphArguments {
  ForceLaw law;
  int gauss_points = 3;
};

// words: everything after the style name, with LIGGGHTS variables already substituted.
// Throws std::invalid_argument naming the keyword and the admissible values.
FixFsiSphArguments parse_fix_fsi_sph_arguments(std::span<const std::string> words);

// The keywords with their meaning, for error messages and documentation.
std::string fix_fsi_sph_usage();

}  // namespace fsi::contact
