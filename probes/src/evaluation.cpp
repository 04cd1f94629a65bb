#include "fsi/probes/evaluation.hpp"

#include <algorithm>
#include <limits>
#include <utility>

#include "fsi/common/error.hpp"
#include "probe_kind.hpp"

namespace fsi::probes {

ProbeSet::ProbeSet(std::vector<ProbeDefinition> probes, ProbeContext context)
    : probes_(std::move(probes)), context_(context) {
  for (const ProbeDefinition& probe : probes_) {
    if (const std::string problem = definition_problem(probe, context_.dimension);
        !problem.empty()) {
      throw Error(problem, "probe '" + probe.name + "'",
                  "use matching fsi-server and fsi-client releases");
    }
    if (probe.kind == ProbeKind::Front && !(context_.particle_spacing > 0.0)) {
      throw Error("front probe '" + probe.name + "' needs the particle spacing d (> 0)",
                  "probe set-up", "give the fluid a spacing (FluidRegion) or particles");
    }
    const detail::KindRules& rules = *detail::rules_of(probe.kind);
    Slots slots;
    slots.first_sum = sum_count_;
    slots.sums = rules.sum_count(probe, context_.dimension);
    slots.first_maximum = maximum_count_;
    slots.maxima = rules.maximum_count(probe, context_.dimension);
    slots.first_column = column_count_;
    slots.columns = rules.columns(probe, context_.dimension).size();
    sum_count_ += slots.sums;
    maximum_count_ += slots.maxima;
    column_count_ += slots.columns;
    slots_.push_back(slots);
  }
}

void ProbeSet::move(std::size_t index, std::vector<double> parameters) {
  if (index >= probes_.size()) {
    throw Error("a placement names probe " + std::to_string(index) + ", the set has " +
                    std::to_string(probes_.size()),
                "probe placement", "use matching fsi-server and fsi-client releases");
  }
  ProbeDefinition moved = probes_[index];
  moved.parameters = std::move(parameters);
  const detail::KindRules& rules = *detail::rules_of(moved.kind);
  std::string problem;
  if (!rules.place) {
    problem = "probe '" + moved.name + "' (" + std::string(rules.name) + ") cannot move";
  } else if (moved.parameters.size() != probes_[index].parameters.size()) {
    problem = "probe '" + moved.name + "' is placed with " +
              std::to_string(moved.parameters.size()) + " parameters, it has " +
              std::to_string(probes_[index].parameters.size());
  } else {
    problem = definition_problem(moved, context_.dimension);
  }
  const Slots& slots = slots_[index];
  if (problem.empty() && (rules.sum_count(moved, context_.dimension) != slots.sums ||
                          rules.maximum_count(moved, context_.dimension) != slots.maxima ||
                          rules.columns(moved, context_.dimension).size() != slots.columns)) {
    problem = "probe '" + moved.name + "' would change its partials or columns when placed";
  }
  if (!problem.empty())
    throw Error(problem, "probe placement", "use matching fsi-server and fsi-client releases");
  probes_[index] = std::move(moved);
}

std::vector<Column> ProbeSet::columns() const {
  std::vector<Column> all;
  for (const ProbeDefinition& probe : probes_) {
    for (Column& column : probes::columns(probe, context_.dimension))
      all.push_back(std::move(column));
  }
  return all;
}

Partials ProbeSet::partials(const ParticleSet& particles, const Kernel& kernel,
                            const WallSamples& wall) const {
  Partials partials;
  partials.sums.assign(sum_count_, 0.0);
  partials.maxima.assign(maximum_count_, -std::numeric_limits<double>::infinity());
  for (std::size_t i = 0; i < probes_.size(); ++i) {
    const Slots& slots = slots_[i];
    detail::rules_of(probes_[i].kind)
        ->partials(probes_[i], context_, particles, kernel, wall,
                   std::span(partials.sums).subspan(slots.first_sum, slots.sums),
                   std::span(partials.maxima).subspan(slots.first_maximum, slots.maxima));
  }
  return partials;
}

bool ProbeSet::needs_wall_samples() const {
  return std::any_of(probes_.begin(), probes_.end(), reads_wall_samples);
}

std::string ProbeSet::wall_problems(const WallSamples& wall) const {
  std::string problems;
  for (const ProbeDefinition& probe : probes_) {
    const detail::WallPatchCount count = detail::rules_of(probe.kind)->wall_patch_samples;
    if (!count || count(probe, context_.dimension, wall) > 0) continue;
    if (!problems.empty()) problems += "; ";
    problems += kind_name(probe.kind) + " probe '" + probe.name +
                "': no sampling point of the wall law lies in its patch (of " +
                std::to_string(wall.count) + " on the boundary mesh)";
  }
  return problems;
}

std::vector<double> ProbeSet::values(const Partials& reduced) const {
  FSI_ASSERT(reduced.sums.size() == sum_count_ && reduced.maxima.size() == maximum_count_,
             "partials of another probe set");
  std::vector<double> values(column_count_, 0.0);
  for (std::size_t i = 0; i < probes_.size(); ++i) {
    const Slots& slots = slots_[i];
    detail::rules_of(probes_[i].kind)
        ->values(probes_[i], context_, std::span(reduced.sums).subspan(slots.first_sum, slots.sums),
                 std::span(reduced.maxima).subspan(slots.first_maximum, slots.maxima),
                 std::span(values).subspan(slots.first_column, slots.columns));
  }
  return values;
}

}  // namespace fsi::probes
