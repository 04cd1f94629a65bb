#pragma once
// Particles owned in LAMMPS' layout (3 values per particle, also in 2D), for the contact core's
// unit tests and bench/contact_scaling.cpp: the one place that turns plain vectors into the
// ParticleArrays an evaluation reads.

#include <algorithm>
#include <array>
#include <cstddef>
#include <vector>

#include "fsi/contact/contact_evaluation.hpp"

namespace fsi::contact::test_support {

struct ParticleCloud {
  std::vector<double> x, v, f;
  std::vector<int> mask;  // group bit 1: every particle takes part until a test clears it

  void add(const std::array<double, 3>& position,
           const std::array<double, 3>& velocity = {0.0, 0.0, 0.0}) {
    x.insert(x.end(), position.begin(), position.end());
    v.insert(v.end(), velocity.begin(), velocity.end());
    f.insert(f.end(), {0.0, 0.0, 0.0});
    mask.push_back(1);
  }
  // A particle of a 2D run: z = 0, no z velocity.
  void add(double px, double py, double vx = 0.0, double vy = 0.0) {
    add({px, py, 0.0}, {vx, vy, 0.0});
  }
  std::size_t count() const { return mask.size(); }
  ParticleArrays arrays() {
    ParticleArrays a;
    a.count = count();
    a.positions = x.data();
    a.velocities = v.data();
    a.forces = f.data();
    a.group_mask = mask;
    a.group_bit = 1;
    return a;
  }
  void clear_forces() { std::fill(f.begin(), f.end(), 0.0); }
};

}  // namespace fsi::contact::test_support
