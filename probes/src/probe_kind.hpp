#pragma once
// The unit of extension of fsi::probes (internal): one file per probe kind (probe_<kind>.cpp)
// defines its rules, and probe_kinds.inc lists it in one line. A kind owns the layout of its
// parameters, its columns, and how its partials are computed on a rank and turned into values
// once reduced over the ranks (sums add, maxima take the largest).

#include <cstddef>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "fsi/probes/evaluation.hpp"
#include "fsi/probes/probe.hpp"

namespace fsi::probes::detail {

// The kinds that read the wall's sampling points: how many of them lie in the probe's patch
// (KindRules of the others: nullptr).
using WallPatchCount = std::size_t (*)(const ProbeDefinition& probe, int dimension,
                                       const WallSamples& wall);

struct KindRules {
  ProbeKind kind;
  std::string_view name;
  // Empty when the definition's parameters fit the kind.
  std::string (*problem)(const ProbeDefinition& probe, int dimension);
  std::vector<Column> (*columns)(const ProbeDefinition& probe, int dimension);
  std::size_t (*sum_count)(const ProbeDefinition& probe, int dimension);
  std::size_t (*maximum_count)(const ProbeDefinition& probe, int dimension);
  // This rank's partials; `sums` arrive zeroed, `maxima` at -infinity.
  void (*partials)(const ProbeDefinition& probe, const ProbeContext& context,
                   const ParticleSet& particles, const Kernel& kernel, const WallSamples& wall,
                   std::span<double> sums, std::span<double> maxima);
  // The values (one per column) from the partials reduced over all ranks.
  void (*values)(const ProbeDefinition& probe, const ProbeContext& context,
                 std::span<const double> sums, std::span<const double> maxima,
                 std::span<double> values);
  // Only kinds that read the wall's sampling points; nullptr otherwise.
  WallPatchCount wall_patch_samples = nullptr;
  // Only kinds with a place in space (can_move): moves their points and turns their directions
  // in `parameters` (the kind's layout) by `placement`; nullptr otherwise.
  void (*place)(std::span<double> parameters, const RigidPlacement& placement) = nullptr;
};

// Every kind of probe_kinds.inc.
const std::vector<KindRules>& probe_kinds();
// nullptr for an unknown kind.
const KindRules* rules_of(ProbeKind kind);

// Helpers the kinds share.
std::string axis_suffix(int axis);  // "x", "y", "z"
// "J/m" in 2D, "J" in 3D: a quantity per unit depth in 2D.
std::string per_depth(int dimension, const std::string& planar, const std::string& spatial);
// The expected parameter count, as a problem text when it differs.
std::string count_problem(const ProbeDefinition& probe, std::size_t expected);
double squared_distance(const double* a, const double* b, int dimension);
// Moves the point parameters[first .. first + 2] (x, y, z) by `placement`; turns the direction
// there likewise.
void move_point(std::span<double> parameters, std::size_t first, const RigidPlacement& placement);
void turn_direction(std::span<double> parameters, std::size_t first,
                    const RigidPlacement& placement);
// Fixed partial counts (KindRules::sum_count, maximum_count) for kinds that need none or one.
inline std::size_t no_partials(const ProbeDefinition&, int) {
  return 0;
}
inline std::size_t one_partial(const ProbeDefinition&, int) {
  return 1;
}

}  // namespace fsi::probes::detail
