#include "fsi/contact/wall_contact.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "fsi/contact/quadrature.hpp"

namespace fsi::contact {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// One Gauss point on a (sub-)segment, with what the pair kernel needs of its segment.
struct SamplingPoint {
  double position[2];
  double velocity[2];
  double along;          // g in [0, 1] on the original segment (eq. 4.5/4.6)
  double length_weight;  // l_sub * w_k
  std::uint32_t vertex_a;
  std::uint32_t vertex_b;
  const double* end_a;  // segment end points, for the closest-distance diagnostic
  const double* end_b;
};

// Calls visit(point) for every sampling point of the refined mesh.
template <class Visit>
void for_each_sampling_point(const ContactSettings& settings, const BoundaryMesh2D& mesh,
                             Visit&& visit) {
  const auto rule = gauss_legendre(settings.gauss_points);
  const double* r = mesh.positions.data();
  const double* v = mesh.velocities.data();
  for (std::size_t segment = 0; segment < mesh.segment_count(); ++segment) {
    const std::uint32_t a = mesh.segments[2 * segment];
    const std::uint32_t b = mesh.segments[2 * segment + 1];
    const double* ra = r + 2 * a;
    const double* rb = r + 2 * b;
    const double* va = v + 2 * a;
    const double* vb = v + 2 * b;
    const double length = std::hypot(rb[0] - ra[0], rb[1] - ra[1]);
    const int levels = bisection_levels(length, settings.refinement_resolution);
    const std::size_t pieces = std::size_t{1} << levels;
    const double piece_fraction = 1.0 / static_cast<double>(pieces);
    const double piece_length = length * piece_fraction;
    SamplingPoint point{};
    point.vertex_a = a;
    point.vertex_b = b;
    point.end_a = ra;
    point.end_b = rb;
    for (std::size_t piece = 0; piece < pieces; ++piece) {
      const double start = static_cast<double>(piece) * piece_fraction;
      for (const QuadraturePoint& q : rule) {
        const double g = start + q.position * piece_fraction;
        point.along = g;
        point.length_weight = piece_length * q.weight;
        for (int k = 0; k < 2; ++k) {
          point.position[k] = (1.0 - g) * ra[k] + g * rb[k];
          point.velocity[k] = (1.0 - g) * va[k] + g * vb[k];
        }
        visit(point);
      }
    }
  }
}

double distance_to_segment(const double* p, const double* a, const double* b) {
  const double ex = b[0] - a[0];
  const double ey = b[1] - a[1];
  const double length2 = ex * ex + ey * ey;
  double t = 0.0;
  if (length2 > 0.0) t = std::clamp(((p[0] - a[0]) * ex + (p[1] - a[1]) * ey) / length2, 0.0, 1.0);
  const double dx = p[0] - a[0] - t * ex;
  const double dy = p[1] - a[1] - t * ey;
  return std::sqrt(dx * dx + dy * dy);
}

// Accumulates everything of one evaluation; the pair kernel is the only place forces are made.
class PairKernel {
 public:
  PairKernel(const ForceLaw& law, const ParticleArrays& particles, std::span<double> vertex_forces,
             std::vector<std::uint8_t>& in_range, ContactDiagnostics& diagnostics)
      : law_(law),
        cutoff2_(law.range() * law.range()),
        particles_(particles),
        vertex_forces_(vertex_forces.data()),
        in_range_(in_range),
        diagnostics_(diagnostics) {}

  void operator()(const SamplingPoint& s, std::size_t i) {
    const double* x = particles_.positions + 3 * i;
    const double dx = x[0] - s.position[0];
    const double dy = x[1] - s.position[1];
    const double distance2 = dx * dx + dy * dy;
    if (distance2 >= cutoff2_) return;
    const double distance = std::sqrt(distance2);
    double fx = 0.0;
    double fy = 0.0;
    if (distance > 0.0) {
      const double along_line = law_.repulsion(distance) / distance;
      fx = along_line * dx;
      fy = along_line * dy;
    }
    const double* u = particles_.velocities + 3 * i;
    const double friction = law_.viscous_scale * law_.viscous_weight(distance);
    fx -= friction * (u[0] - s.velocity[0]);
    fy -= friction * (u[1] - s.velocity[1]);
    fx *= s.length_weight;
    fy *= s.length_weight;

    double* f = particles_.forces + 3 * i;
    f[0] += fx;
    f[1] += fy;
    // Counterforce on the structure, redistributed to the vertices by eq. (4.11).
    const double to_b = s.along;
    const double to_a = 1.0 - s.along;
    vertex_forces_[2 * s.vertex_a] -= to_a * fx;
    vertex_forces_[2 * s.vertex_a + 1] -= to_a * fy;
    vertex_forces_[2 * s.vertex_b] -= to_b * fx;
    vertex_forces_[2 * s.vertex_b + 1] -= to_b * fy;

    diagnostics_.force_on_particles[0] += fx;
    diagnostics_.force_on_particles[1] += fy;
    diagnostics_.pair_force_magnitude_sum += std::sqrt(fx * fx + fy * fy);
    ++diagnostics_.pair_count;
    if (!in_range_[i]) {
      in_range_[i] = 1;
      ++diagnostics_.particles_in_range;
    }
    diagnostics_.closest_distance =
        std::min(diagnostics_.closest_distance, distance_to_segment(x, s.end_a, s.end_b));
  }

 private:
  const ForceLaw& law_;
  double cutoff2_;
  const ParticleArrays& particles_;
  double* vertex_forces_;
  std::vector<std::uint8_t>& in_range_;
  ContactDiagnostics& diagnostics_;
};

bool takes_part(const ParticleArrays& particles, std::size_t i) {
  return particles.group_mask.empty() || (particles.group_mask[i] & particles.group_bit) != 0;
}

void prepare_outputs(const BoundaryMesh2D& mesh, std::span<double> vertex_forces,
                     ContactDiagnostics& diagnostics) {
  if (vertex_forces.size() != mesh.positions.size()) {
    throw std::invalid_argument("vertex force buffer holds " +
                                std::to_string(vertex_forces.size()) + " values, the mesh needs " +
                                std::to_string(mesh.positions.size()));
  }
  std::fill(vertex_forces.begin(), vertex_forces.end(), 0.0);
  diagnostics = ContactDiagnostics{};
  diagnostics.closest_distance = kInfinity;
}

void finish_diagnostics(std::span<const double> vertex_forces, ContactDiagnostics& diagnostics) {
  for (std::size_t k = 0; k < vertex_forces.size(); k += 2) {
    diagnostics.force_on_structure[0] += vertex_forces[k];
    diagnostics.force_on_structure[1] += vertex_forces[k + 1];
  }
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
  // A non-finite particle would poison the cell grid and the force array: refuse it before any
  // force is written.
  for (std::size_t i = 0; i < particles.count; ++i) {
    if (!takes_part(particles, i)) continue;
    const double* x = particles.positions + 3 * i;
    const double* u = particles.velocities + 3 * i;
    if (!std::isfinite(x[0]) || !std::isfinite(x[1]) || !std::isfinite(x[2]) ||
        !std::isfinite(u[0]) || !std::isfinite(u[1]) || !std::isfinite(u[2])) {
      throw NonFiniteParticle(
          i, "particle " + std::to_string(i) +
                 " (local index) has a non-finite position or velocity; the fluid "
                 "has blown up: reduce the time step or raise the wall repulsion k");
    }
  }
}

}  // namespace

void BoundaryMesh2D::validate() const {
  if (positions.size() % 2 != 0 || velocities.size() != positions.size()) {
    throw std::invalid_argument(
        "2D boundary mesh needs x,y per vertex for positions and velocities (" +
        std::to_string(positions.size()) + " position and " + std::to_string(velocities.size()) +
        " velocity values)");
  }
  if (segments.size() % 2 != 0) {
    throw std::invalid_argument("2D boundary segments need two vertex indices each");
  }
  for (std::size_t k = 0; k < segments.size(); ++k) {
    if (segments[k] >= vertex_count()) {
      throw std::invalid_argument("segment " + std::to_string(k / 2) + " refers to vertex " +
                                  std::to_string(segments[k]) + " but the mesh has " +
                                  std::to_string(vertex_count()) + " vertices");
    }
  }
  for (std::size_t k = 0; k < positions.size(); ++k) {
    if (!std::isfinite(positions[k]) || !std::isfinite(velocities[k])) {
      throw std::invalid_argument("vertex " + std::to_string(k / 2) +
                                  " has a non-finite position or velocity");
    }
  }
}

void ContactSettings::validate() const {
  law.validate();
  if (gauss_points < kMinGaussPoints || gauss_points > kMaxGaussPoints) {
    throw std::invalid_argument("gauss points must be 1 to 5, got " + std::to_string(gauss_points));
  }
  if (!std::isfinite(refinement_resolution) || refinement_resolution <= 0.0) {
    throw std::invalid_argument("refinement resolution must be a positive length, got " +
                                std::to_string(refinement_resolution));
  }
}

void ContactDiagnostics::merge(const ContactDiagnostics& other) {
  for (int k = 0; k < 3; ++k) {
    force_on_particles[k] += other.force_on_particles[k];
    force_on_structure[k] += other.force_on_structure[k];
  }
  pair_force_magnitude_sum += other.pair_force_magnitude_sum;
  particles_in_range += other.particles_in_range;
  pair_count += other.pair_count;
  candidate_pairs += other.candidate_pairs;
  sampling_points += other.sampling_points;
  closest_distance = std::min(closest_distance, other.closest_distance);
}

void mark_particles_near_mesh(const ParticleArrays& particles,
                              std::span<const double> vertex_positions, int dimension, double range,
                              std::vector<std::uint8_t>& near) {
  near.assign(particles.count, 0);
  if (vertex_positions.empty()) return;
  double low[3] = {kInfinity, kInfinity, kInfinity};
  double high[3] = {-kInfinity, -kInfinity, -kInfinity};
  for (std::size_t v = 0; v < vertex_positions.size(); v += static_cast<std::size_t>(dimension)) {
    for (int k = 0; k < dimension; ++k) {
      low[k] = std::min(low[k], vertex_positions[v + k]);
      high[k] = std::max(high[k], vertex_positions[v + k]);
    }
  }
  // A relative margin so that a particle exactly at the range is not lost to round-off.
  const double reach = range * (1.0 + 1e-9);
  for (std::size_t i = 0; i < particles.count; ++i) {
    if (!takes_part(particles, i)) continue;
    bool inside = true;
    for (int k = 0; k < dimension && inside; ++k) {
      const double x = particles.positions[3 * i + k];
      inside = x >= low[k] - reach && x <= high[k] + reach;
    }
    near[i] = inside ? 1 : 0;
  }
}

int bisection_levels(double length, double resolution) {
  // 2^60 pieces would be absurd: it means the resolution is far too small for the mesh.
  constexpr int kMaxLevels = 40;
  int levels = 0;
  double piece = length;
  while (piece >= resolution && levels < kMaxLevels) {
    piece *= 0.5;
    ++levels;
  }
  return levels;
}

WallContact2D::WallContact2D(const ContactSettings& settings) : settings_(settings) {
  settings_.validate();
}

ContactDiagnostics WallContact2D::compute(const BoundaryMesh2D& mesh,
                                          const ParticleArrays& particles,
                                          std::span<double> vertex_forces) {
  check_particles(particles);
  ContactDiagnostics diagnostics;
  prepare_outputs(mesh, vertex_forces, diagnostics);
  const double range = settings_.law.range();
  mark_particles_near_mesh(particles, mesh.positions, 2, range, near_);
  grid_.build(particles.positions, near_, range);
  const double reach = range * (1.0 + 1e-9);  // round-off must not lose a pair at the range
  in_range_.assign(particles.count, 0);
  PairKernel kernel(settings_.law, particles, vertex_forces, in_range_, diagnostics);

  for_each_sampling_point(settings_, mesh, [&](const SamplingPoint& s) {
    ++diagnostics.sampling_points;
    diagnostics.candidate_pairs +=
        grid_.visit_near(s.position, reach, [&](std::uint32_t i) { kernel(s, i); });
  });
  finish_diagnostics(vertex_forces, diagnostics);
  return diagnostics;
}

ContactDiagnostics compute_all_pairs(const ContactSettings& settings, const BoundaryMesh2D& mesh,
                                     const ParticleArrays& particles,
                                     std::span<double> vertex_forces) {
  settings.validate();
  check_particles(particles);
  ContactDiagnostics diagnostics;
  prepare_outputs(mesh, vertex_forces, diagnostics);
  std::vector<std::uint8_t> in_range(particles.count, 0);
  PairKernel kernel(settings.law, particles, vertex_forces, in_range, diagnostics);
  for_each_sampling_point(settings, mesh, [&](const SamplingPoint& s) {
    ++diagnostics.sampling_points;
    for (std::size_t i = 0; i < particles.count; ++i) {
      if (takes_part(particles, i)) kernel(s, i);
    }
  });
  finish_diagnostics(vertex_forces, diagnostics);
  return diagnostics;
}

}  // namespace fsi::contact
