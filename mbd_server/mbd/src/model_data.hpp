#pragma once
// The model's storage (internal): bodies and their coordinate offsets, markers, constraint rows,
// force elements, gravity and point loads, with the lookups that name the user in their errors.
// Shared by model.cpp (planar bodies, assembly) and model_spatial.cpp (spatial bodies).

#include <Eigen/Dense>
#include <Eigen/SparseCore>

#include <cmath>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "ancf_beam_2d.hpp"
#include "body.hpp"
#include "body_point.hpp"
#include "coordinate_rows.hpp"
#include "fsi/common/error.hpp"
#include "fsi/common/text.hpp"
#include "fsi/mbd/model.hpp"
#include "point_rows.hpp"
#include "rigid_body_3d.hpp"
#include "spatial_body.hpp"

namespace fsi::mbd {
namespace detail {

// A marker of a planar model has `local`, one of a spatial model `spatial_local`.
struct Marker {
  BodyId body;
  Eigen::Vector2d local;  // body frame, or world frame for kGround
  Eigen::Vector3d spatial_local = Eigen::Vector3d::Zero();
  // A vertex of the tube around a cable (Model::add_cable_surface_marker): spatial_local is its
  // centre-line point (s, 0, 0); these place it on the tube.
  double tube_radius = 0.0;
  Eigen::Vector3d tube_offset = Eigen::Vector3d::Zero();  // unit, normal to the initial tangent
};

// "prismatic joint 'slider'" for a named element, "prismatic joint 3" otherwise.
inline std::string element_name(const std::string& kind, const std::string& name, int index) {
  return name.empty() ? kind + " " + std::to_string(index) : kind + " '" + name + "'";
}

// A time-dependent point force (torque = false) or torque needs a body and a function.
inline void check_time_load(bool on_ground, bool has_function, bool torque,
                            const std::string& user) {
  if (on_ground) {
    throw torque ? Error("the torque acts on the ground, where it does nothing", user,
                         "apply the torque to a body")
                 : Error("the point is on the ground, where a force does nothing", user,
                         "apply the force to a body");
  }
  if (!has_function) {
    throw torque ? Error("no torque function", user, "give torque(t)")
                 : Error("no force function", user, "give force(t)");
  }
}

// Throws fsi::Error naming `user` for a negative or non-finite stiffness, damping or rest length.
inline void check_spring_values(double stiffness, double damping, double rest,
                                const std::string& user) {
  std::string problems;
  if (!(stiffness >= 0.0) || !std::isfinite(stiffness)) problems += " stiffness < 0;";
  if (!(damping >= 0.0) || !std::isfinite(damping)) problems += " damping < 0;";
  if (!(rest >= 0.0) || !std::isfinite(rest)) problems += " rest length < 0;";
  if (!problems.empty()) {
    problems.pop_back();
    throw Error("invalid parameters:" + problems, user,
                "give finite, non-negative stiffness, damping and rest length");
  }
}

// The rest length of a point-to-point element: `given`, or the initial distance; throws
// fsi::Error naming `user` if the points coincide initially (no direction) or the length is
// negative or not finite.
inline double rest_length_of(const std::optional<double>& given, double initial,
                             const std::string& user) {
  if (!(initial > 0.0)) {
    throw Error("the two points coincide initially (the direction of the force is undefined)", user,
                "place the points apart");
  }
  const double rest = given.value_or(initial);
  if (!(rest >= 0.0) || !std::isfinite(rest)) {
    throw Error("the rest length must be finite and non-negative, got " + significant(rest, 9),
                user, "give rest_length >= 0 or none (the initial distance)");
  }
  return rest;
}

}  // namespace detail

struct Model::Data {
  std::vector<std::unique_ptr<detail::Body>> bodies;
  std::vector<int> offsets;  // index of each body's first coordinate in q
  int coordinates = 0;
  std::vector<detail::Marker> markers;
  std::vector<std::unique_ptr<ConstraintElement>> constraints;
  // Release time of each row that has one (Model::set_release_time); rows beyond the end hold
  // for ever.
  std::vector<double> release_times;
  std::vector<std::unique_ptr<ForceElement>> force_elements;
  Eigen::Vector2d gravity = Eigen::Vector2d::Zero();
  Eigen::Vector3d spatial_gravity = Eigen::Vector3d::Zero();
  // 0 until the first body or marker decides: 2 (planar bodies) or 3 (spatial bodies). Point
  // loads and marker coordinates have this many values per marker.
  int dimension = 0;
  std::vector<double> point_loads;  // x, y per marker
  mutable Eigen::MatrixXd mass;     // assembled on first use after a structural change
  mutable bool mass_valid = false;
  mutable Eigen::SparseMatrix<double> sparse_mass;  // the same, sparse
  mutable Eigen::VectorXd mass_diagonal;
  mutable bool sparse_mass_valid = false;
  // Set by Model::set_initial_configuration: replaces the bodies' own initial q and v.
  std::optional<std::pair<Eigen::VectorXd, Eigen::VectorXd>> initial_configuration;

  void check_body(BodyId body, const std::string& user) const {
    if (body < 0 || body >= static_cast<BodyId>(bodies.size())) {
      throw Error(user + " refers to body index " + std::to_string(body) + " but the model has " +
                      std::to_string(bodies.size()) + " bodies",
                  "multibody model", "refer to a body that has been added");
    }
  }
  void check_marker(int marker) const {
    if (marker < 0 || marker >= static_cast<int>(markers.size())) {
      throw Error("marker index " + std::to_string(marker) + " out of range (the model has " +
                      std::to_string(markers.size()) + " markers)",
                  "multibody model", "refer to a marker that has been added");
    }
  }
  // The body as a Kind; for a body of another kind `user` is told it needs `kind_name` (`fix`).
  template <typename Kind>
  const Kind& body_of_kind(BodyId body, const std::string& user, const char* kind_name,
                           const char* fix) const {
    check_body(body, user);
    const auto* of_kind = dynamic_cast<const Kind*>(bodies[body].get());
    if (of_kind == nullptr) {
      throw Error(user + " needs " + kind_name + " but '" + bodies[body]->name() + "' is not one",
                  "multibody model", fix);
    }
    return *of_kind;
  }
  const detail::RigidBody2D& rigid_body(BodyId body, const std::string& user) const {
    return body_of_kind<detail::RigidBody2D>(body, user, "a planar rigid body",
                                             "use the coordinates of a RigidBody2D");
  }
  const detail::AncfBeam2D& ancf_beam(BodyId body, const std::string& user) const {
    return body_of_kind<detail::AncfBeam2D>(body, user, "an ANCF beam",
                                            "refer to a body added with add_ancf_beam");
  }
  const detail::AncfBeam2D& beam_node(BodyId body, int node, const std::string& user) const {
    const auto& beam = ancf_beam(body, user);
    if (node < 0 || node >= beam.node_count()) {
      throw Error(user + " refers to node " + std::to_string(node) + " of ANCF beam '" +
                      beam.name() + "', which has nodes 0.." +
                      std::to_string(beam.node_count() - 1),
                  "multibody model", "refer to an existing node (0 is the start)");
    }
    return beam;
  }
  // Fixes the model's dimension at the first use; throws naming `user` on a mix.
  void require_dimension(int wanted, const std::string& user) {
    if (dimension == 0) dimension = wanted;
    if (dimension == wanted) return;
    throw Error(user + " is " + (wanted == 3 ? "spatial (3D)" : "planar (2D)") +
                    " but the model already holds " +
                    (dimension == 3 ? "spatial (3D)" : "planar (2D)") + " bodies or markers",
                "multibody model",
                "build a model of planar bodies (RigidBody2D, AncfBeam2D) or of spatial ones "
                "(RigidBody3D, PointMass, AncfCable3D), not both");
  }
  int stride() const { return dimension == 3 ? 3 : 2; }
  const detail::SpatialBody* as_spatial(BodyId body) const {
    return dynamic_cast<const detail::SpatialBody*>(bodies[body].get());
  }
  const detail::SpatialBody& spatial_body(BodyId body, const std::string& user) const {
    check_body(body, user);
    const auto* spatial = as_spatial(body);
    if (spatial == nullptr) {
      throw Error(user + " needs a spatial (3D) body but '" + bodies[body]->name() + "' is planar",
                  "multibody model", "use the planar form of the element for planar bodies");
    }
    return *spatial;
  }
  // nullptr for the ground; throws naming `user` (with `fix`) for a body that is not a
  // RigidBody3D.
  const detail::RigidBody3D* rigid_body_3d_or_ground(BodyId body, const std::string& user,
                                                     const std::string& fix) const {
    if (body == kGround) return nullptr;
    const auto* rigid = dynamic_cast<const detail::RigidBody3D*>(&spatial_body(body, user));
    if (rigid == nullptr) {
      throw Error("'" + bodies[body]->name() + "' is not a rigid body", user, fix);
    }
    return rigid;
  }
  // A spatial body point; throws naming `user` for unknown or planar bodies, non-finite or
  // non-material local coordinates.
  detail::SpatialPoint spatial_point(const SpatialPointSpec& spec, const std::string& user) const {
    if (!spec.local.allFinite()) {
      throw Error("point coordinates are not finite", user, "give finite local coordinates");
    }
    if (spec.body == kGround) return {nullptr, 0, spec.local};
    const auto& body = spatial_body(spec.body, user);
    body.check_spatial_local(spec.local, user);
    return {&body, offsets[spec.body], spec.local};
  }
  Eigen::Vector3d initial_spatial_position(const SpatialPointSpec& spec) const {
    if (spec.body == kGround) return spec.local;
    const auto& body = *as_spatial(spec.body);
    Eigen::VectorXd q(body.coordinate_count()), v(body.coordinate_count());
    body.initial_state(q, v);
    return body.spatial_position(q, spec.local);
  }
  BodyId add_body(std::unique_ptr<detail::Body> body, const std::string& kind) {
    require_dimension(dynamic_cast<const detail::SpatialBody*>(body.get()) != nullptr ? 3 : 2,
                      kind + " '" + body->name() + "'");
    for (const auto& other : bodies) {
      if (other->name() == body->name()) {
        throw Error("a second body is named '" + body->name() + "'",
                    kind + " '" + body->name() + "'", "give every body its own name");
      }
    }
    offsets.push_back(coordinates);
    coordinates += body->coordinate_count();
    bodies.push_back(std::move(body));
    mass_valid = false;
    sparse_mass_valid = false;
    return static_cast<BodyId>(bodies.size()) - 1;
  }
  // A body point as the elements see it; throws naming `user` for unknown bodies or
  // non-finite coordinates.
  detail::BodyPoint point(const BodyPointSpec& spec, const std::string& user) const {
    if (!spec.local.allFinite()) {
      throw Error("point coordinates are not finite", user, "give finite local coordinates");
    }
    if (spec.body == kGround) return {nullptr, 0, spec.local};
    check_body(spec.body, user);
    if (as_spatial(spec.body) != nullptr) {
      throw Error(user + " is planar but '" + bodies[spec.body]->name() + "' is a spatial body",
                  "multibody model", "use the spatial form of the element for 3D bodies");
    }
    bodies[spec.body]->check_local_coordinates(spec.local, user);
    return {bodies[spec.body].get(), offsets[spec.body], spec.local};
  }
  // World position of a body point in the bodies' initial state.
  Eigen::Vector2d initial_position(const BodyPointSpec& spec) const {
    if (spec.body == kGround) return spec.local;
    const auto& body = *bodies[spec.body];
    Eigen::VectorXd q(body.coordinate_count()), v(body.coordinate_count());
    body.initial_state(q, v);
    return body.position(q, spec.local);
  }
  std::string point_name(const BodyPointSpec& spec) const {
    if (spec.body == kGround) return "ground";
    return bodies[spec.body]->name();
  }
  // Two points of joints must belong to two different bodies, at most one of them the ground.
  void check_pair(const BodyPointSpec& a, const BodyPointSpec& b, const std::string& user) const {
    if (a.body == b.body) {
      throw Error(
          a.body == kGround ? "both points are on the ground" : "both points are on the same body",
          user, "connect points of two different bodies, or a body and the ground");
    }
  }
  auto segment(const Eigen::VectorXd& x, BodyId body) const {
    return x.segment(offsets[body], bodies[body]->coordinate_count());
  }
};

namespace detail {

// The readouts' view of a model's storage (src/readouts.cpp).
struct ModelAccess {
  using Data = Model::Data;
  static const Data& data(const Model& model) { return *model.data_; }
};

}  // namespace detail

}  // namespace fsi::mbd
