#include "fsi/contact/wall_contact_3d.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "contact_skeleton.hpp"
#include "fsi/contact/triangle_quadrature.hpp"

namespace fsi::contact {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();
constexpr skeleton::MeshShape kTriangleMesh{3, 3, "triangle"};

using Vector = std::array<double, 3>;

Vector difference(const double* a, const double* b) {
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}

double dot(const Vector& a, const Vector& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

Vector cross(const Vector& a, const Vector& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

double norm(const Vector& a) {
  return std::sqrt(dot(a, a));
}

// The geometry of one triangle in the current configuration.
struct Triangle {
  std::uint32_t vertex[3];
  const double* position[3];
  const double* velocity[3];
  double area;
  Vector unit_normal;  // only meaningful when area > 0

  double closest_distance(const double* particle, double closest_so_far) const;
};

Triangle element(const BoundaryMesh3D& mesh, std::size_t triangle) {
  Triangle e{};
  for (int c = 0; c < 3; ++c) {
    e.vertex[c] = mesh.triangles[3 * triangle + c];
    e.position[c] = mesh.positions.data() + 3 * std::size_t{e.vertex[c]};
    e.velocity[c] = mesh.velocities.data() + 3 * std::size_t{e.vertex[c]};
  }
  const Vector normal =
      cross(difference(e.position[1], e.position[0]), difference(e.position[2], e.position[0]));
  const double twice_area = norm(normal);
  e.area = 0.5 * twice_area;
  if (twice_area > 0.0) {
    for (int k = 0; k < 3; ++k)
      e.unit_normal[k] = normal[k] / twice_area;
  }
  return e;
}

double longest_edge(const Triangle& e) {
  double longest = 0.0;
  for (int c = 0; c < 3; ++c) {
    longest = std::max(longest, norm(difference(e.position[(c + 1) % 3], e.position[c])));
  }
  return longest;
}

using Barycentric = std::array<double, 3>;

Barycentric midpoint(const Barycentric& a, const Barycentric& b) {
  return {0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1]), 0.5 * (a[2] + b[2])};
}

// Splits the barycentric triangle (c0, c1, c2) by its edge midpoints, `levels` times, and calls
// leaf(corner0, corner1, corner2) for every resulting sub-triangle, except where
// prune(corner0, corner1, corner2, levels) returns true for it or a triangle containing it.
template <class Leaf, class Prune>
void split(const Barycentric& c0, const Barycentric& c1, const Barycentric& c2, int levels,
           Leaf& leaf, Prune& prune) {
  if (prune(c0, c1, c2, levels)) return;
  if (levels == 0) {
    leaf(c0, c1, c2);
    return;
  }
  const Barycentric m01 = midpoint(c0, c1);
  const Barycentric m12 = midpoint(c1, c2);
  const Barycentric m20 = midpoint(c2, c0);
  split(c0, m01, m20, levels - 1, leaf, prune);
  split(m01, c1, m12, levels - 1, leaf, prune);
  split(m20, m12, c2, levels - 1, leaf, prune);
  split(m12, m20, m01, levels - 1, leaf, prune);
}

[[noreturn]] void too_fine(double longest_edge, double resolution, std::size_t triangle) {
  throw std::invalid_argument(
      "triangle " + std::to_string(triangle) + " with longest edge " +
      std::to_string(longest_edge) + " m would need more than 4^" +
      std::to_string(kMaxRefinementLevel) + " sub-triangles at refinement resolution " +
      std::to_string(resolution) + " m; use a larger resolution or a finer mesh");
}

// The refinement level of every triangle for this evaluation (0 for triangles of zero area,
// which are not sampled). Throws before anything is computed if a level is out of bounds.
void plan_levels(const ContactSettings3D& settings, const BoundaryMesh3D& mesh,
                 std::span<const std::uint8_t> pre_refinement, std::vector<std::uint8_t>& levels) {
  levels.assign(mesh.triangle_count(), 0);
  if (settings.refinement_option == 0) return;
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
    const Triangle e = element(mesh, t);
    if (!(e.area > 0.0)) continue;
    const double edge = longest_edge(e);
    int level = 0;
    switch (settings.refinement_option) {
      case 1:
        level = triangle_refinement_level(edge, settings.refinement_resolution, t);
        break;
      case 2:
        level = pre_refinement[t];
        break;
      default: {  // 3: the stored sub-triangles have edges of edge / 2^pre in the current geometry
        const int pre = pre_refinement[t];
        level = pre + triangle_refinement_level(std::ldexp(edge, -pre),
                                                settings.refinement_resolution, t);
        if (level > kMaxRefinementLevel) too_fine(edge, settings.refinement_resolution, t);
        break;
      }
    }
    levels[t] = static_cast<std::uint8_t>(level);
  }
}

// Every triangle split to its planned level, every sub-triangle sampled by the symmetric rule;
// positions, velocities and corner shares from the barycentric coordinates of the sampling point
// in the original triangle.
class TriangleSampling {
 public:
  using Point = skeleton::SamplingPoint<Triangle, 3, 3>;

  // levels: from plan_levels().
  TriangleSampling(const ContactSettings3D& settings, const BoundaryMesh3D& mesh,
                   std::span<const std::uint8_t> levels)
      : rule_(triangle_rule(settings.quadrature_points)), mesh_(mesh), levels_(levels) {}

  template <class Visit>
  void for_each_point(Visit&& visit, const skeleton::ReachBox<3>* reach,
                      std::size_t& skipped) const {
    for (std::size_t t = 0; t < mesh_.triangle_count(); ++t) {
      const Triangle e = element(mesh_, t);
      if (!(e.area > 0.0)) continue;  // zero area: no contribution
      const int level = levels_[t];
      const double sub_area = std::ldexp(e.area, -2 * level);
      Point point{};
      point.element = &e;
      for (int c = 0; c < 3; ++c) {
        point.corner_vertex[c] = e.vertex[c];
        point.normal[c] = e.unit_normal[c];
      }
      point.element_index = static_cast<std::uint32_t>(t);
      auto leaf = [&](const Barycentric& c0, const Barycentric& c1, const Barycentric& c2) {
        for (const TrianglePoint& q : rule_) {
          const auto& mu = q.barycentric;
          for (int v = 0; v < 3; ++v)
            point.corner_share[v] = mu[0] * c0[v] + mu[1] * c1[v] + mu[2] * c2[v];
          const double* l = point.corner_share;
          for (int k = 0; k < 3; ++k) {
            point.position[k] =
                l[0] * e.position[0][k] + l[1] * e.position[1][k] + l[2] * e.position[2][k];
            point.velocity[k] =
                l[0] * e.velocity[0][k] + l[1] * e.velocity[1][k] + l[2] * e.velocity[2][k];
          }
          point.measure_weight = sub_area * q.weight;
          visit(point);
        }
      };
      auto prune = [&](const Barycentric& c0, const Barycentric& c1, const Barycentric& c2,
                       int levels) {
        if (!reach) return false;
        double corner[3][3];
        const Barycentric* barycentric[3] = {&c0, &c1, &c2};
        for (int c = 0; c < 3; ++c) {
          const Barycentric& l = *barycentric[c];
          for (int k = 0; k < 3; ++k)
            corner[c][k] =
                l[0] * e.position[0][k] + l[1] * e.position[1][k] + l[2] * e.position[2][k];
        }
        const double* corners[3] = {corner[0], corner[1], corner[2]};
        if (!reach->misses(corners, 3)) return false;
        skipped += (std::size_t{1} << (2 * levels)) * rule_.size();
        return true;
      };
      split({1.0, 0.0, 0.0}, {0.0, 1.0, 0.0}, {0.0, 0.0, 1.0}, level, leaf, prune);
    }
  }

 private:
  std::span<const TrianglePoint> rule_;
  const BoundaryMesh3D& mesh_;
  std::span<const std::uint8_t> levels_;
};

// Distance of p to a triangle of positive area, given its distance to the triangle's plane. The
// result is never below plane_distance, so a caller may skip the call when plane_distance alone
// already exceeds what it is looking for.
double distance_to_triangle(const double* p, const Triangle& e, double plane_distance) {
  const double signed_height = dot(difference(p, e.position[0]), e.unit_normal);
  const double foot[3] = {p[0] - signed_height * e.unit_normal[0],
                          p[1] - signed_height * e.unit_normal[1],
                          p[2] - signed_height * e.unit_normal[2]};
  bool inside = true;
  for (int c = 0; c < 3 && inside; ++c) {
    const double* from = e.position[c];
    const double* to = e.position[(c + 1) % 3];
    inside = dot(cross(difference(to, from), difference(foot, from)), e.unit_normal) >= 0.0;
  }
  if (inside) return plane_distance;
  double closest = kInfinity;
  for (int c = 0; c < 3; ++c) {
    closest = std::min(closest,
                       skeleton::distance_to_segment<3>(p, e.position[c], e.position[(c + 1) % 3]));
  }
  return std::max(closest, plane_distance);
}

double Triangle::closest_distance(const double* particle, double closest_so_far) const {
  // The distance to the plane is a lower bound: most pairs end there.
  const double plane_distance = std::abs(dot(difference(particle, position[0]), unit_normal));
  if (!(plane_distance < closest_so_far)) return closest_so_far;
  return std::min(closest_so_far, distance_to_triangle(particle, *this, plane_distance));
}

void pre_refine(const ContactSettings3D& settings, const BoundaryMesh3D& mesh,
                std::vector<std::uint8_t>& pre_refinement) {
  pre_refinement.assign(mesh.triangle_count(), 0);
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
    const Triangle e = element(mesh, t);
    if (!(e.area > 0.0)) continue;
    pre_refinement[t] = static_cast<std::uint8_t>(
        triangle_refinement_level(longest_edge(e), settings.refinement_resolution, t));
  }
}

bool uses_pre_refinement(const ContactSettings3D& settings) {
  return settings.refinement_option == 2 || settings.refinement_option == 3;
}

}  // namespace

void BoundaryMesh3D::validate() const {
  skeleton::validate_mesh(kTriangleMesh, positions, velocities, triangles);
}

void ContactSettings3D::validate() const {
  law.validate();
  if (std::find(kTriangleRulePoints.begin(), kTriangleRulePoints.end(), quadrature_points) ==
      kTriangleRulePoints.end()) {
    throw std::invalid_argument("quadrature points per triangle must be 1, 3 or 7, got " +
                                std::to_string(quadrature_points));
  }
  if (refinement_option < kMinRefinementOption || refinement_option > kMaxRefinementOption) {
    throw std::invalid_argument(
        "refinement option must be 0 (none), 1 (recursive at every evaluation), 2 (pre-refined "
        "once) or 3 (pre-refined, then recursive), got " +
        std::to_string(refinement_option));
  }
  if (!std::isfinite(refinement_resolution) || refinement_resolution <= 0.0) {
    throw std::invalid_argument(
        "refinement resolution must be a positive length (typically the cut-off 2h), got " +
        std::to_string(refinement_resolution));
  }
}

int triangle_refinement_level(double longest_edge, double resolution, std::size_t triangle) {
  int level = 0;
  double edge = longest_edge;
  while (edge >= resolution) {
    if (level == kMaxRefinementLevel) too_fine(longest_edge, resolution, triangle);
    edge *= 0.5;
    ++level;
  }
  return level;
}

WallContact3D::WallContact3D(const ContactSettings3D& settings) : settings_(settings) {
  settings_.validate();
}

void WallContact3D::prepare(const BoundaryMesh3D& mesh) {
  if (!uses_pre_refinement(settings_)) return;
  mesh.validate();
  pre_refine(settings_, mesh, pre_refinement_);
  prepared_ = true;
}

void WallContact3D::prepare(std::vector<std::uint8_t> levels) {
  if (!uses_pre_refinement(settings_)) return;
  pre_refinement_ = std::move(levels);
  prepared_ = true;
}

std::vector<std::uint8_t> pre_refinement_levels(const ContactSettings3D& settings,
                                                const BoundaryMesh3D& mesh) {
  std::vector<std::uint8_t> levels(mesh.triangle_count(), 0);
  if (uses_pre_refinement(settings)) pre_refine(settings, mesh, levels);
  return levels;
}

ContactDiagnostics WallContact3D::compute(const BoundaryMesh3D& mesh,
                                          const ParticleArrays& particles,
                                          std::span<double> vertex_forces,
                                          WallSampleRecord* samples) {
  skeleton::check_evaluation_inputs(kTriangleMesh, particles, mesh.positions, mesh.velocities,
                                    mesh.triangles, vertex_forces);
  if (uses_pre_refinement(settings_)) {
    if (!prepared_) {
      prepare(mesh);
    } else if (pre_refinement_.size() != mesh.triangle_count()) {
      throw std::invalid_argument("the mesh has " + std::to_string(mesh.triangle_count()) +
                                  " triangles but was pre-refined (refinement option " +
                                  std::to_string(settings_.refinement_option) + ") with " +
                                  std::to_string(pre_refinement_.size()) +
                                  "; call prepare() after changing the mesh");
    }
  }
  plan_levels(settings_, mesh, pre_refinement_, levels_);
  return skeleton::evaluate_near_particles(TriangleSampling(settings_, mesh, levels_),
                                           settings_.law, particles, mesh.positions, vertex_forces,
                                           buffers_, samples);
}

ContactDiagnostics compute_all_pairs_3d(const ContactSettings3D& settings,
                                        const BoundaryMesh3D& mesh, const ParticleArrays& particles,
                                        std::span<double> vertex_forces,
                                        WallSampleRecord* samples) {
  settings.validate();
  skeleton::check_evaluation_inputs(kTriangleMesh, particles, mesh.positions, mesh.velocities,
                                    mesh.triangles, vertex_forces);
  std::vector<std::uint8_t> pre_refinement;
  if (uses_pre_refinement(settings)) pre_refine(settings, mesh, pre_refinement);
  std::vector<std::uint8_t> levels;
  plan_levels(settings, mesh, pre_refinement, levels);
  return skeleton::evaluate_all_pairs(TriangleSampling(settings, mesh, levels), settings.law,
                                      particles, vertex_forces, samples);
}

}  // namespace fsi::contact
