// Model's spatial (3D) bodies, connectors and markers (fsi/mbd/model.hpp, "spatial
// bodies and connectors"); the planar ones are in model.cpp and model_elements.cpp.

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "ancf_cable_3d.hpp"
#include "direction_rows.hpp"
#include "force_elements.hpp"
#include "fsi/common/error.hpp"
#include "fsi/common/text.hpp"
#include "fsi/mbd/model.hpp"
#include "model_data.hpp"
#include "point_rows.hpp"
#include "point_to_point_force.hpp"
#include "rigid_body_3d.hpp"
#include "spatial_rotational_spring.hpp"
#include "tension_law.hpp"

namespace fsi::mbd {

using detail::element_name;

namespace {

constexpr const char* kAxisNames[3] = {" (x)", " (y)", " (z)"};

// Two unit vectors normal to `axis` and to each other.
std::pair<Eigen::Vector3d, Eigen::Vector3d> normals(const Eigen::Vector3d& axis) {
  const Eigen::Vector3d a = axis.normalized();
  Eigen::Index smallest = 0;
  a.cwiseAbs().minCoeff(&smallest);
  const Eigen::Vector3d first = a.cross(Eigen::Vector3d::Unit(smallest)).normalized();
  return {first, a.cross(first)};
}

// Three rows that lock the relative orientation of two bodies: e_k . e_l' = 0 for (k, l) = (1, 2),
// (1, 3), (2, 3), with e_k = own(k) the axes of one body and e_l' = held(l) the directions of the
// other that coincide with them initially (the fixed and the prismatic joint in space).
template <typename Own, typename Held>
void add_orientation_rows(std::vector<std::unique_ptr<ConstraintElement>>& constraints,
                          const std::string& user, const Own& own, const Held& held) {
  static constexpr int kPairs[3][2] = {{0, 1}, {0, 2}, {1, 2}};
  for (const auto& pair : kPairs) {
    constraints.push_back(std::make_unique<detail::PerpendicularityConstraint>(
        user + " (e" + std::to_string(pair[0] + 1) + " . e" + std::to_string(pair[1] + 1) + "')",
        own(pair[0]), held(pair[1])));
  }
}

// The spatial body `body` as a Kind (RigidBody3D, AncfCable3D); a body of another kind is a user's
// mistake, named with `kind_name` and the `add_function` that makes one.
template <typename Kind, typename ModelData>
const Kind& spatial_body_of_kind(const ModelData& data, BodyId body, const char* lookup,
                                 const std::string& kind_name, const std::string& add_function) {
  const auto& spatial = data.spatial_body(body, lookup);
  const auto* of_kind = dynamic_cast<const Kind*>(&spatial);
  if (of_kind == nullptr) {
    throw Error("'" + spatial.name() + "' is not " + kind_name, "multibody model",
                "refer to a body added with " + add_function);
  }
  return *of_kind;
}

}  // namespace

BodyId Model::add_rigid_body_3d(const RigidBody3DSpec& spec) {
  auto body = std::make_unique<detail::RigidBody3D>(spec);
  const BodyId id = data_->add_body(std::move(body), "rigid body");
  const int offset = data_->offsets[id];
  static constexpr int kPairs[6][2] = {{0, 0}, {1, 1}, {2, 2}, {0, 1}, {0, 2}, {1, 2}};
  for (const auto& pair : kPairs) {
    data_->constraints.push_back(std::make_unique<detail::OrthonormalityConstraint>(
        "rigid body '" + spec.name + "' orthonormality (e" + std::to_string(pair[0] + 1) + ".e" +
            std::to_string(pair[1] + 1) + ")",
        offset, pair[0], pair[1]));
  }
  return id;
}

BodyId Model::add_point_mass(const PointMassSpec& spec) {
  return data_->add_body(std::make_unique<detail::PointMass3D>(spec), "point mass");
}

BodyId Model::add_ancf_cable(const AncfCableSpec& spec) {
  return data_->add_body(std::make_unique<detail::AncfCable3D>(spec), "ANCF cable");
}

int Model::add_cable_clamp(BodyId cable_id, int node) {
  const int first = constraint_count();
  const auto* cable = [&] {
    data_->check_body(cable_id, "a cable clamp");
    const auto* c = dynamic_cast<const detail::AncfCable3D*>(data_->bodies[cable_id].get());
    if (c == nullptr) {
      throw Error("a cable clamp needs an ANCF cable but '" + data_->bodies[cable_id]->name() +
                      "' is not one",
                  "multibody model", "clamp a body added with add_ancf_cable");
    }
    return c;
  }();
  if (node < 0 || node >= cable->node_count()) {
    throw Error("a cable clamp refers to node " + std::to_string(node) + " of ANCF cable '" +
                    cable->name() + "', which has nodes 0.." +
                    std::to_string(cable->node_count() - 1),
                "multibody model", "refer to an existing node (0 is the start)");
  }
  const Eigen::VectorXd reference = cable->reference_coordinates();
  const std::string target = "cable clamp on " + cable->name() + " node " + std::to_string(node);
  const int base = data_->offsets[cable_id] + 6 * node;
  for (int k = 0; k < 3; ++k) {
    data_->constraints.push_back(std::make_unique<detail::CoordinateConstraint>(
        target + kAxisNames[k], base + k, reference(6 * node + k)));
  }
  // The slope stays normal to two initial normals n1, n2: its direction is held, its length
  // (the axial strain at the clamp) is free, as the planar BeamClamp::Direction.
  const auto [n1, n2] = normals(reference.segment<3>(6 * node + 3));
  int which = 1;
  for (const Eigen::Vector3d& n : {n1, n2}) {
    Eigen::VectorXi indices(3);
    indices << base + 3, base + 4, base + 5;
    data_->constraints.push_back(std::make_unique<detail::LinearCoordinateConstraint>(
        target + " (slope direction " + std::to_string(which++) + ")", indices, n, 0.0));
  }
  return first;
}

void Model::set_spatial_gravity(const Eigen::Vector3d& acceleration) {
  if (!acceleration.allFinite()) {
    throw Error("gravity is not finite", "multibody model", "give a finite acceleration vector");
  }
  data_->spatial_gravity = acceleration;
}

int Model::add_spatial_marker(BodyId body, const Eigen::Vector3d& local_coordinates) {
  (void)data_->spatial_point({body, local_coordinates}, "a marker");  // checks body and point
  data_->require_dimension(3, "a spatial marker");
  data_->markers.push_back({body, Eigen::Vector2d::Zero(), local_coordinates});
  data_->point_loads.resize(3 * data_->markers.size(), 0.0);
  return static_cast<int>(data_->markers.size()) - 1;
}

int Model::add_spherical_joint(const SpatialPointSpec& a, const SpatialPointSpec& b,
                               const std::string& name) {
  const int first = constraint_count();
  const std::string user = element_name("spherical joint", name, first);
  const detail::SpatialPoint pa = data_->spatial_point(a, user);
  const detail::SpatialPoint pb = data_->spatial_point(b, user);
  data_->check_pair({a.body, {}}, {b.body, {}}, user);
  for (int axis = 0; axis < 3; ++axis) {
    data_->constraints.push_back(
        std::make_unique<detail::SpatialPointConstraint>(user + kAxisNames[axis], pa, pb, axis));
  }
  return first;
}

int Model::add_revolute_joint_3d(const RevoluteJoint3DSpec& spec) {
  const int first = constraint_count();
  const std::string user = element_name("revolute joint", spec.name, first);
  const std::string fix =
      "connect RigidBody3D bodies (or the ground); hold a cable with a clamp or a spherical joint";
  const detail::RigidBody3D* body_a = data_->rigid_body_3d_or_ground(spec.a.body, user, fix);
  const detail::RigidBody3D* body_b = data_->rigid_body_3d_or_ground(spec.b.body, user, fix);
  const double axis_length = spec.axis.norm();
  if (!(axis_length > 0.0) || !spec.axis.allFinite()) {
    throw Error("the axis must be a finite, non-zero vector", user, "give e.g. axis = [0, 0, 1]");
  }
  if (spec.rate && !std::isfinite(*spec.rate)) {
    throw Error("the drive rate is not finite, got " + significant(*spec.rate, 9), user,
                "give a finite rate [rad/s], or none for a free hinge");
  }
  data_->check_pair({spec.a.body, {}}, {spec.b.body, {}}, user);
  const detail::SpatialPoint pa = data_->spatial_point(spec.a, user);
  const detail::SpatialPoint pb = data_->spatial_point(spec.b, user);
  for (int axis = 0; axis < 3; ++axis) {
    data_->constraints.push_back(
        std::make_unique<detail::SpatialPointConstraint>(user + kAxisNames[axis], pa, pb, axis));
  }
  // The axis in the world and in b's body frame; two directions of b normal to it.
  const Eigen::Vector3d unit = spec.axis / axis_length;
  const Eigen::Matrix3d from_a =
      body_a != nullptr ? Eigen::Matrix3d(body_a->spec().orientation) : Eigen::Matrix3d::Identity();
  const Eigen::Vector3d world = from_a * unit;
  const Eigen::Matrix3d to_b = body_b != nullptr
                                   ? Eigen::Matrix3d(body_b->spec().orientation.transpose())
                                   : Eigen::Matrix3d::Identity();
  const auto [n1, n2] = normals(to_b * world);
  const detail::SpatialDirection axis_direction{
      pa, data_->spatial_point({spec.a.body, spec.a.local + unit}, user)};
  int which = 1;
  for (const Eigen::Vector3d& n : {n1, n2}) {
    const detail::SpatialDirection normal{
        pb, data_->spatial_point({spec.b.body, spec.b.local + n}, user)};
    data_->constraints.push_back(std::make_unique<detail::PerpendicularityConstraint>(
        user + " (axis normal " + std::to_string(which++) + ")", axis_direction, normal));
  }
  if (spec.rate) {
    // e1, e2 normal to the axis in a's frame (e1 x e2 = axis), u the direction of b along e1
    // initially.
    const auto [e1, e2] = normals(unit);
    auto of_a = [&](const Eigen::Vector3d& d) {
      return detail::SpatialDirection{pa,
                                      data_->spatial_point({spec.a.body, spec.a.local + d}, user)};
    };
    const detail::SpatialDirection u{
        pb, data_->spatial_point({spec.b.body, spec.b.local + to_b * (from_a * e1)}, user)};
    data_->constraints.push_back(std::make_unique<detail::RotationDriveConstraint>(
        user + " (drive)", of_a(e1), of_a(e2), u, *spec.rate));
  }
  return first;
}

int Model::add_fixed_joint_3d(const FixedJoint3DSpec& spec) {
  const int first = constraint_count();
  const std::string user = element_name("fixed joint", spec.name, first);
  if (spec.body == kGround) {
    throw Error("the fixed body is the ground", user, "fix a RigidBody3D to the ground or a body");
  }
  data_->check_pair({spec.body, {}}, {spec.to, {}}, user);
  const std::string fix = "fix RigidBody3D bodies (or to the ground)";
  const detail::RigidBody3D* fixed = data_->rigid_body_3d_or_ground(spec.body, user, fix);
  const detail::RigidBody3D* holder = data_->rigid_body_3d_or_ground(spec.to, user, fix);
  // The body's centre and axes in the frame of `to` (the world for the ground).
  const Eigen::Matrix3d to_frame =
      holder != nullptr ? Eigen::Matrix3d(holder->spec().orientation) : Eigen::Matrix3d::Identity();
  const Eigen::Vector3d origin =
      holder != nullptr ? holder->spec().position : Eigen::Vector3d::Zero();
  const Eigen::Vector3d centre = to_frame.transpose() * (fixed->spec().position - origin);
  const Eigen::Matrix3d axes = to_frame.transpose() * fixed->spec().orientation;
  const detail::SpatialPoint own = data_->spatial_point({spec.body, Eigen::Vector3d::Zero()}, user);
  const detail::SpatialPoint held = data_->spatial_point({spec.to, centre}, user);
  for (int axis = 0; axis < 3; ++axis) {
    data_->constraints.push_back(
        std::make_unique<detail::SpatialPointConstraint>(user + kAxisNames[axis], own, held, axis));
  }
  auto body_axis = [&](int k) {
    return detail::SpatialDirection{
        own, data_->spatial_point({spec.body, Eigen::Vector3d::Unit(k)}, user)};
  };
  auto held_axis = [&](int k) {
    return detail::SpatialDirection{held,
                                    data_->spatial_point({spec.to, centre + axes.col(k)}, user)};
  };
  add_orientation_rows(data_->constraints, user, body_axis, held_axis);
  return first;
}

int Model::add_prismatic_joint_3d(const PrismaticJoint3DSpec& spec) {
  const int first = constraint_count();
  const std::string user = element_name("prismatic joint", spec.name, first);
  const std::string fix = "connect RigidBody3D bodies (or the ground)";
  const detail::RigidBody3D* body_a = data_->rigid_body_3d_or_ground(spec.a.body, user, fix);
  const detail::RigidBody3D* body_b = data_->rigid_body_3d_or_ground(spec.b.body, user, fix);
  const double axis_length = spec.axis.norm();
  if (!(axis_length > 0.0) || !spec.axis.allFinite()) {
    throw Error("the axis must be a finite, non-zero vector", user, "give e.g. axis = [1, 0, 0]");
  }
  data_->check_pair({spec.a.body, {}}, {spec.b.body, {}}, user);
  const Eigen::Matrix3d frame_a =
      body_a != nullptr ? Eigen::Matrix3d(body_a->spec().orientation) : Eigen::Matrix3d::Identity();
  const Eigen::Matrix3d frame_b =
      body_b != nullptr ? Eigen::Matrix3d(body_b->spec().orientation) : Eigen::Matrix3d::Identity();
  const Eigen::Vector3d unit = spec.axis / axis_length;
  const Eigen::Vector3d offset =
      data_->initial_spatial_position(spec.b) - data_->initial_spatial_position(spec.a);
  const double off_line = (offset - offset.dot(frame_a * unit) * (frame_a * unit)).norm();
  if (off_line > 1e-9 * std::max(1.0, offset.norm())) {
    throw Error("point_b is " + significant(off_line, 6) +
                    " m off the sliding line through point_a along the axis",
                user, "place point_b on that line (or point_a on it, or turn the axis)");
  }
  const detail::SpatialPoint pa = data_->spatial_point(spec.a, user);
  const detail::SpatialPoint pb = data_->spatial_point(spec.b, user);
  // The offset b - a stays normal to the two normals of the axis fixed in a.
  const detail::SpatialDirection offset_direction{pa, pb};
  const auto [n1, n2] = normals(unit);
  int which = 1;
  for (const Eigen::Vector3d& n : {n1, n2}) {
    const detail::SpatialDirection normal{
        pa, data_->spatial_point({spec.a.body, spec.a.local + n}, user)};
    data_->constraints.push_back(std::make_unique<detail::PerpendicularityConstraint>(
        user + " (normal " + std::to_string(which++) + ")", offset_direction, normal));
  }
  // a's axes e_k and the directions of b that coincide with them initially stay perpendicular.
  const Eigen::Matrix3d a_in_b = frame_b.transpose() * frame_a;
  auto axis_of_a = [&](int k) {
    return detail::SpatialDirection{
        pa, data_->spatial_point({spec.a.body, spec.a.local + Eigen::Vector3d::Unit(k)}, user)};
  };
  auto axis_on_b = [&](int k) {
    return detail::SpatialDirection{
        pb, data_->spatial_point({spec.b.body, spec.b.local + a_in_b.col(k)}, user)};
  };
  add_orientation_rows(data_->constraints, user, axis_of_a, axis_on_b);
  return first;
}

int Model::add_cable_surface_marker(BodyId cable_id, double s, double angle, double radius) {
  (void)cable(cable_id);
  if (!std::isfinite(angle) || !(radius >= 0.0) || !std::isfinite(radius)) {
    throw Error("the tube angle or radius is not finite (or the radius negative)",
                "a tube vertex on '" + data_->bodies[cable_id]->name() + "'",
                "give a finite angle and a non-negative radius");
  }
  const int marker = add_spatial_marker(cable_id, {s, 0.0, 0.0});
  // The vertex's direction from the centre line in the straight initial cable, once.
  const AncfCableSpec& spec = cable(cable_id);
  const auto [n1, n2] = normals(spec.end - spec.start);
  data_->markers[marker].tube_radius = radius;
  data_->markers[marker].tube_offset = std::cos(angle) * n1 + std::sin(angle) * n2;
  return marker;
}

int Model::add_spatial_distance_constraint(const SpatialPointSpec& a, const SpatialPointSpec& b,
                                           std::optional<double> length, const std::string& name) {
  const std::string user = element_name("distance constraint", name, constraint_count());
  const detail::SpatialPoint pa = data_->spatial_point(a, user);
  const detail::SpatialPoint pb = data_->spatial_point(b, user);
  data_->check_pair({a.body, {}}, {b.body, {}}, user);
  const double rod = length.value_or(
      (data_->initial_spatial_position(b) - data_->initial_spatial_position(a)).norm());
  if (!(rod > 0.0) || !std::isfinite(rod)) {
    throw Error("the length must be positive and finite, got " + significant(rod, 9), user,
                "give a positive length, or place the points apart initially");
  }
  data_->constraints.push_back(
      std::make_unique<detail::SpatialDistanceConstraint>(user, pa, pb, rod));
  return constraint_count() - 1;
}

int Model::add_spatial_point_force(const SpatialPointForceSpec& spec) {
  const int index = force_element_count();
  const std::string user = element_name("point force", spec.name, index);
  detail::check_time_load(spec.point.body == kGround, static_cast<bool>(spec.force), false, user);
  add_force_element(std::make_unique<detail::SpatialPointForce>(
      user, data_->spatial_point(spec.point, user), spec.force));
  return index;
}

int Model::add_spatial_spring_damper(const SpatialSpringDamperSpec& spec) {
  const int index = force_element_count();
  const std::string user = element_name("spring-damper", spec.name, index);
  const detail::SpatialPoint a = data_->spatial_point(spec.a, user);
  const detail::SpatialPoint b = data_->spatial_point(spec.b, user);
  data_->check_pair({spec.a.body, {}}, {spec.b.body, {}}, user);
  const double rest = spec.rest_length.value_or(
      (data_->initial_spatial_position(spec.b) - data_->initial_spatial_position(spec.a)).norm());
  detail::check_spring_values(spec.stiffness, spec.damping, rest, user);
  add_force_element(std::make_unique<detail::SpatialPointToPointForce>(
      user, a, b, rest, std::make_shared<detail::LinearTension>(spec.stiffness, spec.damping)));
  return index;
}

int Model::add_spatial_nonlinear_spring_damper(const SpatialNonlinearSpringDamperSpec& spec) {
  const int index = force_element_count();
  const std::string user = element_name("nonlinear spring-damper", spec.name, index);
  if (!spec.tension)
    throw Error("no tension function", user, "give tension(elongation, rate, time)");
  const detail::SpatialPoint a = data_->spatial_point(spec.a, user);
  const detail::SpatialPoint b = data_->spatial_point(spec.b, user);
  data_->check_pair({spec.a.body, {}}, {spec.b.body, {}}, user);
  const double rest = detail::rest_length_of(
      spec.rest_length,
      (data_->initial_spatial_position(spec.b) - data_->initial_spatial_position(spec.a)).norm(),
      user);
  add_force_element(std::make_unique<detail::SpatialPointToPointForce>(
      user, a, b, rest, std::make_shared<detail::UserTension>(spec.tension)));
  return index;
}

int Model::add_spatial_torque(const SpatialTorqueSpec& spec) {
  const int index = force_element_count();
  const std::string user = element_name("torque", spec.name, index);
  detail::check_time_load(spec.body == kGround, static_cast<bool>(spec.torque), true, user);
  const auto& body = data_->spatial_body(spec.body, user);
  if (dynamic_cast<const detail::RigidBody3D*>(&body) == nullptr) {
    throw Error("'" + body.name() + "' is not a spatial rigid body", user,
                "apply torques to RigidBody3D bodies; load a cable or a point mass with forces");
  }
  add_force_element(
      std::make_unique<detail::SpatialTorque>(user, data_->offsets[spec.body] + 3, spec.torque));
  return index;
}

int Model::add_spatial_rotational_spring_damper(const SpatialRotationalSpringDamperSpec& spec) {
  const int index = force_element_count();
  const bool user_law = static_cast<bool>(spec.torque);
  const std::string user =
      element_name(user_law ? "nonlinear rotational spring-damper" : "rotational spring-damper",
                   spec.name, index);
  const std::string fix = "connect RigidBody3D bodies (or body_a to the ground)";
  if (spec.a == kGround) {
    throw Error("body a is the ground", user,
                "give the body whose axis holds the spring as body_a, the ground (if any) as b");
  }
  const detail::RigidBody3D* body_a = data_->rigid_body_3d_or_ground(spec.a, user, fix);
  const detail::RigidBody3D* body_b = data_->rigid_body_3d_or_ground(spec.b, user, fix);
  data_->check_pair({spec.a, {}}, {spec.b, {}}, user);
  const double axis_length = spec.axis.norm();
  if (!(axis_length > 0.0) || !spec.axis.allFinite()) {
    throw Error("the axis must be a finite, non-zero vector", user, "give e.g. axis = [0, 0, 1]");
  }
  if (!std::isfinite(spec.stiffness) || spec.stiffness < 0.0 || !std::isfinite(spec.damping) ||
      spec.damping < 0.0) {
    throw Error("stiffness and damping must be finite and non-negative", user,
                "check stiffness and damping");
  }
  if (user_law && (spec.stiffness != 0.0 || spec.damping != 0.0)) {
    throw Error("a torque law and a stiffness or damping", user,
                "write the whole torque in the law (k*rotation + c*rate + ...)");
  }
  const double rest = spec.rest_angle.value_or(0.0);
  if (!std::isfinite(rest)) throw Error("the rest angle is not finite", user, "check rest_angle");
  if (std::abs(rest) > detail::SpatialRotationalSpringDamper::kTwistLimit) {
    throw Error("the rest angle " + significant(rest, 6) +
                    " rad is beyond the +-170 degrees (2.967 rad) the twist is measured within",
                user,
                "give the rest angle within half a turn of the initial configuration (a turn "
                "more or less is the same rest position)");
  }
  // e1, e2 normal to the axis in a's axes (e1 x e2 = axis); u the direction of b (or of the
  // world) along e1 initially: differences of material points, from the centres of mass.
  const Eigen::Vector3d unit = spec.axis / axis_length;
  const auto [e1, e2] = normals(unit);
  const Eigen::Vector3d e1_world = Eigen::Matrix3d(body_a->spec().orientation) * e1;
  auto direction = [&](BodyId body, const Eigen::Vector3d& local) {
    return detail::SpatialDirection{data_->spatial_point({body, Eigen::Vector3d::Zero()}, user),
                                    data_->spatial_point({body, local}, user)};
  };
  const detail::SpatialDirection u =
      body_b != nullptr
          ? direction(spec.b, Eigen::Matrix3d(body_b->spec().orientation).transpose() * e1_world)
          : direction(kGround, e1_world);
  std::shared_ptr<const detail::TensionLaw> law;
  if (user_law) {
    law = std::make_shared<detail::UserTension>(spec.torque);
  } else {
    law = std::make_shared<detail::LinearTension>(spec.stiffness, spec.damping);
  }
  add_force_element(std::make_unique<detail::SpatialRotationalSpringDamper>(
      user, direction(spec.a, e1), direction(spec.a, e2), u, rest, std::move(law)));
  return index;
}

const std::string& Model::body_name(BodyId body) const {
  data_->check_body(body, "a body lookup");
  return data_->bodies[body]->name();
}

std::string Model::body_kind(BodyId body) const {
  data_->check_body(body, "a body lookup");
  const detail::Body* b = data_->bodies[body].get();
  if (dynamic_cast<const detail::RigidBody2D*>(b)) return "rigid_body_2d";
  if (dynamic_cast<const detail::AncfBeam2D*>(b)) return "ancf_beam";
  if (dynamic_cast<const detail::RigidBody3D*>(b)) return "rigid_body_3d";
  if (dynamic_cast<const detail::PointMass3D*>(b)) return "point_mass";
  return "ancf_cable";
}

double Model::body_mass(BodyId body) const {
  data_->check_body(body, "a body lookup");
  const detail::Body* b = data_->bodies[body].get();
  if (const auto* r = dynamic_cast<const detail::RigidBody2D*>(b)) return r->spec().mass;
  if (const auto* r = dynamic_cast<const detail::RigidBody3D*>(b)) return r->spec().mass;
  if (const auto* p = dynamic_cast<const detail::PointMass3D*>(b)) return p->spec().mass;
  if (const auto* beam = dynamic_cast<const detail::AncfBeam2D*>(b))
    return beam->spec().mass_per_length * beam->length();
  const auto& c = dynamic_cast<const detail::AncfCable3D&>(*b);
  return c.spec().mass_per_length * c.length();
}

int Model::dimension() const {
  return data_->stride();
}

const RigidBody3DSpec& Model::rigid_body_3d(BodyId body) const {
  return spatial_body_of_kind<detail::RigidBody3D>(*data_, body, "a body lookup",
                                                   "a spatial rigid body", "add_rigid_body_3d")
      .spec();
}

bool Model::is_cable(BodyId body) const {
  data_->check_body(body, "a body lookup");
  return dynamic_cast<const detail::AncfCable3D*>(data_->bodies[body].get()) != nullptr;
}

const AncfCableSpec& Model::cable(BodyId cable) const {
  return spatial_body_of_kind<detail::AncfCable3D>(*data_, cable, "a cable lookup", "an ANCF cable",
                                                   "add_ancf_cable")
      .spec();
}

int Model::cable_node_count(BodyId cable_id) const {
  return cable(cable_id).element_count + 1;
}

int Model::cable_coordinate_index(BodyId cable_id, int node, int component) const {
  const int nodes = cable_node_count(cable_id);
  FSI_ASSERT(node >= 0 && node < nodes && component >= 0 && component < 6,
             "cable node or component out of range");
  return data_->offsets[cable_id] + 6 * node + component;
}

void Model::check_spatial_point(const SpatialPointSpec& point, const std::string& user) const {
  (void)data_->spatial_point(point, user);
}

}  // namespace fsi::mbd
