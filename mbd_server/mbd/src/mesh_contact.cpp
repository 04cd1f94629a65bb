#include "mesh_contact.hpp"

#include <unsupported/Eigen/AutoDiff>

#include <algorithm>
#include <cmath>
#include <limits>

#include "spatial_body.hpp"

namespace fsi::mbd::detail {
namespace {

template <typename Scalar, int D>
using Vec = Eigen::Matrix<Scalar, D, 1>;

// The pair's unknowns: D + 1 positions, then D + 1 velocities, D components each.
template <int D>
constexpr int kPairUnknowns = 2 * D*(D + 1);

template <int D>
using Dual = Eigen::AutoDiffScalar<Eigen::Matrix<double, kPairUnknowns<D>, 1>>;

double value_of(double x) {
  return x;
}
template <typename Derivatives>
double value_of(const Eigen::AutoDiffScalar<Derivatives>& x) {
  return x.value();
}

// Eigen's AutoDiff has no tanh.
double tanh_of(double x) {
  return std::tanh(x);
}
template <typename Derivatives>
Eigen::AutoDiffScalar<Derivatives> tanh_of(const Eigen::AutoDiffScalar<Derivatives>& x) {
  const double t = std::tanh(x.value());
  return Eigen::AutoDiffScalar<Derivatives>(t, Derivatives((1.0 - t * t) * x.derivatives()));
}

// The element's outward unit normal and the barycentric weights of the vertex's projection onto
// it. x[0] is the vertex, x[1..D] the element's vertices.
template <typename S>
void element_frame(const std::array<Vec<S, 2>, 3>& x, double sign, Vec<S, 2>& normal,
                   std::array<S, 2>& weights) {
  using std::sqrt;
  const Vec<S, 2> tangent = x[2] - x[1];
  const S length_squared = tangent.squaredNorm();
  normal = Vec<S, 2>(tangent.y(), -tangent.x()) * (S(sign) / sqrt(length_squared));
  const S along = tangent.dot(x[0] - x[1]) / length_squared;
  weights = {S(1.0) - along, along};
}

template <typename S>
void element_frame(const std::array<Vec<S, 3>, 4>& x, double sign, Vec<S, 3>& normal,
                   std::array<S, 3>& weights) {
  using std::sqrt;
  const Vec<S, 3> first = x[2] - x[1], second = x[3] - x[1], relative = x[0] - x[1];
  const Vec<S, 3> area = first.cross(second);
  normal = area * (S(sign) / sqrt(area.squaredNorm()));
  const S d11 = first.squaredNorm(), d12 = first.dot(second), d22 = second.squaredNorm();
  const S r1 = relative.dot(first), r2 = relative.dot(second);
  const S determinant = d11 * d22 - d12 * d12;
  const S beta = (d22 * r1 - d12 * r2) / determinant;
  const S gamma = (d11 * r2 - d12 * r1) / determinant;
  weights = {S(1.0) - beta - gamma, beta, gamma};
}

// The forces on the pair's D + 1 points (vertex first); false (and no forces) when the normal
// force would pull. The normal part is -grad(stiffness gap^2 / 2) exactly (the projection's
// weights are the gap's gradient, docs/theory.md), the damping and friction act on the relative
// velocity of the vertex and the projection point, so neither can feed energy in.
template <typename S, int D>
bool pair_forces(const std::array<Vec<S, D>, D + 1>& position,
                 const std::array<Vec<S, D>, D + 1>& velocity, double sign, const ContactLaw& law,
                 std::array<Vec<S, D>, D + 1>& force) {
  Vec<S, D> normal;
  std::array<S, D> weights;
  element_frame(position, sign, normal, weights);
  const S depth = -normal.dot(position[0] - position[1]);
  Vec<S, D> relative = velocity[0];
  for (int k = 0; k < D; ++k)
    relative -= weights[k] * velocity[k + 1];
  const S normal_speed = normal.dot(relative);
  // The damper comes in over the first damping_onset_depth of the penetration: a force that
  // jumped to c d(delta)/dt at first touch would make the stage equations discontinuous, and
  // Newton would cycle between touching and not touching.
  S damping = S(law.damping);
  if (law.damping_onset_depth > 0.0 && value_of(depth) < law.damping_onset_depth)
    damping = law.damping * depth / law.damping_onset_depth;
  const S normal_force = law.stiffness * depth - damping * normal_speed;
  if (!(value_of(normal_force) > 0.0)) return false;
  Vec<S, D> on_vertex = normal_force * normal;
  if (law.friction_coefficient > 0.0) {
    const Vec<S, D> sliding = relative - normal_speed * normal;
    const S speed_squared = sliding.squaredNorm();
    const double scale = law.regularisation_speed;
    // tanh(|u|/v_reg)/|u|, its series below 1e-4 v_reg (relative error 2e-17), where the square
    // root's derivative would be singular.
    S shape;
    if (value_of(speed_squared) < 1e-8 * scale * scale) {
      shape = (S(1.0) - speed_squared / (3.0 * scale * scale)) / scale;
    } else {
      using std::sqrt;
      const S speed = sqrt(speed_squared);
      const S ratio = speed / scale;
      shape = tanh_of(ratio) / speed;
    }
    on_vertex -= (law.friction_coefficient * normal_force * shape) * sliding;
  }
  force[0] = on_vertex;
  for (int k = 0; k < D; ++k)
    force[k + 1] = -weights[k] * on_vertex;
  return true;
}

template <typename Point>
auto world_position(const Point& point, const Eigen::VectorXd& q) {
  return point.position(q);
}

// Axis-aligned box, grown by a margin.
template <int D>
struct Box {
  Vec<double, D> low = Vec<double, D>::Constant(std::numeric_limits<double>::infinity());
  Vec<double, D> high = -low;
  void include(const Vec<double, D>& x) {
    low = low.cwiseMin(x);
    high = high.cwiseMax(x);
  }
  void grow(double margin) {
    low.array() -= margin;
    high.array() += margin;
  }
  bool contains(const Vec<double, D>& x) const {
    return (x.array() >= low.array()).all() && (x.array() <= high.array()).all();
  }
  bool overlaps(const Box& other) const {
    return (low.array() <= other.high.array()).all() && (other.low.array() <= high.array()).all();
  }
};

}  // namespace

template <typename Point, int D>
MeshContact<Point, D>::MeshContact(std::string description, ContactSurface<Point, D> first,
                                   ContactSurface<Point, D> second, const ContactLaw& law)
    : SparseForceElement(std::move(description)),
      first_(std::move(first)),
      second_(std::move(second)),
      law_(law) {}

template <typename Point, int D>
std::vector<ContactPair> MeshContact<Point, D>::pairs(const Eigen::VectorXd& q) const {
  std::array<std::vector<Vector>, 2> positions;
  std::array<Box<D>, 2> bounds;
  for (int side = 0; side < 2; ++side) {
    for (const Point& vertex : surface(side).vertices) {
      positions[side].push_back(world_position(vertex, q));
      bounds[side].include(positions[side].back());
    }
    bounds[side].grow(law_.depth_limit);
  }
  std::vector<ContactPair> found;
  if (!bounds[0].overlaps(bounds[1])) return found;
  for (int side = 0; side < 2; ++side) {
    const int other = 1 - side;
    const auto& elements = surface(other).elements;
    std::vector<Box<D>> element_bounds(elements.size());
    for (std::size_t e = 0; e < elements.size(); ++e) {
      for (int corner : elements[e])
        element_bounds[e].include(positions[other][corner]);
      element_bounds[e].grow(law_.depth_limit);
    }
    for (std::size_t vertex = 0; vertex < positions[side].size(); ++vertex) {
      const Vector& x = positions[side][vertex];
      if (!bounds[other].contains(x)) continue;
      ContactPair best{side, static_cast<int>(vertex), -1, law_.depth_limit};
      for (std::size_t e = 0; e < elements.size(); ++e) {
        if (!element_bounds[e].contains(x)) continue;
        std::array<Vector, D + 1> corners;
        corners[0] = x;
        for (int k = 0; k < D; ++k)
          corners[k + 1] = positions[other][elements[e][k]];
        Vector normal;
        std::array<double, D> weights;
        element_frame(corners, surface(other).normal_signs[e], normal, weights);
        const double depth = -normal.dot(x - corners[1]);
        const bool projects_inside = std::all_of(weights.begin(), weights.end(),
                                                 [](double w) { return w >= 0.0 && w <= 1.0; });
        // The smallest depth wins, so a vertex at a corner of the other surface is pushed out
        // through the nearer face, and each vertex feels one element: its energy is one
        // stiffness depth^2 / 2.
        if (projects_inside && depth > 0.0 && depth <= best.depth) {
          best.element = static_cast<int>(e);
          best.depth = depth;
        }
      }
      if (best.element >= 0) found.push_back(best);
    }
  }
  return found;
}

template <typename Point, int D>
std::array<const Point*, D + 1> MeshContact<Point, D>::pair_points(const ContactPair& pair) const {
  std::array<const Point*, D + 1> points;
  points[0] = &surface(pair.vertex_side).vertices[pair.vertex];
  const auto& other = surface(1 - pair.vertex_side);
  for (int k = 0; k < D; ++k)
    points[k + 1] = &other.vertices[other.elements[pair.element][k]];
  return points;
}

template <typename Point, int D>
void MeshContact<Point, D>::add_force(double, const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                                      Eigen::VectorXd& force) const {
  for (const ContactPair& pair : pairs(q)) {
    const auto points = pair_points(pair);
    std::array<Vector, D + 1> position, velocity, on_point;
    for (int k = 0; k <= D; ++k) {
      position[k] = points[k]->position(q);
      velocity[k] = points[k]->velocity(q, v);
    }
    const double sign = surface(1 - pair.vertex_side).normal_signs[pair.element];
    if (!pair_forces<double, D>(position, velocity, sign, law_, on_point)) continue;
    for (int k = 0; k <= D; ++k)
      points[k]->add_load(q, on_point[k], force);
  }
}

template <typename Point, int D>
bool MeshContact<Point, D>::add_jacobian_entries(double, const Eigen::VectorXd& q,
                                                 const Eigen::VectorXd& v,
                                                 MatrixSink& force_by_position,
                                                 MatrixSink& force_by_velocity) const {
  using Scalar = Dual<D>;
  constexpr int velocity_offset = D * (D + 1);
  using Matrix = Eigen::Matrix<double, D, D>;
  for (const ContactPair& pair : pairs(q)) {
    const auto points = pair_points(pair);
    std::array<Vec<Scalar, D>, D + 1> position, velocity, on_point;
    std::array<PointColumns<D>, D + 1> jacobian, velocity_jacobian;
    for (int k = 0; k <= D; ++k) {
      const Vector x = points[k]->position(q), u = points[k]->velocity(q, v);
      for (int c = 0; c < D; ++c) {
        position[k](c) = Scalar(x(c), kPairUnknowns<D>, k * D + c);
        velocity[k](c) = Scalar(u(c), kPairUnknowns<D>, velocity_offset + k * D + c);
      }
      points[k]->add_jacobian(q, 1.0, jacobian[k]);
      points[k]->add_velocity_jacobian(q, v, 1.0, velocity_jacobian[k]);
    }
    const double sign = surface(1 - pair.vertex_side).normal_signs[pair.element];
    if (!pair_forces<Scalar, D>(position, velocity, sign, law_, on_point)) continue;
    // Q = sum_k J_k^T F_k(x, u) with x_j = r_j(q), u_j = J_j(q) v:
    // dQ/dq = sum J_k^T (dF_k/dx_j J_j + dF_k/du_j d(J_j v)/dq) + d(J_k^T)/dq F_k,
    // dQ/dv = sum J_k^T dF_k/du_j J_j.
    for (int k = 0; k <= D; ++k) {
      Vector value;
      for (int c = 0; c < D; ++c)
        value(c) = on_point[k](c).value();
      for (int j = 0; j <= D; ++j) {
        Matrix by_position, by_velocity;
        for (int r = 0; r < D; ++r) {
          for (int c = 0; c < D; ++c) {
            by_position(r, c) = on_point[k](r).derivatives()(j * D + c);
            by_velocity(r, c) = on_point[k](r).derivatives()(velocity_offset + j * D + c);
          }
        }
        jacobian[k].add_transpose_product(force_by_position, by_position, jacobian[j]);
        jacobian[k].add_transpose_product(force_by_position, by_velocity, velocity_jacobian[j]);
        jacobian[k].add_transpose_product(force_by_velocity, by_velocity, jacobian[j]);
      }
      points[k]->add_load_derivative(q, value, force_by_position);
    }
  }
  return true;
}

template <typename Point, int D>
double MeshContact<Point, D>::potential_energy(double, const Eigen::VectorXd& q) const {
  double energy = 0.0;
  for (const ContactPair& pair : pairs(q))
    energy += 0.5 * law_.stiffness * pair.depth * pair.depth;
  return energy;
}

std::vector<double> planar_outward_signs(const std::vector<Eigen::Vector3d>& vertices,
                                         const std::vector<std::array<int, 2>>& elements) {
  // An open polyline acts to the left of its direction of travel: -1 turns the right normal.
  std::vector<double> signs(elements.size(), -1.0);
  std::vector<bool> visited(elements.size(), false);
  auto same_place = [&](int a, int b) {
    return a == b || (vertices[a].head<2>() - vertices[b].head<2>()).norm() <=
                         1e-12 * (1.0 + vertices[a].head<2>().norm());
  };
  for (std::size_t start = 0; start < elements.size(); ++start) {
    if (visited[start]) continue;
    // Follow the segments end to start; a loop back to `start` is a closed outline.
    std::vector<std::size_t> loop{start};
    visited[start] = true;
    bool closed = false;
    for (;;) {
      const int end = elements[loop.back()][1];
      if (same_place(end, elements[start][0])) {
        closed = true;
        break;
      }
      std::size_t next = elements.size();
      for (std::size_t e = 0; e < elements.size() && next == elements.size(); ++e) {
        if (!visited[e] && same_place(elements[e][0], end)) next = e;
      }
      if (next == elements.size()) break;
      visited[next] = true;
      loop.push_back(next);
    }
    if (!closed) continue;
    double twice_area = 0.0;
    for (std::size_t e : loop) {
      const Eigen::Vector3d& a = vertices[elements[e][0]];
      const Eigen::Vector3d& b = vertices[elements[e][1]];
      twice_area += a.x() * b.y() - b.x() * a.y();
    }
    // Counter-clockwise (positive area): outward is to the right of travel.
    for (std::size_t e : loop)
      signs[e] = twice_area > 0.0 ? 1.0 : -1.0;
  }
  return signs;
}

double spatial_outward_sign(const std::vector<Eigen::Vector3d>& vertices,
                            const std::vector<std::array<int, 3>>& elements) {
  // Closed: every directed edge has its reverse in another triangle.
  std::vector<std::pair<int, int>> edges;
  for (const auto& triangle : elements) {
    for (int k = 0; k < 3; ++k)
      edges.emplace_back(triangle[k], triangle[(k + 1) % 3]);
  }
  std::sort(edges.begin(), edges.end());
  bool closed = !edges.empty();
  for (const auto& [a, b] : edges)
    closed = closed && std::binary_search(edges.begin(), edges.end(), std::make_pair(b, a));
  if (!closed) return 1.0;
  double six_volume = 0.0;
  for (const auto& triangle : elements) {
    six_volume += vertices[triangle[0]].dot(vertices[triangle[1]].cross(vertices[triangle[2]]));
  }
  return six_volume > 0.0 ? 1.0 : -1.0;
}

template class MeshContact<BodyPoint, 2>;
template class MeshContact<SpatialPoint, 3>;

}  // namespace fsi::mbd::detail
