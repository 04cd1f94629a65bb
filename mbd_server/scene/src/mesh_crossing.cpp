#include "fsi/scene/mesh_crossing.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <cstdio>
#include <limits>

#include "distances.hpp"
#include "fsi/common/error.hpp"

namespace fsi::scene {
namespace {

struct Box {
  Eigen::Vector3d low = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d high = -low;
  void include(const Eigen::Vector3d& x) {
    low = low.cwiseMin(x);
    high = high.cwiseMax(x);
  }
  bool overlaps(const Box& other) const {
    return (low.array() <= other.high.array()).all() && (other.low.array() <= high.array()).all();
  }
};

Eigen::Vector3d vertex_at(const std::vector<double>& positions, int dimension,
                          std::uint32_t vertex) {
  const std::size_t k = static_cast<std::size_t>(dimension) * vertex;
  return {positions[k], positions[k + 1], dimension == 3 ? positions[k + 2] : 0.0};
}

double orientation(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  return (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
}

// Closed test: segments that only touch (an end on the other, collinear overlap) intersect.
bool segments_intersect(const Eigen::Vector3d& p1, const Eigen::Vector3d& p2,
                        const Eigen::Vector3d& q1, const Eigen::Vector3d& q2,
                        Eigen::Vector3d& where) {
  const double d1 = orientation(q1, q2, p1), d2 = orientation(q1, q2, p2);
  const double d3 = orientation(p1, p2, q1), d4 = orientation(p1, p2, q2);
  if (d1 == 0.0 && d2 == 0.0) {  // collinear: do the extents along the line overlap?
    const Eigen::Vector3d direction = p2 - p1;
    const double length2 = direction.squaredNorm();
    const double s1 = (q1 - p1).dot(direction) / length2, s2 = (q2 - p1).dot(direction) / length2;
    if (std::max(s1, s2) < 0.0 || std::min(s1, s2) > 1.0) return false;
    where = p1 + std::clamp(std::min(s1, s2), 0.0, 1.0) * direction;
    return true;
  }
  if (d1 * d2 > 0.0 || d3 * d4 > 0.0) return false;
  where = d1 == d2 ? p1 : Eigen::Vector3d(p1 + d1 / (d1 - d2) * (p2 - p1));
  return true;
}

// Closed test of the segment p -> q against the triangle (a, b, c); an edge in the triangle's
// plane does not count (a face lying on another is not a crossing).
bool edge_crosses_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& q,
                           const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                           const Eigen::Vector3d& c, Eigen::Vector3d& where) {
  const Eigen::Vector3d direction = q - p, e1 = b - a, e2 = c - a;
  const Eigen::Vector3d h = direction.cross(e2);
  const double determinant = e1.dot(h);
  const double scale = direction.norm() * e1.norm() * e2.norm();
  if (std::abs(determinant) <= 1e-14 * scale) return false;
  const Eigen::Vector3d s = p - a;
  const double u = s.dot(h) / determinant;
  if (u < 0.0 || u > 1.0) return false;
  const Eigen::Vector3d r = s.cross(e1);
  const double v = direction.dot(r) / determinant;
  if (v < 0.0 || u + v > 1.0) return false;
  const double t = e2.dot(r) / determinant;
  if (t < 0.0 || t > 1.0) return false;
  where = p + t * direction;
  return true;
}

std::string pair_name(const CrossingWatch::Part& a, const CrossingWatch::Part& b) {
  auto one = [](const CrossingWatch::Part& part) {
    return part.body == mbd::kGround ? std::string("the ground") : "'" + part.name + "'";
  };
  return one(a) + " and " + one(b);
}

// Vertex k of element e of a part at `positions`.
Eigen::Vector3d corner(const std::vector<double>& positions, int dimension,
                       const CrossingWatch::Part& part, std::size_t e, std::size_t k) {
  return vertex_at(positions, dimension,
                   part.elements[e * static_cast<std::size_t>(dimension) + k]);
}

// The box of element e, grown by `margin` on every side.
Box element_box(const std::vector<double>& positions, int dimension,
                const CrossingWatch::Part& part, std::size_t e, double margin = 0.0) {
  Box box;
  for (std::size_t k = 0; k < static_cast<std::size_t>(dimension); ++k)
    box.include(corner(positions, dimension, part, e, k));
  box.low.array() -= margin;
  box.high.array() += margin;
  return box;
}

// Does element e of part a cross element f of part b (2D: the segments intersect; 3D: an edge of
// one passes through the other triangle)?
bool elements_cross(int dimension, const CrossingWatch::Part& a, std::size_t e,
                    const CrossingWatch::Part& b, std::size_t f,
                    const std::vector<double>& positions, Eigen::Vector3d& hit) {
  auto point = [&](const CrossingWatch::Part& part, std::size_t element, std::size_t k) {
    return corner(positions, dimension, part, element, k);
  };
  if (dimension == 2)
    return segments_intersect(point(a, e, 0), point(a, e, 1), point(b, f, 0), point(b, f, 1), hit);
  auto edges_against = [&](const CrossingWatch::Part& edges, std::size_t g,
                           const CrossingWatch::Part& faces, std::size_t h) {
    for (std::size_t k = 0; k < 3; ++k) {
      if (edge_crosses_triangle(point(edges, g, k), point(edges, g, (k + 1) % 3),
                                point(faces, h, 0), point(faces, h, 1), point(faces, h, 2), hit))
        return true;
    }
    return false;
  };
  return edges_against(a, e, b, f) || edges_against(b, f, a, e);
}

// Do elements e of a and f of b pass through each other by more than `tolerance` (2D: each
// segment has its ends on both sides of the other's line, farther than the tolerance; 3D: an
// edge of one has its ends on both sides of the other's plane so, and passes through it)? Not
// a touch: a vertex on the other element, a collinear or coplanar overlap.
bool elements_pass_through(int dimension, const CrossingWatch::Part& a, std::size_t e,
                           const CrossingWatch::Part& b, std::size_t f,
                           const std::vector<double>& positions, double tolerance) {
  auto point = [&](const CrossingWatch::Part& part, std::size_t element, std::size_t k) {
    return corner(positions, dimension, part, element, k);
  };
  auto apart = [&](double side_p, double side_q, double scale) {
    return side_p * side_q < 0.0 && std::abs(side_p) > tolerance * scale &&
           std::abs(side_q) > tolerance * scale;
  };
  if (dimension == 2) {
    const Eigen::Vector3d p1 = point(a, e, 0), p2 = point(a, e, 1);
    const Eigen::Vector3d q1 = point(b, f, 0), q2 = point(b, f, 1);
    return apart(orientation(q1, q2, p1), orientation(q1, q2, p2), (q2 - q1).norm()) &&
           apart(orientation(p1, p2, q1), orientation(p1, p2, q2), (p2 - p1).norm());
  }
  auto edges_through = [&](const CrossingWatch::Part& edges, std::size_t g,
                           const CrossingWatch::Part& faces, std::size_t h) {
    const Eigen::Vector3d t0 = point(faces, h, 0), t1 = point(faces, h, 1), t2 = point(faces, h, 2);
    const Eigen::Vector3d normal = (t1 - t0).cross(t2 - t0).normalized();
    for (std::size_t k = 0; k < 3; ++k) {
      const Eigen::Vector3d p = point(edges, g, k), q = point(edges, g, (k + 1) % 3);
      Eigen::Vector3d hit;
      if (apart(normal.dot(p - t0), normal.dot(q - t0), 1.0) &&
          edge_crosses_triangle(p, q, t0, t1, t2, hit))
        return true;
    }
    return false;
  };
  return edges_through(a, e, b, f) || edges_through(b, f, a, e);
}

}  // namespace

CrossingWatch::CrossingWatch(const Scene& scene, const mbd::State& start) : scene_(scene) {
  const BoundaryMesh& boundary = scene.boundary;
  for (BodyElements& part : elements_by_body(boundary, scene.model)) {
    parts_.push_back({part.body,
                      part.body == mbd::kGround ? "ground" : scene.model.body_name(part.body),
                      std::move(part.elements)});
  }
  std::vector<double> positions, velocities;
  boundary_state(boundary, scene.model, start, positions, velocities);
  for (std::size_t i = 0; i < parts_.size(); ++i) {
    for (std::size_t j = i + 1; j < parts_.size(); ++j) {
      const mbd::BodyId a = parts_[i].body, b = parts_[j].body;
      const bool has_contact =
          std::any_of(scene.contact_pairs.begin(), scene.contact_pairs.end(), [&](const auto& p) {
            return (p.first == a && p.second == b) || (p.first == b && p.second == a);
          });
      if (has_contact) continue;
      std::array<double, 3> where{};
      if (!find_crossing(parts_[i], parts_[j], positions, where)) {
        watched_.push_back({i, j, {}, {}});
        continue;
      }
      const std::string pair = pair_name(parts_[i], parts_[j]);
      const double tolerance = 1e-9 * extent(parts_[i], parts_[j], positions);
      const bool ground = a == mbd::kGround || b == mbd::kGround;
      if (!ground || pass_through(parts_[i], parts_[j], positions, tolerance)) {
        // Meshes that pass through each other by design (a hinge above a lid the paddle sticks
        // out of), or two bodies: the pair is not watched.
        excluded_.push_back(pair + ": not watched (" +
                            (ground ? "they pass through each other at the start"
                                    : "two bodies touching at the start") +
                            ")");
        continue;
      }
      // The body's elements that touch the ground now (to rounding: a tip drawn on the floor)
      // are left out against it; the ground's are all tested.
      const std::size_t body = a == mbd::kGround ? j : i;
      const std::size_t other = body == i ? j : i;
      Skipped skipped = touching(parts_[body], parts_[other], positions, tolerance);
      const auto count = std::count(skipped.begin(), skipped.end(), true);
      excluded_.push_back(pair + ": the " + std::to_string(count) + " of its " +
                          std::to_string(skipped.size()) +
                          " elements touching the ground at the start are not tested against it, "
                          "the others are");
      if (body == i) {
        watched_.push_back({i, j, std::move(skipped), {}});
      } else {
        watched_.push_back({i, j, {}, std::move(skipped)});
      }
    }
  }
}

double CrossingWatch::extent(const Part& a, const Part& b,
                             const std::vector<double>& positions) const {
  Box box;
  for (const Part* part : {&a, &b}) {
    for (std::uint32_t vertex : part->elements)
      box.include(vertex_at(positions, scene_.boundary.dimension, vertex));
  }
  return (box.high - box.low).norm();
}

bool CrossingWatch::pass_through(const Part& a, const Part& b, const std::vector<double>& positions,
                                 double tolerance) const {
  const int dimension = scene_.boundary.dimension;
  const std::size_t corners = static_cast<std::size_t>(dimension);
  auto boxes = [&](const Part& part) {
    std::vector<Box> found(part.elements.size() / corners);
    for (std::size_t e = 0; e < found.size(); ++e)
      found[e] = element_box(positions, dimension, part, e);
    return found;
  };
  const std::vector<Box> boxes_a = boxes(a), boxes_b = boxes(b);
  for (std::size_t e = 0; e < boxes_a.size(); ++e) {
    for (std::size_t f = 0; f < boxes_b.size(); ++f) {
      if (boxes_a[e].overlaps(boxes_b[f]) &&
          elements_pass_through(dimension, a, e, b, f, positions, tolerance))
        return true;
    }
  }
  return false;
}

CrossingWatch::Skipped CrossingWatch::touching(const Part& part, const Part& other,
                                               const std::vector<double>& positions,
                                               double tolerance) const {
  const int dimension = scene_.boundary.dimension;
  const auto corners = static_cast<std::size_t>(dimension);
  const std::size_t count = part.elements.size() / corners;
  const std::size_t others = other.elements.size() / corners;
  auto point = [&](const Part& of, std::size_t e, std::size_t k) {
    return corner(positions, dimension, of, e, k);
  };
  // Distance of a vertex of one element to another element (segment or triangle).
  auto vertex_to = [&](const Eigen::Vector3d& p, const Part& of, std::size_t f) {
    const Eigen::Vector3d a = point(of, f, 0), b = point(of, f, 1);
    if (dimension == 2) return detail::distance_to_segment(p.data(), a.data(), b.data(), 3);
    const Eigen::Vector3d c = point(of, f, 2);
    return detail::distance_to_triangle(p.data(), a.data(), b.data(), c.data());
  };
  std::vector<Box> other_boxes;
  for (std::size_t f = 0; f < others; ++f)
    other_boxes.push_back(element_box(positions, dimension, other, f, tolerance));
  Skipped skipped(count, false);
  for (std::size_t e = 0; e < count; ++e) {
    const Box box = element_box(positions, dimension, part, e, tolerance);
    for (std::size_t f = 0; f < others && !skipped[e]; ++f) {
      if (!box.overlaps(other_boxes[f])) continue;
      double gap = std::numeric_limits<double>::infinity();
      for (std::size_t k = 0; k < corners; ++k) {
        gap = std::min(gap, vertex_to(point(part, e, k), other, f));
        gap = std::min(gap, vertex_to(point(other, f, k), part, e));
      }
      Eigen::Vector3d hit;
      skipped[e] = gap <= tolerance || elements_cross(dimension, part, e, other, f, positions, hit);
    }
  }
  return skipped;
}

bool CrossingWatch::find_crossing(const Part& a, const Part& b,
                                  const std::vector<double>& positions,
                                  std::array<double, 3>& where, const Skipped& skip_a,
                                  const Skipped& skip_b) const {
  const int dimension = scene_.boundary.dimension;
  const auto corners = static_cast<std::size_t>(dimension);
  auto part_box = [&](const Part& part) {
    Box box;
    for (std::uint32_t vertex : part.elements)
      box.include(vertex_at(positions, dimension, vertex));
    return box;
  };
  const Box box_a = part_box(a), box_b = part_box(b);
  if (!box_a.overlaps(box_b)) return false;
  // The elements of each part inside the other's box, with their own boxes.
  auto candidates = [&](const Part& part, const Box& other, const Skipped& skip) {
    std::vector<std::pair<std::size_t, Box>> found;
    for (std::size_t e = 0; e < part.elements.size() / corners; ++e) {
      if (!skip.empty() && skip[e]) continue;
      const Box box = element_box(positions, dimension, part, e);
      if (box.overlaps(other)) found.emplace_back(e, box);
    }
    return found;
  };
  const auto near_a = candidates(a, box_b, skip_a), near_b = candidates(b, box_a, skip_b);
  for (const auto& [e, box_e] : near_a) {
    for (const auto& [f, box_f] : near_b) {
      if (!box_e.overlaps(box_f)) continue;
      Eigen::Vector3d hit;
      if (elements_cross(dimension, a, e, b, f, positions, hit)) {
        where = {hit.x(), hit.y(), hit.z()};
        return true;
      }
    }
  }
  return false;
}

void CrossingWatch::check(const mbd::State& state) const {
  if (watched_.empty()) return;
  std::vector<double> positions, velocities;
  boundary_state(scene_.boundary, scene_.model, state, positions, velocities);
  for (const WatchedPair& pair : watched_) {
    const std::size_t i = pair.a, j = pair.b;
    std::array<double, 3> where{};
    if (!find_crossing(parts_[i], parts_[j], positions, where, pair.skip_a, pair.skip_b)) continue;
    char place[96];
    if (scene_.boundary.dimension == 2) {
      std::snprintf(place, sizeof place, "(%.6g, %.6g) m", where[0], where[1]);
    } else {
      std::snprintf(place, sizeof place, "(%.6g, %.6g, %.6g) m", where[0], where[1], where[2]);
    }
    const Part& a = parts_[i];
    const Part& b = parts_[j];
    const std::string body_b = b.body == mbd::kGround ? "ground" : b.name;
    throw Error("the meshes of " + pair_name(a, b) + " cross at " + place +
                    ": they have no contact between them, so one has passed into the other",
                "mesh crossing check",
                "add Contact { body_a = \"" + a.name + "\"; body_b = \"" + body_b +
                    "\" } to the scene if they should touch, or reduce the step size if they "
                    "should not have met");
  }
}

}  // namespace fsi::scene
