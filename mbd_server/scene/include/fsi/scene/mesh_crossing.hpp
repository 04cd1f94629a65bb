#pragma once
// Meshes that pass through each other without contact between them: a run checks after every
// step that no two meshes of different bodies (or a body and the ground) that have no Contact
// block cross (2D: two segments intersect; 3D: an edge of one crosses a triangle of the other),
// and stops with both names, the time, the place and the fix. Where a body's mesh already crosses
// or touches the ground at the start (a link hinged to the ground at a shared vertex, a piston
// drawn against the tank walls, a plate clamped to the floor), its elements that do are not
// tested against the ground, its others are (a clamped plate that bends down through the floor
// is caught, a piston sliding along a wall of many elements is not stopped); a body that passes
// through the ground at the start (by design: a paddle sticking out through a lid) and two
// bodies touching at the start are not watched against each other. The run's log names such
// pairs.

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "fsi/mbd/constrained_system.hpp"
#include "fsi/scene/scene.hpp"

namespace fsi::scene {

class CrossingWatch {
 public:
  // Splits the boundary mesh by body and decides, at `start`, which pairs are watched.
  CrossingWatch(const Scene& scene, const mbd::State& start);
  // Throws fsi::Error naming both meshes, the time and a crossing point if two watched meshes
  // cross at `state`. Cheap while the meshes' bounding boxes stay apart.
  void check(const mbd::State& state) const;
  // For each pair whose meshes cross or touch at the start, "'lever' and the ground: ..." with
  // what is left unwatched.
  const std::vector<std::string>& excluded_pairs() const { return excluded_; }
  // How many pairs are watched.
  std::size_t watched_pair_count() const { return watched_.size(); }

  struct Part {
    mbd::BodyId body;
    std::string name;
    std::vector<std::uint32_t> elements;  // dimension vertex indices each, as in BoundaryMesh
  };

 private:
  // Which elements of a part take part in the test (empty: all).
  using Skipped = std::vector<bool>;
  // A crossing point of parts a and b at `positions`, if any, among the elements not skipped.
  bool find_crossing(const Part& a, const Part& b, const std::vector<double>& positions,
                     std::array<double, 3>& where, const Skipped& skip_a = {},
                     const Skipped& skip_b = {}) const;
  // The diagonal of the box around both parts at `positions`.
  double extent(const Part& a, const Part& b, const std::vector<double>& positions) const;
  // Do two elements of a and b pass through each other (not a touch) at `positions`?
  bool pass_through(const Part& a, const Part& b, const std::vector<double>& positions,
                    double tolerance) const;
  // The elements of `part` that cross or come within `tolerance` of `other` at `positions`.
  Skipped touching(const Part& part, const Part& other, const std::vector<double>& positions,
                   double tolerance) const;

  struct WatchedPair {
    std::size_t a, b;        // parts
    Skipped skip_a, skip_b;  // their elements touching the other at the start
  };

  const Scene& scene_;
  std::vector<Part> parts_;
  std::vector<WatchedPair> watched_;
  std::vector<std::string> excluded_;
};

}  // namespace fsi::scene
