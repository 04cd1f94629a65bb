#pragma once
// The argument syntax of `fix ID group fsi/sph keyword value ...` (docs/fix_fsi_sph.md), parsed
// without LIGGGHTS so it can be tested and reported precisely. Every keyword is declared once in
// a table (fix_arguments.cpp) from which parsing, checking and the usage text are derived.

#include <span>
#include <string>

#include "fsi/contact/force_law.hpp"

namespace fsi::contact {

struct FixFsiSphArguments {
  ForceLaw law;
  int gauss_points = 3;         // 2D: Gauss–Legendre points per (sub-)segment, 1..5
  int triangle_points = 7;      // 3D: symmetric triangle rule, 1, 3 or 7 points
  double warn_fraction = 0.25;  // penetration warning below warn_fraction * r0
  // `spacing`/`pressure` given: k, r0 and cutoff of `law` were derived from them.
  bool uses_true_shape = false;
  TrueShape true_shape;
};

// words: everything after the style name, with LIGGGHTS variables already substituted;
// dimension: 2 or 3, that of the LIGGGHTS run (the true-shape wall's k depends on it).
// Throws std::invalid_argument naming the keyword and the admissible values.
FixFsiSphArguments parse_fix_fsi_sph_arguments(std::span<const std::string> words, int dimension);

// The keywords with their meaning, for error messages (`--help`) and documentation.
std::string fix_fsi_sph_usage();
// The keyword table as Markdown (docs/fix_fsi_sph.md embeds it; a test checks they agree).
std::string fix_fsi_sph_keyword_table_markdown();

}  // namespace fsi::contact
