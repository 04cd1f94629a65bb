#pragma once
// Periodic boundaries for the wall contact. A structure in a periodic LIGGGHTS box is drawn once
// per period; a particle near one end of the period must feel the walls at the other end, beyond
// the periodic boundary, as LIGGGHTS' own pair forces do through ghost atoms. The contact core
// evaluates the particles of this process together with their images shifted by +-period along
// every periodic axis (only those that come within the wall's range of the mesh), and folds the
// images' forces back onto the particles. Each pair (particle, sampling point) then counts once,
// at the nearest image, as long as the range is below half a period and no part of the structure
// is drawn twice (the mesh spans at most one period: check_periodic_mesh).
//
// Pure C++ over plain arrays: no LIGGGHTS types.

#include <array>
#include <cstddef>
#include <span>
#include <vector>

#include "fsi/contact/contact_evaluation.hpp"

namespace fsi::contact {

// The periodic axes of the simulation box (LIGGGHTS `boundary p ...`) and its extent along them.
struct Periodicity {
  int dimension = 2;                    // axes 0 .. dimension-1 are considered
  std::array<bool, 3> periodic{};       // per axis
  std::array<double, 3> low{}, high{};  // box bounds per axis
  bool any() const;
  double period(int axis) const { return high[axis] - low[axis]; }
};

// Throws std::invalid_argument, naming the axis and the numbers, when along a periodic axis the
// wall's range is not below half the period, or the mesh vertices span more than one period
// (a wall drawn longer than the period would act twice on the particles near its ends).
void check_periodic_mesh(const Periodicity& box, std::span<const double> vertex_positions,
                         double range);

class PeriodicImages {
 public:
  // The particles followed by every image x + n P (n = -1 or +1 along each periodic axis, and
  // their combinations) that lies within `range` of the bounding box of the mesh vertices
  // (`box.dimension` values per vertex). Only participating particles get images. The arrays
  // returned point into this object and stay valid until the next call; their forces start at 0.
  ParticleArrays extend(const ParticleArrays& particles, const Periodicity& box,
                        std::span<const double> vertex_positions, double range);
  // Adds the forces of the extended arrays (each particle's own and its images') to
  // particles.forces.
  void fold_forces(const ParticleArrays& particles) const;
  std::size_t image_count() const { return origin_.size() - owned_; }
  // The particle an index of the extended arrays belongs to.
  std::size_t origin(std::size_t extended_index) const { return origin_[extended_index]; }

 private:
  std::size_t owned_ = 0;
  std::vector<double> positions_, velocities_, forces_;
  std::vector<int> mask_;
  std::vector<std::size_t> origin_;
};

}  // namespace fsi::contact
