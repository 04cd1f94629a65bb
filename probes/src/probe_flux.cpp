// flux: the volume flux through a segment (2D, per unit depth) or a planar polygon (3D),
//   Q = integral over the section of sum_j V_j W(|x - x_j|) (v_j . n) dA,  V_j = m_j / rho_j,
// the SPH interpolation of the volume flux density without Shepard normalisation: inside the
// fluid the kernel sum is about 1 and the integrand is v . n, towards a free surface it falls to
// 0 with the fluid, so a section that is partly dry counts only its wet part. The integral is
// the midpoint rule on `samples` equal pieces of the segment (3D: of every triangle of the
// polygon's fan, each cut into samples^2 similar triangles). The normal n: 2D, the segment's
// direction from its first to its second point turned clockwise (a segment drawn upwards counts
// flow in +x); 3D, the right-hand rule of the vertex order. Parameters: the vertex count, the
// vertices' x, y, z, the samples.

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "probe_kind.hpp"

namespace fsi::probes::detail {
namespace {

using Vector = std::array<double, 3>;

Vector vertex(const ProbeDefinition& probe, std::size_t k) {
  return {probe.parameters[1 + 3 * k], probe.parameters[2 + 3 * k], probe.parameters[3 + 3 * k]};
}
std::size_t vertex_count(const ProbeDefinition& probe) {
  return static_cast<std::size_t>(probe.parameters[0]);
}
Vector minus(const Vector& a, const Vector& b) {
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}
Vector cross(const Vector& a, const Vector& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
double dot(const Vector& a, const Vector& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
double norm(const Vector& a) {
  return std::sqrt(dot(a, a));
}

// The section as sample points with weights (lengths or areas) and its unit normal.
struct Section {
  std::vector<Vector> points;
  std::vector<double> weights;
  Vector normal{};
};

Section section_of(const ProbeDefinition& probe, int dimension) {
  Section section;
  const auto samples = static_cast<std::size_t>(probe.parameters.back());
  const std::size_t count = vertex_count(probe);
  if (dimension == 2) {
    const Vector a = vertex(probe, 0), b = vertex(probe, 1), along = minus(b, a);
    const double length = norm(along);
    section.normal = {along[1] / length, -along[0] / length, 0.0};
    for (std::size_t s = 0; s < samples; ++s) {
      const double t = (static_cast<double>(s) + 0.5) / static_cast<double>(samples);
      section.points.push_back({a[0] + t * along[0], a[1] + t * along[1], 0.0});
      section.weights.push_back(length / static_cast<double>(samples));
    }
    return section;
  }
  const Vector origin = vertex(probe, 0);
  Vector area_vector{};
  for (std::size_t k = 1; k + 1 < count; ++k) {
    const Vector c = cross(minus(vertex(probe, k), origin), minus(vertex(probe, k + 1), origin));
    for (int i = 0; i < 3; ++i)
      area_vector[i] += c[i];
  }
  const double twice_area = norm(area_vector);
  for (int i = 0; i < 3; ++i)
    section.normal[i] = area_vector[i] / twice_area;
  const double n = static_cast<double>(samples);
  for (std::size_t k = 1; k + 1 < count; ++k) {
    const Vector p = vertex(probe, k), q = vertex(probe, k + 1);
    const Vector u = minus(p, origin), v = minus(q, origin);
    // Signed with the polygon's normal, so that a non-convex fan still sums to its area.
    const double piece = 0.5 * dot(cross(u, v), section.normal) / (n * n);
    auto add = [&](double i, double j) {
      section.points.push_back({origin[0] + (i * u[0] + j * v[0]) / n,
                                origin[1] + (i * u[1] + j * v[1]) / n,
                                origin[2] + (i * u[2] + j * v[2]) / n});
      section.weights.push_back(piece);
    };
    for (std::size_t i = 0; i < samples; ++i) {
      for (std::size_t j = 0; i + j < samples; ++j) {
        add(static_cast<double>(i) + 1.0 / 3.0, static_cast<double>(j) + 1.0 / 3.0);
        if (i + j + 1 < samples)
          add(static_cast<double>(i) + 2.0 / 3.0, static_cast<double>(j) + 2.0 / 3.0);
      }
    }
  }
  return section;
}

std::string problem(const ProbeDefinition& probe, int dimension) {
  const std::string where = "flux probe '" + probe.name + "'";
  if (probe.parameters.size() < 2) return where + " has no vertices";
  const double count = probe.parameters[0];
  const double wanted = dimension == 2 ? 2.0 : 3.0;
  if (count != std::floor(count) || count < wanted || count > 1000.0 ||
      (dimension == 2 && count != 2.0))
    return where + (dimension == 2 ? " needs a segment of 2 points" : " needs 3 to 1000 points");
  if (std::string counted = count_problem(probe, 2 + 3 * static_cast<std::size_t>(count));
      !counted.empty())
    return counted;
  const double samples = probe.parameters.back();
  if (samples < 1.0 || samples > 1000.0 || samples != std::floor(samples))
    return where + " needs 1 to 1000 samples";
  double size = 0.0;
  for (std::size_t k = 1; k < vertex_count(probe); ++k)
    size = std::max(size, norm(minus(vertex(probe, k), vertex(probe, 0))));
  if (!(size > 0.0)) return where + " has no extent";
  if (dimension == 3) {
    const Section section = section_of(probe, dimension);
    if (!std::isfinite(section.normal[0])) return where + " has no area (its points are in line)";
    for (std::size_t k = 0; k < vertex_count(probe); ++k) {
      if (std::abs(dot(minus(vertex(probe, k), vertex(probe, 0)), section.normal)) > 1e-9 * size)
        return where + " is not planar (point " + std::to_string(k + 1) + " is off the plane)";
    }
  }
  return {};
}

std::vector<Column> columns(const ProbeDefinition& probe, int dimension) {
  return {{probe.name + "_flux", per_depth(dimension, "m^2/s", "m^3/s")}};
}

void partials(const ProbeDefinition& probe, const ProbeContext& context,
              const ParticleSet& particles, const Kernel& kernel, const WallSamples&,
              std::span<double> sums, std::span<double>) {
  const int dimension = context.dimension;
  const Section section = section_of(probe, dimension);
  // Only particles within the kernel's support of the section's bounding box contribute.
  Vector lower, upper;
  lower.fill(std::numeric_limits<double>::infinity());
  upper.fill(-std::numeric_limits<double>::infinity());
  for (const Vector& point : section.points) {
    for (int k = 0; k < 3; ++k) {
      lower[k] = std::min(lower[k], point[k] - kernel.support);
      upper[k] = std::max(upper[k], point[k] + kernel.support);
    }
  }
  const double support2 = kernel.support * kernel.support;
  double flux = 0.0;
  for (std::size_t i = 0; i < particles.owned; ++i) {
    const double* x = &particles.positions[i * dimension];
    bool near = true;
    for (int k = 0; k < dimension; ++k)
      near = near && x[k] >= lower[k] && x[k] <= upper[k];
    if (!near) continue;
    double normal_velocity = 0.0;
    for (int k = 0; k < dimension; ++k)
      normal_velocity += particles.velocities[i * dimension + k] * section.normal[k];
    const double volume = particles.mass[i] / particles.density[i];
    for (std::size_t s = 0; s < section.points.size(); ++s) {
      const double distance2 = squared_distance(x, section.points[s].data(), dimension);
      if (distance2 < support2)
        flux += section.weights[s] * volume * kernel.value(std::sqrt(distance2)) * normal_velocity;
    }
  }
  sums[0] = flux;
}

void values(const ProbeDefinition&, const ProbeContext&, std::span<const double> sums,
            std::span<const double>, std::span<double> values) {
  values[0] = sums[0];
}

// Every vertex of the section moves with a body.
void place(std::span<double> parameters, const RigidPlacement& placement) {
  const auto vertices = static_cast<std::size_t>(parameters[0]);
  for (std::size_t k = 0; k < vertices; ++k)
    move_point(parameters, 1 + 3 * k, placement);
}

}  // namespace

KindRules flux_probe_rules() {
  return {ProbeKind::Flux, "flux",   problem, columns, one_partial,
          no_partials,     partials, values,  nullptr, place};
}

}  // namespace fsi::probes::detail
