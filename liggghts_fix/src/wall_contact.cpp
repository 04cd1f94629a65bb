#include "fsi/contact/wall_contact.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "contact_skeleton.hpp"
#include "fsi/contact/quadrature.hpp"

namespace fsi::contact {
namespace {

constexpr skeleton::MeshShape kSegmentMesh{2, 2, "segment"};

// A segment in the current configuration: its end points, for the closest-distance diagnostic.
struct Segment {
  const double* end_a;
  const double* end_b;

  double closest_distance(const double* particle, double closest_so_far) const {
    return std::min(closest_so_far, skeleton::distance_to_segment<2>(particle, end_a, end_b));
  }
};

// Every segment bisected until its pieces are shorter than the resolution, every piece sampled by
// the Gauss–Legendre rule; positions and velocities interpolated linearly (eq. 4.5/4.6).
class SegmentSampling {
 public:
  using Point = skeleton::SamplingPoint<Segment, 2, 2>;

  SegmentSampling(const ContactSettings& settings, const BoundaryMesh2D& mesh)
      : rule_(gauss_legendre(settings.gauss_points)),
        resolution_(settings.refinement_resolution),
        mesh_(mesh) {}

  template <class Visit>
  void for_each_point(Visit&& visit, const skeleton::ReachBox<2>* reach,
                      std::size_t& skipped) const {
    const double* r = mesh_.positions.data();
    const double* v = mesh_.velocities.data();
    for (std::size_t segment = 0; segment < mesh_.segment_count(); ++segment) {
      const std::uint32_t a = mesh_.segments[2 * segment];
      const std::uint32_t b = mesh_.segments[2 * segment + 1];
      const double* ra = r + 2 * a;
      const double* rb = r + 2 * b;
      const double* va = v + 2 * a;
      const double* vb = v + 2 * b;
      const Segment element{ra, rb};
      const double length = std::hypot(rb[0] - ra[0], rb[1] - ra[1]);
      const int levels = bisection_levels(length, resolution_);
      const std::size_t pieces = std::size_t{1} << levels;
      const double* ends[2] = {ra, rb};
      if (reach && reach->misses(ends, 2)) {
        skipped += pieces * rule_.size();
        continue;
      }
      const double piece_fraction = 1.0 / static_cast<double>(pieces);
      const double piece_length = length * piece_fraction;
      Point point{};
      point.element = &element;
      point.corner_vertex[0] = a;
      point.corner_vertex[1] = b;
      point.element_index = static_cast<std::uint32_t>(segment);
      const double inverse_length = length > 0.0 ? 1.0 / length : 0.0;  // 0: no normal
      point.normal[0] = (rb[1] - ra[1]) * inverse_length;
      point.normal[1] = -(rb[0] - ra[0]) * inverse_length;
      for (std::size_t piece = 0; piece < pieces; ++piece) {
        const double start = static_cast<double>(piece) * piece_fraction;
        if (reach && pieces > 1) {
          const double end = start + piece_fraction;
          const double from[2] = {(1.0 - start) * ra[0] + start * rb[0],
                                  (1.0 - start) * ra[1] + start * rb[1]};
          const double to[2] = {(1.0 - end) * ra[0] + end * rb[0],
                                (1.0 - end) * ra[1] + end * rb[1]};
          const double* piece_ends[2] = {from, to};
          if (reach->misses(piece_ends, 2)) {
            skipped += rule_.size();
            continue;
          }
        }
        for (const QuadraturePoint& q : rule_) {
          const double g = start + q.position * piece_fraction;  // along the segment, eq. 4.5
          point.corner_share[0] = 1.0 - g;
          point.corner_share[1] = g;
          point.measure_weight = piece_length * q.weight;
          for (int k = 0; k < 2; ++k) {
            point.position[k] = (1.0 - g) * ra[k] + g * rb[k];
            point.velocity[k] = (1.0 - g) * va[k] + g * vb[k];
          }
          visit(point);
        }
      }
    }
  }

 private:
  std::span<const QuadraturePoint> rule_;
  double resolution_;
  const BoundaryMesh2D& mesh_;
};

}  // namespace

void BoundaryMesh2D::validate() const {
  skeleton::validate_mesh(kSegmentMesh, positions, velocities, segments);
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
                                          std::span<double> vertex_forces,
                                          WallSampleRecord* samples) {
  skeleton::check_evaluation_inputs(kSegmentMesh, particles, mesh.positions, mesh.velocities,
                                    mesh.segments, vertex_forces);
  return skeleton::evaluate_near_particles(SegmentSampling(settings_, mesh), settings_.law,
                                           particles, mesh.positions, vertex_forces, buffers_,
                                           samples);
}

ContactDiagnostics compute_all_pairs(const ContactSettings& settings, const BoundaryMesh2D& mesh,
                                     const ParticleArrays& particles,
                                     std::span<double> vertex_forces, WallSampleRecord* samples) {
  settings.validate();
  skeleton::check_evaluation_inputs(kSegmentMesh, particles, mesh.positions, mesh.velocities,
                                    mesh.segments, vertex_forces);
  return skeleton::evaluate_all_pairs(SegmentSampling(settings, mesh), settings.law, particles,
                                      vertex_forces, samples);
}

}  // namespace fsi::contact
