#pragma once
// Meshes that pass through each other without contact between them: a run checks after every
// step that no two meshes of different bodies (or a body and the ground) that have no Contact
// block cross (2D: two segments intersect; 3D: an edge of one crosses a triangle of the other),
// and stops with both names, the time, the place and the fix. Where two meshes already cross or
// touch at the start (a body hinged to the ground at a shared vertex, a piston drawn against the
// tank walls, a plate clamped to the floor), the elements that do are not watched against each
// other, the rest of the pair is (a clamped plate that bends down through the floor is caught);
// the run's log names such pairs.

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
  // "'lever' and the ground" for each pair whose meshes cross or touch at the start: the elements
  // that do are not watched against each other, the others are.
  const std::vector<std::string>& excluded_pairs() const { return excluded_; }
  // How many pairs are watched.
  std::size_t watched_pair_count() const { return watched_.size(); }

  struct Part {
    mbd::BodyId body;
    std::string name;
    std::vector<std::uint32_t> elements;  // dimension vertex indices each, as in BoundaryMesh
  };

 private:
  // Element pairs (an element of a, one of b: their indices in the parts) that cross or touch.
  using ElementPairs = std::vector<std::pair<std::size_t, std::size_t>>;
  // A crossing point of parts a and b at `positions`, if any, among the element pairs not in
  // `ignored` (sorted); with `all`, every crossing element pair is collected there.
  bool find_crossing(const Part& a, const Part& b, const std::vector<double>& positions,
                     std::array<double, 3>& where, const ElementPairs& ignored,
                     ElementPairs* all = nullptr) const;

  struct WatchedPair {
    std::size_t a, b;      // parts
    ElementPairs ignored;  // crossing or touching at the start (sorted)
  };

  const Scene& scene_;
  std::vector<Part> parts_;
  std::vector<WatchedPair> watched_;
  std::vector<std::string> excluded_;
};

}  // namespace fsi::scene
