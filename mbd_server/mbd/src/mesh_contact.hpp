#pragma once
// Penalty contact between two surface meshes (internal; built by Model::add_contact from a
// ContactSpec, law and conventions in element_specs.hpp and docs/theory.md): planar vertex to
// segment (BodyPoint, D = 2) and spatial vertex to triangle (SpatialPoint, D = 3), both ways.
//
// A contact pair is a vertex of one surface and an element (D vertices) of the other. Its forces
// are a function of the D + 1 points' world positions and velocities alone; their derivatives
// with respect to those 2 D (D + 1) numbers are exact (forward-mode automatic differentiation of
// the same code, pair_forces below) and reach q and v through the points' exact Jacobians, as
// for the spring-damper. Which element a vertex acts against (the smallest depth among those it
// lies behind and projects onto) is decided at (q) and held fixed for the derivatives.

#include <array>
#include <string>
#include <vector>

#include "body_point.hpp"
#include "fsi/mbd/element_specs.hpp"
#include "fsi/mbd/force_element.hpp"
#include "sink_elements.hpp"

namespace fsi::mbd::detail {

struct ContactLaw {
  double stiffness = 0.0;
  double damping = 0.0;
  double friction_coefficient = 0.0;
  double regularisation_speed = 1e-3;
  double depth_limit = 0.0;
  double damping_onset_depth = 0.0;
};

// One surface in the form the element evaluates: its vertices as points of the model, its
// elements, and per element +1 or -1 that turns its geometric normal (planar: right of a -> b;
// spatial: (b - a) x (c - a)) into the outward one.
template <typename Point, int D>
struct ContactSurface {
  std::string name;
  std::vector<Point> vertices;
  std::vector<std::array<int, D>> elements;
  std::vector<double> normal_signs;
};

// A vertex of surface `vertex_side` (0 or 1) behind element `element` of the other surface.
struct ContactPair {
  int vertex_side = 0;
  int vertex = 0;
  int element = 0;
  double depth = 0.0;
};

template <typename Point, int D>
class MeshContact final : public SparseForceElement {
 public:
  using Vector = Eigen::Matrix<double, D, 1>;
  MeshContact(std::string description, ContactSurface<Point, D> first,
              ContactSurface<Point, D> second, const ContactLaw& law);

  void add_force(double time, const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                 Eigen::VectorXd& force) const override;
  bool add_jacobian_entries(double time, const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                            MatrixSink& force_by_position,
                            MatrixSink& force_by_velocity) const override;
  // stiffness delta^2 / 2 over the pairs in contact: the penalty energy.
  double potential_energy(double time, const Eigen::VectorXd& q) const override;

  // The pairs in contact at q (broad phase by bounding boxes, then per element).
  std::vector<ContactPair> pairs(const Eigen::VectorXd& q) const;

 private:
  const ContactSurface<Point, D>& surface(int side) const { return side == 0 ? first_ : second_; }
  // The pair's D + 1 points: its vertex, then the element's vertices.
  std::array<const Point*, D + 1> pair_points(const ContactPair& pair) const;

  ContactSurface<Point, D> first_;
  ContactSurface<Point, D> second_;
  ContactLaw law_;
};

using PlanarMeshContact = MeshContact<BodyPoint, 2>;
class SpatialPoint;
using SpatialMeshContact = MeshContact<SpatialPoint, 3>;

// The outward sign of a surface given by local vertex coordinates (rigid motions and the beams'
// (s, eta) map keep orientation): closed outlines by their signed area (planar, per loop: a loop
// of negative area is reversed) or volume (spatial); open ones by the convention of
// ContactSurfaceSpec. Planar: one sign per element (loops may wind differently); spatial: the
// same sign for every element.
std::vector<double> planar_outward_signs(const std::vector<Eigen::Vector3d>& vertices,
                                         const std::vector<std::array<int, 2>>& elements);
double spatial_outward_sign(const std::vector<Eigen::Vector3d>& vertices,
                            const std::vector<std::array<int, 3>>& elements);

}  // namespace fsi::mbd::detail
