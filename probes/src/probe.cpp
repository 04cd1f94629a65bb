#include "fsi/probes/probe.hpp"

#include <cmath>
#include <utility>

#include "fsi/common/error.hpp"

#include "probe_kind.hpp"

namespace fsi::probes {

ProbeDefinition fluid_energy_probe(std::string name, const std::array<double, 3>& datum) {
  return {ProbeKind::FluidEnergy, std::move(name), {datum[0], datum[1], datum[2]}};
}

ProbeDefinition point_probe(std::string name, const std::array<double, 3>& point) {
  return {ProbeKind::Point, std::move(name), {point[0], point[1], point[2]}};
}

ProbeDefinition free_surface_probe(std::string name, const std::array<double, 3>& bottom,
                                   double length, int samples) {
  return {ProbeKind::FreeSurface,
          std::move(name),
          {bottom[0], bottom[1], bottom[2], length, static_cast<double>(samples)}};
}

ProbeDefinition front_probe(std::string name, int axis, int direction, int min_neighbours) {
  return {ProbeKind::Front,
          std::move(name),
          {static_cast<double>(axis), static_cast<double>(direction),
           static_cast<double>(min_neighbours)}};
}

ProbeDefinition flux_probe(std::string name, const std::vector<std::array<double, 3>>& points,
                           int samples) {
  ProbeDefinition probe{ProbeKind::Flux, std::move(name), {static_cast<double>(points.size())}};
  for (const auto& point : points)
    probe.parameters.insert(probe.parameters.end(), point.begin(), point.end());
  probe.parameters.push_back(static_cast<double>(samples));
  return probe;
}

ProbeDefinition wall_pressure_probe(
    std::string name, const std::array<double, 3>& centre, double radius,
    const std::array<double, 3>& fluid_side,
    const std::vector<std::pair<std::uint32_t, std::uint32_t>>& element_ranges) {
  ProbeDefinition probe{ProbeKind::WallPressure,
                        std::move(name),
                        {centre[0], centre[1], centre[2], radius, fluid_side[0], fluid_side[1],
                         fluid_side[2], static_cast<double>(element_ranges.size())}};
  for (const auto& [first, end] : element_ranges) {
    probe.parameters.push_back(static_cast<double>(first));
    probe.parameters.push_back(static_cast<double>(end));
  }
  return probe;
}

std::array<double, 3> RigidPlacement::point(const std::array<double, 3>& x) const {
  std::array<double, 3> moved = direction(x);
  for (int i = 0; i < 3; ++i)
    moved[i] += translation[i];
  return moved;
}

std::array<double, 3> RigidPlacement::direction(const std::array<double, 3>& v) const {
  std::array<double, 3> turned{};
  for (int i = 0; i < 3; ++i)
    turned[i] = rotation[3 * i] * v[0] + rotation[3 * i + 1] * v[1] + rotation[3 * i + 2] * v[2];
  return turned;
}

bool can_move(ProbeKind kind) {
  const detail::KindRules* rules = detail::rules_of(kind);
  return rules && rules->place;
}

ProbeDefinition placed(const ProbeDefinition& initial, const RigidPlacement& placement) {
  const detail::KindRules* rules = detail::rules_of(initial.kind);
  if (!rules || !rules->place) {
    throw Error(
        "probe '" + initial.name + "' (" + kind_name(initial.kind) + ") cannot move with a body",
        "probe placement",
        "attach only point, free_surface, flux and wall_pressure probes to a body");
  }
  ProbeDefinition moved = initial;
  rules->place(moved.parameters, placement);
  return moved;
}

std::vector<Column> columns(const ProbeDefinition& probe, int dimension) {
  const detail::KindRules* rules = detail::rules_of(probe.kind);
  if (!rules) return {};
  return rules->columns(probe, dimension);
}

bool reads_wall_samples(const ProbeDefinition& probe) {
  const detail::KindRules* rules = detail::rules_of(probe.kind);
  return rules && rules->wall_patch_samples;
}

std::string kind_name(ProbeKind kind) {
  const detail::KindRules* rules = detail::rules_of(kind);
  if (!rules) return "kind " + std::to_string(static_cast<std::uint32_t>(kind));
  return std::string(rules->name);
}

bool is_known_kind(std::uint32_t kind) {
  return detail::rules_of(static_cast<ProbeKind>(kind)) != nullptr;
}

std::string definition_problem(const ProbeDefinition& probe, int dimension) {
  const detail::KindRules* rules = detail::rules_of(probe.kind);
  if (!rules) return "probe '" + probe.name + "' is of unknown " + kind_name(probe.kind);
  if (dimension != 2 && dimension != 3)
    return "probes need dimension 2 or 3, not " + std::to_string(dimension);
  for (double parameter : probe.parameters) {
    if (!std::isfinite(parameter)) return "probe '" + probe.name + "' has a parameter not finite";
  }
  return rules->problem(probe, dimension);
}

}  // namespace fsi::probes
