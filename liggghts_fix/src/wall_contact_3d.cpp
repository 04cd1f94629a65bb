#include "fsi/contact/wall_contact_3d.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <string>

#include "fsi/contact/triangle_quadrature.hpp"

namespace fsi::contact {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();
// The cell search covers [s - r, s + r] widened by this fraction of r, so that a pair accepted by
// the rounded test |x - s|^2 < r^2 is never in a cell the search skipped.
constexpr double kSearchMargin = 1e-9;

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
struct Element {
  std::uint32_t vertex[3];
  const double* position[3];
  const double* velocity[3];
  double area;
  Vector unit_normal;  // only meaningful when area > 0
};

Element element(const BoundaryMesh3D& mesh, std::size_t triangle) {
  Element e{};
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

double longest_edge(const Element& e) {
  double longest = 0.0;
  for (int c = 0; c < 3; ++c) {
    longest = std::max(longest, norm(difference(e.position[(c + 1) % 3], e.position[c])));
  }
  return longest;
}

// One sampling point, with what the pair kernel needs of its triangle.
struct SamplingPoint {
  double position[3];
  double velocity[3];
  double barycentric[3];  // with respect to the original triangle (eq. 4.11 in 3D)
  double area_weight;     // A_sub * w_k
  const Element* element;
};

using Barycentric = std::array<double, 3>;

Barycentric midpoint(const Barycentric& a, const Barycentric& b) {
  return {0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1]), 0.5 * (a[2] + b[2])};
}

// Splits the barycentric triangle (c0, c1, c2) by its edge midpoints, `levels` times, and calls
// leaf(corner0, corner1, corner2) for every resulting sub-triangle.
template <class Leaf>
void split(const Barycentric& c0, const Barycentric& c1, const Barycentric& c2, int levels,
           Leaf& leaf) {
  if (levels == 0) {
    leaf(c0, c1, c2);
    return;
  }
  const Barycentric m01 = midpoint(c0, c1);
  const Barycentric m12 = midpoint(c1, c2);
  const Barycentric m20 = midpoint(c2, c0);
  split(c0, m01, m20, levels - 1, leaf);
  split(m01, c1, m12, levels - 1, leaf);
  split(m20, m12, c2, levels - 1, leaf);
  split(m12, m20, m01, levels - 1, leaf);
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
    const Element e = element(mesh, t);
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

// Calls visit(point) for every sampling point of the refined mesh, with the levels of
// plan_levels().
template <class Visit>
void for_each_sampling_point(const ContactSettings3D& settings, const BoundaryMesh3D& mesh,
                             std::span<const std::uint8_t> levels, Visit&& visit) {
  const auto rule = triangle_rule(settings.quadrature_points);
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
    const Element e = element(mesh, t);
    if (!(e.area > 0.0)) continue;  // zero area: no contribution
    const int level = levels[t];
    const double sub_area = std::ldexp(e.area, -2 * level);
    SamplingPoint point{};
    point.element = &e;
    auto leaf = [&](const Barycentric& c0, const Barycentric& c1, const Barycentric& c2) {
      for (const TrianglePoint& q : rule) {
        const auto& mu = q.barycentric;
        for (int v = 0; v < 3; ++v)
          point.barycentric[v] = mu[0] * c0[v] + mu[1] * c1[v] + mu[2] * c2[v];
        const double* l = point.barycentric;
        for (int k = 0; k < 3; ++k) {
          point.position[k] =
              l[0] * e.position[0][k] + l[1] * e.position[1][k] + l[2] * e.position[2][k];
          point.velocity[k] =
              l[0] * e.velocity[0][k] + l[1] * e.velocity[1][k] + l[2] * e.velocity[2][k];
        }
        point.area_weight = sub_area * q.weight;
        visit(point);
      }
    };
    split({1.0, 0.0, 0.0}, {0.0, 1.0, 0.0}, {0.0, 0.0, 1.0}, level, leaf);
  }
}

double distance_to_segment(const double* p, const double* a, const double* b) {
  const Vector edge = difference(b, a);
  const Vector offset = difference(p, a);
  const double length2 = dot(edge, edge);
  double t = 0.0;
  if (length2 > 0.0) t = std::clamp(dot(offset, edge) / length2, 0.0, 1.0);
  return norm({offset[0] - t * edge[0], offset[1] - t * edge[1], offset[2] - t * edge[2]});
}

// Distance of p to a triangle of positive area, given its distance to the triangle's plane. The
// result is never below plane_distance, so a caller may skip the call when plane_distance alone
// already exceeds what it is looking for.
double distance_to_triangle(const double* p, const Element& e, double plane_distance) {
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
    closest = std::min(closest, distance_to_segment(p, e.position[c], e.position[(c + 1) % 3]));
  }
  return std::max(closest, plane_distance);
}

// Accumulates everything of one evaluation; the pair kernel is the only place forces are made.
class PairKernel {
 public:
  PairKernel(const ForceLaw& law, const ParticleArrays& particles, std::span<double> vertex_forces,
             std::vector<std::uint8_t>& in_range, ContactDiagnostics& diagnostics)
      : law_(law),
        range2_(law.range() * law.range()),
        particles_(particles),
        vertex_forces_(vertex_forces.data()),
        in_range_(in_range),
        diagnostics_(diagnostics) {}

  void operator()(const SamplingPoint& s, std::size_t i) {
    const double* x = particles_.positions + 3 * i;
    const double dx[3] = {x[0] - s.position[0], x[1] - s.position[1], x[2] - s.position[2]};
    const double distance2 = dx[0] * dx[0] + dx[1] * dx[1] + dx[2] * dx[2];
    if (distance2 >= range2_) return;
    const double distance = std::sqrt(distance2);
    // At distance 0 the repulsion has no direction and contributes nothing.
    const double along_line = distance > 0.0 ? law_.repulsion(distance) / distance : 0.0;
    const double friction = law_.viscous_scale * law_.viscous_weight(distance);
    const double* u = particles_.velocities + 3 * i;
    double force[3];
    for (int k = 0; k < 3; ++k) {
      force[k] = (along_line * dx[k] - friction * (u[k] - s.velocity[k])) * s.area_weight;
    }

    double* f = particles_.forces + 3 * i;
    for (int k = 0; k < 3; ++k) {
      f[k] += force[k];
      diagnostics_.force_on_particles[k] += force[k];
    }
    // Counterforce on the structure, redistributed to the vertices by barycentric weighting.
    for (int v = 0; v < 3; ++v) {
      double* target = vertex_forces_ + 3 * std::size_t{s.element->vertex[v]};
      for (int k = 0; k < 3; ++k)
        target[k] -= s.barycentric[v] * force[k];
    }

    diagnostics_.pair_force_magnitude_sum +=
        std::sqrt(force[0] * force[0] + force[1] * force[1] + force[2] * force[2]);
    ++diagnostics_.pair_count;
    if (!in_range_[i]) {
      in_range_[i] = 1;
      ++diagnostics_.particles_in_range;
    }
    const double plane_distance =
        std::abs(dot(difference(x, s.element->position[0]), s.element->unit_normal));
    if (plane_distance < diagnostics_.closest_distance) {
      diagnostics_.closest_distance = std::min(diagnostics_.closest_distance,
                                               distance_to_triangle(x, *s.element, plane_distance));
    }
  }

 private:
  const ForceLaw& law_;
  double range2_;
  const ParticleArrays& particles_;
  double* vertex_forces_;
  std::vector<std::uint8_t>& in_range_;
  ContactDiagnostics& diagnostics_;
};

bool takes_part(const ParticleArrays& particles, std::size_t i) {
  return particles.group_mask.empty() || (particles.group_mask[i] & particles.group_bit) != 0;
}

std::string coordinates(const double* x) {
  char text[96];
  std::snprintf(text, sizeof text, "(%.6g, %.6g, %.6g)", x[0], x[1], x[2]);
  return text;
}

void check_particles(const ParticleArrays& particles) {
  if (particles.count > 0 && (!particles.positions || !particles.velocities || !particles.forces)) {
    throw std::invalid_argument("particle arrays are missing positions, velocities or forces");
  }
  if (!particles.group_mask.empty() && particles.group_mask.size() < particles.count) {
    throw std::invalid_argument("group mask is shorter than the particle count");
  }
  if (particles.count > std::numeric_limits<std::uint32_t>::max()) {
    throw std::invalid_argument("more than 2^32 particles on one process");
  }
  for (std::size_t i = 0; i < particles.count; ++i) {
    if (!takes_part(particles, i)) continue;
    const double* x = particles.positions + 3 * i;
    const double* u = particles.velocities + 3 * i;
    for (int k = 0; k < 3; ++k) {
      if (!std::isfinite(x[k]) || !std::isfinite(u[k])) {
        throw std::invalid_argument(
            "particle " + std::to_string(i) + " has a non-finite position " + coordinates(x) +
            " or velocity " + coordinates(u) +
            "; the SPH state is broken (check the time step and the wall forces)");
      }
    }
  }
}

void check_vertex_forces(const BoundaryMesh3D& mesh, std::span<const double> vertex_forces) {
  if (vertex_forces.size() != mesh.positions.size()) {
    throw std::invalid_argument("vertex force buffer holds " +
                                std::to_string(vertex_forces.size()) + " values, the mesh needs " +
                                std::to_string(mesh.positions.size()) + " (3 per vertex)");
  }
}

void start_outputs(std::span<double> vertex_forces, ContactDiagnostics& diagnostics) {
  std::fill(vertex_forces.begin(), vertex_forces.end(), 0.0);
  diagnostics = ContactDiagnostics{};
  diagnostics.closest_distance = kInfinity;
}

void finish_diagnostics(std::span<const double> vertex_forces, ContactDiagnostics& diagnostics) {
  for (std::size_t k = 0; k < vertex_forces.size(); k += 3) {
    for (int c = 0; c < 3; ++c)
      diagnostics.force_on_structure[c] += vertex_forces[k + c];
  }
}

void pre_refine(const ContactSettings3D& settings, const BoundaryMesh3D& mesh,
                std::vector<std::uint8_t>& pre_refinement) {
  pre_refinement.assign(mesh.triangle_count(), 0);
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
    const Element e = element(mesh, t);
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
  if (positions.size() % 3 != 0 || velocities.size() != positions.size()) {
    throw std::invalid_argument(
        "3D boundary mesh needs x,y,z per vertex for positions and velocities (" +
        std::to_string(positions.size()) + " position and " + std::to_string(velocities.size()) +
        " velocity values)");
  }
  if (triangles.size() % 3 != 0) {
    throw std::invalid_argument("3D boundary triangles need three vertex indices each (" +
                                std::to_string(triangles.size()) + " indices given)");
  }
  for (std::size_t k = 0; k < triangles.size(); ++k) {
    if (triangles[k] >= vertex_count()) {
      throw std::invalid_argument("triangle " + std::to_string(k / 3) + " refers to vertex " +
                                  std::to_string(triangles[k]) + " but the mesh has " +
                                  std::to_string(vertex_count()) + " vertices (0 to " +
                                  std::to_string(vertex_count()) + " - 1)");
    }
  }
  for (std::size_t k = 0; k < positions.size(); ++k) {
    if (!std::isfinite(positions[k]) || !std::isfinite(velocities[k])) {
      const std::size_t vertex = k / 3;
      throw std::invalid_argument("vertex " + std::to_string(vertex) + " has a non-finite " +
                                  "position " + coordinates(&positions[3 * vertex]) +
                                  " or velocity " + coordinates(&velocities[3 * vertex]));
    }
  }
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

ContactDiagnostics WallContact3D::compute(const BoundaryMesh3D& mesh,
                                          const ParticleArrays& particles,
                                          std::span<double> vertex_forces) {
  // Every check before anything is written.
  check_particles(particles);
  mesh.validate();
  check_vertex_forces(mesh, vertex_forces);
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
  std::vector<std::uint8_t> levels;
  plan_levels(settings_, mesh, pre_refinement_, levels);

  ContactDiagnostics diagnostics;
  start_outputs(vertex_forces, diagnostics);
  mark_particles_near_mesh(particles, mesh.positions, 3, settings_.law.range(), near_);
  grid_.build(particles.positions, near_, settings_.law.range());
  in_range_.assign(particles.count, 0);
  PairKernel kernel(settings_.law, particles, vertex_forces, in_range_, diagnostics);
  const double reach = settings_.law.range() * (1.0 + kSearchMargin);

  for_each_sampling_point(settings_, mesh, levels, [&](const SamplingPoint& s) {
    ++diagnostics.sampling_points;
    diagnostics.candidate_pairs +=
        grid_.visit_near(s.position, reach, [&](std::uint32_t i) { kernel(s, i); });
  });
  finish_diagnostics(vertex_forces, diagnostics);
  return diagnostics;
}

ContactDiagnostics compute_all_pairs_3d(const ContactSettings3D& settings,
                                        const BoundaryMesh3D& mesh, const ParticleArrays& particles,
                                        std::span<double> vertex_forces) {
  settings.validate();
  check_particles(particles);
  mesh.validate();
  check_vertex_forces(mesh, vertex_forces);
  std::vector<std::uint8_t> pre_refinement;
  if (uses_pre_refinement(settings)) pre_refine(settings, mesh, pre_refinement);
  std::vector<std::uint8_t> levels;
  plan_levels(settings, mesh, pre_refinement, levels);

  ContactDiagnostics diagnostics;
  start_outputs(vertex_forces, diagnostics);
  std::vector<std::uint8_t> in_range(particles.count, 0);
  PairKernel kernel(settings.law, particles, vertex_forces, in_range, diagnostics);
  for_each_sampling_point(settings, mesh, levels, [&](const SamplingPoint& s) {
    ++diagnostics.sampling_points;
    for (std::size_t i = 0; i < particles.count; ++i) {
      if (!takes_part(particles, i)) continue;
      ++diagnostics.candidate_pairs;
      kernel(s, i);
    }
  });
  finish_diagnostics(vertex_forces, diagnostics);
  return diagnostics;
}

}  // namespace fsi::contact
