#include "fsi/contact/fix_arguments.hpp"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <optional>
#include <stdexcept>

namespace fsi::contact {
namespace {

double parse_number(const std::string& keyword, const std::string& text) {
  errno = 0;
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  if (text.empty() || end != text.c_str() + text.size() || errno == ERANGE ||
      !std::isfinite(value)) {
    throw std::invalid_argument("fix fsi/sph: keyword '" + keyword +
                                "' needs a finite number, got '" + text + "'");
  }
  return value;
}

}  // namespace

std::string fix_fsi_sph_usage() {
  return "fix ID group fsi/sph k K t T r0 R0 cutoff RC [gauss N] [kernel spiky] [law thesis]\n"
         "  k       repulsion scale (force density at zero distance), >= 0\n"
         "  t       viscous wall-friction scale, >= 0 (thesis eq. 6.4: t ~ nu*rho/h)\n"
         "  r0      equilibrium distance, 0 < r0 <= cutoff (r0 = cutoff: no adhesion)\n"
         "  cutoff  interaction range r_c = 2h\n"
         "  gauss   Gauss-Legendre points per sub-segment, 1..5 (default 3)\n"
         "  kernel  Laplacian for the viscous term: spiky (default, thesis eq. 5.5)\n"
         "  law     repulsive law: thesis (default, eq. 4.2)";
}

FixFsiSphArguments parse_fix_fsi_sph_arguments(std::span<const std::string> words) {
  FixFsiSphArguments result;
  std::optional<double> k, t, r0, cutoff;
  if (words.size() % 2 != 0) {
    throw std::invalid_argument("fix fsi/sph: keyword '" + words.back() +
                                "' has no value; usage:\n" + fix_fsi_sph_usage());
  }
  for (std::size_t i = 0; i < words.size(); i += 2) {
    const std::string& keyword = words[i];
    const std::string& value = words[i + 1];
    if (keyword == "k") {
      k = parse_number(keyword, value);
    } else if (keyword == "t") {
      t = parse_number(keyword, value);
    } else if (keyword == "r0") {
      r0 = parse_number(keyword, value);
    } else if (keyword == "cutoff") {
      cutoff = parse_number(keyword, value);
    } else if (keyword == "gauss") {
      const double points = parse_number(keyword, value);
      if (points != std::floor(points) || points < 1 || points > 5) {
        throw std::invalid_argument("fix fsi/sph: keyword 'gauss' needs an integer 1..5, got '" +
                                    value + "'");
      }
      result.gauss_points = static_cast<int>(points);
    } else if (keyword == "kernel") {
      if (value != "spiky") {
        throw std::invalid_argument("fix fsi/sph: kernel '" + value +
                                    "' is not available; this version supports: spiky");
      }
    } else if (keyword == "law") {
      if (value != "thesis") {
        throw std::invalid_argument("fix fsi/sph: law '" + value +
                                    "' is not available; this version supports: thesis");
      }
    } else {
      throw std::invalid_argument("fix fsi/sph: unknown keyword '" + keyword + "'; usage:\n" +
                                  fix_fsi_sph_usage());
    }
  }
  const auto require = [](const std::optional<double>& value, const char* keyword) {
    if (!value) {
      throw std::invalid_argument(std::string("fix fsi/sph: missing keyword '") + keyword +
                                  "'; usage:\n" + fix_fsi_sph_usage());
    }
    return *value;
  };
  result.law.repulsion_scale = require(k, "k");
  result.law.viscous_scale = require(t, "t");
  result.law.equilibrium_distance = require(r0, "r0");
  result.law.cutoff = require(cutoff, "cutoff");
  try {
    result.law.validate();
  } catch (const std::invalid_argument& bad) {
    throw std::invalid_argument(std::string("fix fsi/sph: ") + bad.what());
  }
  return result;
}

}  // namespace fsi::contact
