// The registry of probe kinds: probe_kinds.inc, read twice, declares each kind's rules and lists
// them, so that a new kind is its file and one line there.

#include "probe_kind.hpp"

#include <algorithm>

namespace fsi::probes::detail {

#define FSI_PROBE_KIND(kind) KindRules kind##_probe_rules();
#include "probe_kinds.inc"
#undef FSI_PROBE_KIND

const std::vector<KindRules>& probe_kinds() {
  static const std::vector<KindRules> kinds = {
#define FSI_PROBE_KIND(kind) kind##_probe_rules(),
#include "probe_kinds.inc"
#undef FSI_PROBE_KIND
  };
  return kinds;
}

const KindRules* rules_of(ProbeKind kind) {
  for (const KindRules& rules : probe_kinds()) {
    if (rules.kind == kind) return &rules;
  }
  return nullptr;
}

std::string axis_suffix(int axis) {
  return axis == 0 ? "x" : axis == 1 ? "y" : "z";
}

std::string per_depth(int dimension, const std::string& planar, const std::string& spatial) {
  return dimension == 3 ? spatial : planar;
}

std::string count_problem(const ProbeDefinition& probe, std::size_t expected) {
  if (probe.parameters.size() == expected) return {};
  return "a " + std::string(rules_of(probe.kind)->name) + " probe has " + std::to_string(expected) +
         " parameters, '" + probe.name + "' has " + std::to_string(probe.parameters.size());
}

double squared_distance(const double* a, const double* b, int dimension) {
  double sum = 0.0;
  for (int k = 0; k < dimension; ++k)
    sum += (a[k] - b[k]) * (a[k] - b[k]);
  return sum;
}

void move_point(std::span<double> parameters, std::size_t first, const RigidPlacement& placement) {
  const auto moved =
      placement.point({parameters[first], parameters[first + 1], parameters[first + 2]});
  std::copy(moved.begin(), moved.end(), parameters.begin() + static_cast<std::ptrdiff_t>(first));
}

void turn_direction(std::span<double> parameters, std::size_t first,
                    const RigidPlacement& placement) {
  const auto turned =
      placement.direction({parameters[first], parameters[first + 1], parameters[first + 2]});
  std::copy(turned.begin(), turned.end(), parameters.begin() + static_cast<std::ptrdiff_t>(first));
}

}  // namespace fsi::probes::detail
