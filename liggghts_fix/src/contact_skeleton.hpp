#pragma once
// The one skeleton of the wall contact (thesis ch. 4) that 2D segments and 3D triangles share:
// input checks, the pair kernel (the only place forces are made), the diagnostics and the
// redistribution of eq. (4.11)/(4.12). What differs between the two is only how an element is
// sampled, so each half supplies a sampling: an object with
//   using Point = SamplingPoint<Element, Dimension, Corners>;
//   template <class Visit>
//   void for_each_point(Visit&& visit, const ReachBox<Dimension>* reach,
//                       std::size_t& skipped) const;  // visit(const Point&)
// that skips, when reach is not null, every (sub-)element whose corners' bounding box misses
// *reach, adding the sampling points it would have had to `skipped` (a rank then evaluates only
// its share of the boundary: thesis §7.1),
// and an Element type with
//   double closest_distance(const double* particle, double closest_so_far) const;
// returning min(closest_so_far, distance of the particle to the element).
// Internal to fsi_contact: wall_contact.cpp and wall_contact_3d.cpp are its only users.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>
#include <string>
#include <vector>

#include "fsi/contact/cell_grid.hpp"
#include "fsi/contact/contact_evaluation.hpp"
#include "fsi/contact/force_law.hpp"
#include "fsi/contact/redistribution.hpp"

namespace fsi::contact::skeleton {

// One quadrature point on a (sub-)element, with what the pair kernel needs of its element.
template <class ElementType, int Dimension, int Corners>
struct SamplingPoint {
  using Element = ElementType;
  static constexpr int kDimension = Dimension;
  double position[Dimension];
  double velocity[Dimension];
  double measure_weight;     // length (2D) or area (3D) of the sub-element times the rule's weight
  double normal[Dimension];  // unit normal of the element (WallSampleRecord's orientation)
  std::uint32_t element_index;
  std::uint32_t corner_vertex[Corners];
  double corner_share[Corners];  // eq. (4.11/4.12) weights of the point in the original element
  const Element* element;
};

// The box a sampling point must lie in to have a partner particle: the bounding box of the
// particles that can reach the mesh, widened by the search reach. A sampling point lies in the
// bounding box of its (sub-)element's corners, so an element whose box misses this one has no
// pair: skipping it changes nothing but the work.
template <int Dimension>
struct ReachBox {
  double low[Dimension];
  double high[Dimension];

  // True when the bounding box of `count` corners lies entirely outside this box.
  bool misses(const double* const* corners, int count) const {
    for (int k = 0; k < Dimension; ++k) {
      bool all_below = true;
      bool all_above = true;
      for (int c = 0; c < count; ++c) {
        all_below = all_below && corners[c][k] < low[k];
        all_above = all_above && corners[c][k] > high[k];
      }
      if (all_below || all_above) return true;
    }
    return false;
  }
};

inline bool takes_part(const ParticleArrays& particles, std::size_t i) {
  return particles.group_mask.empty() || (particles.group_mask[i] & particles.group_bit) != 0;
}

// The shape of a mesh in words, for the messages of validate_mesh.
struct MeshShape {
  int dimension;
  int corners;               // vertex indices per element
  const char* element_name;  // "segment", "triangle"
};

// Throws std::invalid_argument on inconsistent array sizes, an element referring to a missing
// vertex (naming both) or a vertex with a non-finite position or velocity (naming it).
void validate_mesh(const MeshShape& shape, std::span<const double> positions,
                   std::span<const double> velocities, std::span<const std::uint32_t> elements);

// The checks every evaluation makes before it writes anything: the particle arrays (throws
// NonFiniteParticle for a participating particle with a non-finite position or velocity), the
// size of the vertex force buffer (like vertex_positions) and the mesh (validate_mesh).
void check_evaluation_inputs(const MeshShape& shape, const ParticleArrays& particles,
                             std::span<const double> vertex_positions,
                             std::span<const double> vertex_velocities,
                             std::span<const std::uint32_t> elements,
                             std::span<const double> vertex_forces);

// No pair made yet with the particle (PairKernel's last_element).
inline constexpr std::uint32_t kNoElement = std::numeric_limits<std::uint32_t>::max();

// Accumulates everything of one evaluation; the only place forces are made. `last_element` holds
// kNoElement for every particle at the start.
template <class Point>
class PairKernel {
 public:
  static constexpr int kDimension = Point::kDimension;

  PairKernel(const ForceLaw& law, const ParticleArrays& particles, std::span<double> vertex_forces,
             std::vector<std::uint32_t>& last_element, ContactDiagnostics& diagnostics)
      : law_(law),
        range2_(law.range() * law.range()),
        particles_(particles),
        vertex_forces_(vertex_forces.data()),
        last_element_(last_element),
        diagnostics_(diagnostics) {}

  void operator()(const Point& s, std::size_t i) {
    const double* x = particles_.positions + 3 * i;
    double offset[kDimension];
    for (int k = 0; k < kDimension; ++k)
      offset[k] = x[k] - s.position[k];
    double distance2 = offset[0] * offset[0];
    for (int k = 1; k < kDimension; ++k)
      distance2 += offset[k] * offset[k];
    if (distance2 >= range2_) return;
    const double distance = std::sqrt(distance2);
    // At distance 0 the repulsion has no direction and contributes nothing.
    const double along_line = distance > 0.0 ? law_.repulsion(distance) / distance : 0.0;
    const double friction = law_.viscous_scale * law_.viscous_weight(distance);
    const double* u = particles_.velocities + 3 * i;
    double force[kDimension];
    for (int k = 0; k < kDimension; ++k)
      force[k] = (along_line * offset[k] - friction * (u[k] - s.velocity[k])) * s.measure_weight;

    double* f = particles_.forces + 3 * i;
    for (int k = 0; k < kDimension; ++k) {
      f[k] += force[k];
      diagnostics_.force_on_particles[k] += force[k];
    }
    redistribute(force, s.corner_vertex, s.corner_share, vertex_forces_);
    if (sample_force_) {
      for (int k = 0; k < kDimension; ++k)
        sample_force_[k] -= force[k];
      ++*sample_pairs_;
    }

    double magnitude2 = force[0] * force[0];
    for (int k = 1; k < kDimension; ++k)
      magnitude2 += force[k] * force[k];
    diagnostics_.pair_force_magnitude_sum += std::sqrt(magnitude2);
    ++diagnostics_.pair_count;
    // The particle's distance to the element is the same for every sampling point of the
    // element, and a sampling visits an element's points one after another: the distance is
    // taken once per particle and element (per pair it cost 5-8 % of the kernel: performance.md).
    std::uint32_t& last = last_element_[i];
    if (last != s.element_index) {
      if (last == kNoElement) ++diagnostics_.particles_in_range;
      last = s.element_index;
      diagnostics_.closest_distance = s.element->closest_distance(x, diagnostics_.closest_distance);
    }
  }

  // Starts sampling point `s` of the record (when there is one): the pairs that follow add their
  // reaction to its force.
  void begin_sample(const Point& s, WallSampleRecord* record) {
    if (!record) return;
    const auto append = [](std::vector<double>& to, const double* values) {
      to.insert(to.end(), values, values + kDimension);
    };
    append(record->positions, s.position);
    append(record->normals, s.normal);
    record->forces.resize(record->forces.size() + kDimension, 0.0);
    record->measures.push_back(s.measure_weight);
    record->elements.push_back(s.element_index);
    record->pairs.push_back(0);
    sample_force_ = record->forces.data() + record->forces.size() - kDimension;
    sample_pairs_ = &record->pairs.back();
  }

 private:
  const ForceLaw& law_;
  double range2_;
  const ParticleArrays& particles_;
  double* vertex_forces_;
  std::vector<std::uint32_t>& last_element_;
  ContactDiagnostics& diagnostics_;
  double* sample_force_ = nullptr;  // the recorded sampling point's force, when recording
  std::uint32_t* sample_pairs_ = nullptr;
};

// Empties the record for an evaluation of `Dimension`; nullptr when there is nothing to record.
template <int Dimension>
WallSampleRecord* start_record(WallSampleRecord* record) {
  if (!record || !record->enabled) return nullptr;
  record->clear();
  record->dimension = Dimension;
  return record;
}

// Zeroes the vertex forces and starts the diagnostics (no particle seen yet).
inline ContactDiagnostics start_evaluation(std::span<double> vertex_forces) {
  std::fill(vertex_forces.begin(), vertex_forces.end(), 0.0);
  ContactDiagnostics diagnostics;
  diagnostics.closest_distance = std::numeric_limits<double>::infinity();
  return diagnostics;
}

// The force on the structure is the sum of the vertex forces, as the server will apply them.
template <int Dimension>
void finish_evaluation(std::span<const double> vertex_forces, ContactDiagnostics& diagnostics) {
  for (std::size_t v = 0; v < vertex_forces.size(); v += Dimension) {
    for (int k = 0; k < Dimension; ++k)
      diagnostics.force_on_structure[k] += vertex_forces[v + k];
  }
}

// The cell grid's search radius is the range widened by this fraction, so that a pair accepted by
// the rounded test |x - s|^2 < r^2 is never in a cell the search skipped.
inline constexpr double kSearchMargin = 1e-9;

// The evaluation with a cell grid over the particles near the mesh (thesis §5.5.2). The inputs
// must have passed check_evaluation_inputs.
template <class Sampling>
ContactDiagnostics evaluate_near_particles(
    const Sampling& sampling, const ForceLaw& law, const ParticleArrays& particles,
    std::span<const double> vertex_positions, std::span<double> vertex_forces,
    NeighbourSearchBuffers<Sampling::Point::kDimension>& buffers,
    WallSampleRecord* samples = nullptr) {
  using Point = typename Sampling::Point;
  WallSampleRecord* record = start_record<Point::kDimension>(samples);
  ContactDiagnostics diagnostics = start_evaluation(vertex_forces);
  const double range = law.range();
  mark_particles_near_mesh(particles, vertex_positions, Point::kDimension, range, buffers.near);
  buffers.grid.build(particles.positions, buffers.near, range);
  buffers.last_element.assign(particles.count, kNoElement);
  PairKernel<Point> kernel(law, particles, vertex_forces, buffers.last_element, diagnostics);
  const double reach = range * (1.0 + kSearchMargin);
  // A record holds every sampling point (the probes sum them over the ranks), so it turns the
  // skipping off.
  ReachBox<Point::kDimension> box;
  for (int k = 0; k < Point::kDimension; ++k) {
    box.low[k] = buffers.grid.members_low()[k] - reach;
    box.high[k] = buffers.grid.members_high()[k] + reach;
  }
  sampling.for_each_point(
      [&](const Point& s) {
        ++diagnostics.sampling_points;
        kernel.begin_sample(s, record);
        diagnostics.candidate_pairs +=
            buffers.grid.visit_near(s.position, reach, [&](std::uint32_t i) { kernel(s, i); });
      },
      record ? nullptr : &box, diagnostics.sampling_points_skipped);
  diagnostics.sampling_points += diagnostics.sampling_points_skipped;
  finish_evaluation<Point::kDimension>(vertex_forces, diagnostics);
  return diagnostics;
}

// The same sampling against every participating particle: the reference the cell grid is
// tested against. The inputs must have passed check_evaluation_inputs.
template <class Sampling>
ContactDiagnostics evaluate_all_pairs(const Sampling& sampling, const ForceLaw& law,
                                      const ParticleArrays& particles,
                                      std::span<double> vertex_forces,
                                      WallSampleRecord* samples = nullptr) {
  using Point = typename Sampling::Point;
  WallSampleRecord* record = start_record<Point::kDimension>(samples);
  ContactDiagnostics diagnostics = start_evaluation(vertex_forces);
  std::vector<std::uint32_t> last_element(particles.count, kNoElement);
  PairKernel<Point> kernel(law, particles, vertex_forces, last_element, diagnostics);
  sampling.for_each_point(
      [&](const Point& s) {
        ++diagnostics.sampling_points;
        kernel.begin_sample(s, record);
        for (std::size_t i = 0; i < particles.count; ++i) {
          if (!takes_part(particles, i)) continue;
          ++diagnostics.candidate_pairs;
          kernel(s, i);
        }
      },
      nullptr, diagnostics.sampling_points_skipped);
  finish_evaluation<Point::kDimension>(vertex_forces, diagnostics);
  return diagnostics;
}

// Distance of point p to the segment a-b (Dimension coordinates each).
template <int Dimension>
double distance_to_segment(const double* p, const double* a, const double* b) {
  double edge[Dimension];
  double offset[Dimension];
  double length2 = 0.0;
  double along = 0.0;
  for (int k = 0; k < Dimension; ++k) {
    edge[k] = b[k] - a[k];
    offset[k] = p[k] - a[k];
    length2 += edge[k] * edge[k];
    along += offset[k] * edge[k];
  }
  const double t = length2 > 0.0 ? std::clamp(along / length2, 0.0, 1.0) : 0.0;
  double distance2 = 0.0;
  for (int k = 0; k < Dimension; ++k) {
    const double gap = offset[k] - t * edge[k];
    distance2 += gap * gap;
  }
  return std::sqrt(distance2);
}

}  // namespace fsi::contact::skeleton
