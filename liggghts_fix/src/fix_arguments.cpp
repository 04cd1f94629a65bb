#include "fsi/contact/fix_arguments.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <set>
#include <stdexcept>
#include <vector>

namespace fsi::contact {
namespace {

// The default of k, r0 and cutoff: required, unless the true-shape keywords derive them.
constexpr const char* kFromSpacing = "required, or derived from spacing and pressure";

using Apply =
    std::function<void(FixFsiSphArguments&, const std::string& keyword, const std::string& value)>;

struct Keyword {
  const char* name;
  const char* value;     // admissible values, for usage and documentation
  const char* meaning;   // one line
  const char* fallback;  // default, or nullptr when the keyword is required
  Apply apply;
};

[[noreturn]] void reject(const std::string& keyword, const std::string& text,
                         const std::string& expected) {
  throw std::invalid_argument("fix fsi/sph: keyword '" + keyword + "' needs " + expected +
                              ", got '" + text + "'");
}

double number(const std::string& keyword, const std::string& text) {
  errno = 0;
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  if (text.empty() || end != text.c_str() + text.size() || errno == ERANGE ||
      !std::isfinite(value)) {
    reject(keyword, text, "a finite number");
  }
  return value;
}

int integer(const std::string& keyword, const std::string& text,
            std::initializer_list<int> allowed) {
  const double value = number(keyword, text);
  const bool whole = value == std::floor(value) && std::abs(value) < 1e6;
  if (!whole ||
      std::find(allowed.begin(), allowed.end(), static_cast<int>(value)) == allowed.end()) {
    std::string list;
    for (int option : allowed)
      list += (list.empty() ? "" : ", ") + std::to_string(option);
    reject(keyword, text, "one of " + list);
  }
  return static_cast<int>(value);
}

const std::vector<Keyword>& keywords() {
  static const std::vector<Keyword> table{
      {"k", "number >= 0",
       "repulsion scale: force density at zero distance (thesis law; 2D: N/m^2 per unit depth)",
       kFromSpacing,
       [](auto& a, const auto& key, const auto& v) { a.law.repulsion_scale = number(key, v); }},
      {"t", "number >= 0",
       "viscous (wall friction) scale; no slip for a fluid of nu: t = rho0 nu / r_v (r_v = "
       "cutoff_visc; docs/theory.md)",
       nullptr,
       [](auto& a, const auto& key, const auto& v) { a.law.viscous_scale = number(key, v); }},
      {"r0", "0 < r0 <= cutoff",
       "equilibrium distance of the repulsion; r0 < cutoff adds adhesion between r0 and cutoff",
       kFromSpacing,
       [](auto& a, const auto& key, const auto& v) {
         a.law.equilibrium_distance = number(key, v);
       }},
      {"cutoff", "number > 0",
       "range r_c = 2h of the repulsion (and of the viscous term by default)", kFromSpacing,
       [](auto& a, const auto& key, const auto& v) { a.law.cutoff = number(key, v); }},
      {"spacing", "number > 0",
       "true-shape wall: the particle lattice constant d; with `pressure`, sets k, r0 and cutoff "
       "so "
       "that the fluid sees the mesh's true outline (instead of k, r0, cutoff)",
       "none",
       [](auto& a, const auto& key, const auto& v) {
         a.true_shape.spacing = number(key, v);
         if (!(a.true_shape.spacing > 0.0)) reject(key, v, "a positive length");
       }},
      {"pressure", "number > 0",
       "true-shape wall: reference pressure at which the first layer rests at 0.75 d (e.g. rho0 g "
       "H / 2 for a column of height H)",
       "none",
       [](auto& a, const auto& key, const auto& v) {
         a.true_shape.pressure = number(key, v);
         if (!(a.true_shape.pressure > 0.0)) reject(key, v, "a positive pressure");
       }},
      {"cutoff_visc", "number > 0", "range of the viscous term when it differs from cutoff",
       "cutoff",
       [](auto& a, const auto& key, const auto& v) {
         a.law.viscous_cutoff = number(key, v);
         if (a.law.viscous_cutoff <= 0.0) reject(key, v, "a positive length");
       }},
      {"law", "thesis or lj", "repulsive law: thesis eq. (4.2) or Lennard-Jones-like eq. (4.3)",
       "thesis",
       [](auto& a, const auto& key, const auto& v) {
         if (v == "thesis") {
           a.law.repulsion_law = RepulsionLaw::Thesis;
         } else if (v == "lj") {
           a.law.repulsion_law = RepulsionLaw::LennardJones;
         } else {
           reject(key, v, "'thesis' or 'lj'");
         }
       }},
      {"p1", "integer", "repulsive exponent of the lj law, p2 < p1 <= 24", "4",
       [](auto& a, const auto& key, const auto& v) {
         a.law.lj_p1 = integer(key, v, {2,  3,  4,  5,  6,  7,  8,  9,  10, 11, 12, 13,
                                        14, 15, 16, 17, 18, 19, 20, 21, 22, 23, 24});
       }},
      {"p2", "integer", "attractive exponent of the lj law, 1 <= p2 < p1", "2",
       [](auto& a, const auto& key, const auto& v) {
         a.law.lj_p2 = integer(key, v, {1,  2,  3,  4,  5,  6,  7,  8,  9,  10, 11, 12,
                                        13, 14, 15, 16, 17, 18, 19, 20, 21, 22, 23});
       }},
      {"kernel", "spiky or cubic",
       "weight of the viscous term: renormalised spiky Laplacian (eq. 5.5) or cubic-spline shape",
       "spiky",
       [](auto& a, const auto& key, const auto& v) {
         if (v == "spiky") {
           a.law.viscous_kernel = ViscousKernel::Spiky;
         } else if (v == "cubic") {
           a.law.viscous_kernel = ViscousKernel::CubicSpline;
         } else {
           reject(key, v, "'spiky' or 'cubic'");
         }
       }},
      {"gauss", "1 ... 5", "2D: Gauss-Legendre points per (sub-)segment (thesis Table 4.1: 3)", "3",
       [](auto& a, const auto& key, const auto& v) {
         a.gauss_points = integer(key, v, {1, 2, 3, 4, 5});
       }},
      {"triangle", "1, 3 or 7", "3D: points of the symmetric triangle rule (thesis §4.3: 7)", "7",
       [](auto& a, const auto& key, const auto& v) {
         a.triangle_points = integer(key, v, {1, 3, 7});
       }},
      {"warn", "0 <= f < 1",
       "warn when a particle comes closer to a wall than f * r0 (0 = never warn)", "0.25",
       [](auto& a, const auto& key, const auto& v) {
         a.warn_fraction = number(key, v);
         if (a.warn_fraction < 0.0 || a.warn_fraction >= 1.0) reject(key, v, "0 <= f < 1");
       }},
  };
  return table;
}

}  // namespace

std::string fix_fsi_sph_usage() {
  std::string text =
      "fix ID group fsi/sph t T (k K r0 R0 cutoff RC | spacing D pressure P) [keyword value ...]\n";
  for (const Keyword& keyword : keywords()) {
    std::string line = "  " + std::string(keyword.name);
    line.resize(14, ' ');
    text += line + keyword.value + ": " + keyword.meaning;
    text += keyword.fallback ? std::string(" (default ") + keyword.fallback + ")\n"
                             : std::string(" (required)\n");
  }
  return text;
}

std::string fix_fsi_sph_keyword_table_markdown() {
  std::string text = "| keyword | value | meaning | default |\n|---|---|---|---|\n";
  for (const Keyword& keyword : keywords()) {
    text += std::string("| `") + keyword.name + "` | " + keyword.value + " | " + keyword.meaning +
            " | " + (keyword.fallback ? keyword.fallback : "required") + " |\n";
  }
  return text;
}

FixFsiSphArguments parse_fix_fsi_sph_arguments(std::span<const std::string> words, int dimension) {
  FixFsiSphArguments result;
  if (words.size() % 2 != 0) {
    throw std::invalid_argument("fix fsi/sph: keyword '" + words.back() +
                                "' has no value; usage:\n" + fix_fsi_sph_usage());
  }
  std::set<std::string> seen;
  for (std::size_t i = 0; i < words.size(); i += 2) {
    const std::string& name = words[i];
    const auto& table = keywords();
    const auto keyword = std::find_if(table.begin(), table.end(),
                                      [&](const Keyword& entry) { return name == entry.name; });
    if (keyword == table.end()) {
      throw std::invalid_argument("fix fsi/sph: unknown keyword '" + name + "'; usage:\n" +
                                  fix_fsi_sph_usage());
    }
    if (!seen.insert(name).second) {
      throw std::invalid_argument("fix fsi/sph: keyword '" + name +
                                  "' is given twice; keep one of them");
    }
    keyword->apply(result, name, words[i + 1]);
  }
  const bool true_shape = seen.contains("spacing") || seen.contains("pressure");
  result.uses_true_shape = true_shape;
  if (true_shape) {
    if (!seen.contains("spacing") || !seen.contains("pressure")) {
      throw std::invalid_argument(
          "fix fsi/sph: the true-shape wall needs both 'spacing' (the lattice constant d) and "
          "'pressure' (e.g. rho0 g H / 2); add the missing one");
    }
    for (const char* derived : {"k", "r0", "cutoff", "law"}) {
      if (seen.contains(derived)) {
        throw std::invalid_argument(std::string("fix fsi/sph: '") + derived +
                                    "' is derived from 'spacing' and 'pressure' (true-shape "
                                    "wall); remove it, or remove 'spacing' and 'pressure'");
      }
    }
    try {
      apply_true_shape(result.law, result.true_shape, dimension);
    } catch (const std::invalid_argument& bad) {
      throw std::invalid_argument(std::string("fix fsi/sph: ") + bad.what());
    }
  } else {
    for (const char* required : {"k", "r0", "cutoff"}) {
      if (!seen.contains(required)) {
        throw std::invalid_argument(std::string("fix fsi/sph: missing keyword '") + required +
                                    "' (or give 'spacing' and 'pressure' for the true-shape "
                                    "wall); usage:\n" +
                                    fix_fsi_sph_usage());
      }
    }
  }
  for (const Keyword& keyword : keywords()) {
    if (!keyword.fallback && !seen.contains(keyword.name)) {
      throw std::invalid_argument(std::string("fix fsi/sph: missing keyword '") + keyword.name +
                                  "'; usage:\n" + fix_fsi_sph_usage());
    }
  }
  const bool lj = result.law.repulsion_law == RepulsionLaw::LennardJones;
  if (!lj && (seen.contains("p1") || seen.contains("p2"))) {
    throw std::invalid_argument(
        "fix fsi/sph: keywords 'p1'/'p2' apply to 'law lj' only; add 'law lj' or remove them");
  }
  try {
    result.law.validate();
  } catch (const std::invalid_argument& bad) {
    throw std::invalid_argument(std::string("fix fsi/sph: ") + bad.what());
  }
  return result;
}

}  // namespace fsi::contact
