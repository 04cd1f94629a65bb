#include "fsi/contact/periodic_images.hpp"

#include <algorithm>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <string>

namespace fsi::contact {
namespace {

constexpr const char* kAxisNames[] = {"x", "y", "z"};
// A mesh drawn exactly over one period (vertices at both box bounds) is not "longer" by
// round-off.
constexpr double kRelativeSlack = 1e-9;

std::string number(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", value);
  return text;
}

struct Bounds {
  std::array<double, 3> low{}, high{};
};

Bounds mesh_bounds(std::span<const double> vertex_positions, int dimension) {
  constexpr double kInfinity = std::numeric_limits<double>::infinity();
  Bounds b;
  b.low.fill(kInfinity);
  b.high.fill(-kInfinity);
  for (std::size_t v = 0; v + static_cast<std::size_t>(dimension) <= vertex_positions.size();
       v += static_cast<std::size_t>(dimension)) {
    for (int k = 0; k < dimension; ++k) {
      b.low[k] = std::min(b.low[k], vertex_positions[v + k]);
      b.high[k] = std::max(b.high[k], vertex_positions[v + k]);
    }
  }
  return b;
}

}  // namespace

bool Periodicity::any() const {
  for (int k = 0; k < dimension; ++k)
    if (periodic[k]) return true;
  return false;
}

void check_periodic_mesh(const Periodicity& box, std::span<const double> vertex_positions,
                         double range) {
  if (vertex_positions.empty()) return;
  const Bounds b = mesh_bounds(vertex_positions, box.dimension);
  for (int k = 0; k < box.dimension; ++k) {
    if (!box.periodic[k]) continue;
    const double period = box.period(k);
    if (!(2.0 * range < period)) {
      throw std::invalid_argument(
          std::string("fix fsi/sph: the box is periodic along ") + kAxisNames[k] + " with period " +
          number(period) + ", not more than twice the wall's range " + number(range) +
          " (cutoff, cutoff_visc): a particle would meet the same wall twice; "
          "make the periodic box longer than " +
          number(2.0 * range));
    }
    const double span = b.high[k] - b.low[k];
    if (span > period * (1.0 + kRelativeSlack)) {
      throw std::invalid_argument(
          std::string("fix fsi/sph: the box is periodic along ") + kAxisNames[k] + " with period " +
          number(period) + " (" + number(box.low[k]) + " to " + number(box.high[k]) +
          "), but the meshes span " + number(span) + " (" + number(b.low[k]) + " to " +
          number(b.high[k]) + ") along it: draw each wall once per period (e.g. from " +
          number(box.low[k]) + " to " + number(box.high[k]) +
          "); the fix adds the periodic images itself");
    }
  }
}

ParticleArrays PeriodicImages::extend(const ParticleArrays& particles, const Periodicity& box,
                                      std::span<const double> vertex_positions, double range) {
  const std::size_t n = particles.count;
  owned_ = n;
  positions_.assign(particles.positions, particles.positions + 3 * n);
  velocities_.assign(particles.velocities, particles.velocities + 3 * n);
  mask_.assign(n, 1);
  origin_.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    origin_[i] = i;
    const bool takes_part =
        particles.group_mask.empty() || (particles.group_mask[i] & particles.group_bit) != 0;
    if (!takes_part) mask_[i] = 0;
  }
  if (!vertex_positions.empty()) {
    const Bounds b = mesh_bounds(vertex_positions, box.dimension);
    const double reach = range * (1.0 + kRelativeSlack);
    for (std::size_t i = 0; i < n; ++i) {
      if (mask_[i] == 0) continue;
      // Every combination of shifts -1, 0, +1 along the periodic axes (the digits of c in base 3)
      // but the unshifted one.
      int combinations = 1;
      for (int k = 0; k < box.dimension; ++k)
        combinations *= box.periodic[k] ? 3 : 1;
      for (int c = 0; c < combinations; ++c) {
        double image[3] = {particles.positions[3 * i], particles.positions[3 * i + 1],
                           particles.positions[3 * i + 2]};
        int code = c;
        bool shifted = false;
        for (int k = 0; k < box.dimension; ++k) {
          if (!box.periodic[k]) continue;
          const int shift = code % 3 - 1;
          code /= 3;
          image[k] += shift * box.period(k);
          shifted = shifted || shift != 0;
        }
        bool near = shifted;
        for (int k = 0; k < box.dimension && near; ++k)
          near = image[k] >= b.low[k] - reach && image[k] <= b.high[k] + reach;
        if (!near) continue;
        positions_.insert(positions_.end(), image, image + 3);
        velocities_.insert(velocities_.end(), particles.velocities + 3 * i,
                           particles.velocities + 3 * i + 3);
        mask_.push_back(1);
        origin_.push_back(i);
      }
    }
  }
  forces_.assign(positions_.size(), 0.0);
  ParticleArrays extended;
  extended.count = origin_.size();
  extended.positions = positions_.data();
  extended.velocities = velocities_.data();
  extended.forces = forces_.data();
  extended.group_mask = mask_;
  extended.group_bit = 1;
  return extended;
}

void PeriodicImages::fold_forces(const ParticleArrays& particles) const {
  for (std::size_t j = 0; j < origin_.size(); ++j) {
    double* f = particles.forces + 3 * origin_[j];
    for (int k = 0; k < 3; ++k)
      f[k] += forces_[3 * j + k];
  }
}

}  // namespace fsi::contact
