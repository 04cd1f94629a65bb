#include "fsi/scene/mesh_crossing.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <cstdio>
#include <limits>
#include <map>

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

}  // namespace

CrossingWatch::CrossingWatch(const Scene& scene, const mbd::State& start) : scene_(scene) {
  const BoundaryMesh& boundary = scene.boundary;
  const int corners = boundary.dimension;
  std::map<mbd::BodyId, std::size_t> part_of_body;
  const auto& elements = boundary.elements();
  for (std::size_t e = 0; e + corners <= elements.size(); e += corners) {
    const std::uint32_t first = elements[e];
    const mbd::BodyId body = first < boundary.dynamic_vertex_count
                                 ? scene.model.marker_body(static_cast<int>(first))
                                 : mbd::kGround;
    auto [found, added] = part_of_body.emplace(body, parts_.size());
    if (added) {
      parts_.push_back({body, body == mbd::kGround ? "ground" : scene.model.body_name(body), {}});
    }
    auto& part = parts_[found->second].elements;
    part.insert(part.end(), elements.begin() + static_cast<std::ptrdiff_t>(e),
                elements.begin() + static_cast<std::ptrdiff_t>(e + corners));
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
      ElementPairs touching;
      if (find_crossing(parts_[i], parts_[j], positions, where, {}, &touching))
        excluded_.push_back(pair_name(parts_[i], parts_[j]));
      std::sort(touching.begin(), touching.end());
      watched_.push_back({i, j, std::move(touching)});
    }
  }
}

bool CrossingWatch::find_crossing(const Part& a, const Part& b,
                                  const std::vector<double>& positions,
                                  std::array<double, 3>& where, const ElementPairs& ignored,
                                  ElementPairs* all) const {
  const int dimension = scene_.boundary.dimension;
  const auto corners = static_cast<std::size_t>(dimension);
  auto element_box = [&](const Part& part, std::size_t e) {
    Box box;
    for (std::size_t k = 0; k < corners; ++k)
      box.include(vertex_at(positions, dimension, part.elements[e * corners + k]));
    return box;
  };
  auto part_box = [&](const Part& part) {
    Box box;
    for (std::uint32_t vertex : part.elements)
      box.include(vertex_at(positions, dimension, vertex));
    return box;
  };
  const Box box_a = part_box(a), box_b = part_box(b);
  if (!box_a.overlaps(box_b)) return false;
  // The elements of each part inside the other's box, with their own boxes.
  auto candidates = [&](const Part& part, const Box& other) {
    std::vector<std::pair<std::size_t, Box>> found;
    for (std::size_t e = 0; e < part.elements.size() / corners; ++e) {
      const Box box = element_box(part, e);
      if (box.overlaps(other)) found.emplace_back(e, box);
    }
    return found;
  };
  const auto near_a = candidates(a, box_b), near_b = candidates(b, box_a);
  auto point = [&](const Part& part, std::size_t e, std::size_t k) {
    return vertex_at(positions, dimension, part.elements[e * corners + k]);
  };
  // 3D: the edges of one part's triangles against the other's triangles.
  auto edges_against = [&](const Part& edges_part, std::size_t e, const Part& faces_part,
                           std::size_t f, Eigen::Vector3d& hit) {
    for (std::size_t k = 0; k < 3; ++k) {
      if (edge_crosses_triangle(point(edges_part, e, k), point(edges_part, e, (k + 1) % 3),
                                point(faces_part, f, 0), point(faces_part, f, 1),
                                point(faces_part, f, 2), hit))
        return true;
    }
    return false;
  };
  bool found = false;
  for (const auto& [e, box_e] : near_a) {
    for (const auto& [f, box_f] : near_b) {
      if (!box_e.overlaps(box_f)) continue;
      if (std::binary_search(ignored.begin(), ignored.end(), std::make_pair(e, f))) continue;
      Eigen::Vector3d hit;
      const bool crossing = dimension == 2
                                ? segments_intersect(point(a, e, 0), point(a, e, 1), point(b, f, 0),
                                                     point(b, f, 1), hit)
                                : edges_against(a, e, b, f, hit) || edges_against(b, f, a, e, hit);
      if (!crossing) continue;
      if (!found) where = {hit.x(), hit.y(), hit.z()};
      found = true;
      if (all == nullptr) return true;
      all->emplace_back(e, f);
    }
  }
  return found;
}

void CrossingWatch::check(const mbd::State& state) const {
  if (watched_.empty()) return;
  std::vector<double> positions, velocities;
  boundary_state(scene_.boundary, scene_.model, state, positions, velocities);
  for (const WatchedPair& pair : watched_) {
    const std::size_t i = pair.a, j = pair.b;
    std::array<double, 3> where{};
    if (!find_crossing(parts_[i], parts_[j], positions, where, pair.ignored)) continue;
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
