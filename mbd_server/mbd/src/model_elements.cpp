// Model's connectors (prismatic joint, clamp), force elements (rotational, nonlinear and
// piecewise-linear spring-dampers), time-dependent loads, and the readouts of elements for
// sensors and messages. Built only on the public model and the body points, so that new element
// types stay out of model.cpp.

#include <cmath>
#include <memory>
#include <string>

#include "body_point.hpp"
#include "coordinate_rows.hpp"
#include "force_elements.hpp"
#include "fsi/common/error.hpp"
#include "fsi/common/text.hpp"
#include "fsi/mbd/model.hpp"
#include "measured_force.hpp"
#include "model_data.hpp"
#include "point_rows.hpp"
#include "point_to_point_force.hpp"

namespace fsi::mbd {

using detail::element_name;

namespace {

void require_two_ends(BodyId a, BodyId b, const std::string& user) {
  if (a == b) {
    throw Error(a == kGround ? "both ends are on the ground" : "both ends are on the same body",
                user, "connect two different bodies, or a body and the ground");
  }
}

bool non_negative(double value) {
  return std::isfinite(value) && value >= 0.0;
}

// The index of a planar rigid body's angle in q, -1 for the ground.
int angle_index(const Model& model, BodyId body, const std::string& user) {
  if (body == kGround) return -1;
  if (body < 0 || body >= model.body_count()) {
    throw Error("refers to body index " + std::to_string(body) + " but the model has " +
                    std::to_string(model.body_count()) + " bodies",
                user, "refer to a body that has been added");
  }
  try {
    return model.coordinate_index(body, Coordinate::Angle);
  } catch (const Error&) {
    throw Error("needs the angle of a planar rigid body", user,
                "connect RigidBody2D bodies (or the ground)");
  }
}

// Two planar rigid bodies' angles in q (-1 for the ground) and their initial relative angle
// phi_a - phi_b (the ground's angle is 0): what a relative-angle row or a rotational spring needs.
struct AnglePair {
  int a = -1;
  int b = -1;
  double initial_difference = 0.0;
};

AnglePair angle_pair(const Model& model, BodyId a, BodyId b, const std::string& user) {
  AnglePair angles{angle_index(model, a, user), angle_index(model, b, user), 0.0};
  angles.initial_difference =
      (angles.a >= 0 ? model.body(a).angle : 0.0) - (angles.b >= 0 ? model.body(b).angle : 0.0);
  return angles;
}

// angle_pair for an element whose end a must be a body (the ground, if any, at end b):
// `a_is_ground` is the problem and `fix` how to fix it when a is the ground.
AnglePair body_first_angle_pair(const Model& model, BodyId a, BodyId b, const std::string& user,
                                const char* a_is_ground, const char* fix) {
  if (a == kGround) throw Error(a_is_ground, user, fix);
  require_two_ends(a, b, user);
  return angle_pair(model, a, b, user);
}

}  // namespace

int Model::add_prismatic_joint(const PrismaticJointSpec& spec) {
  const int first_row = constraint_count();
  const std::string user = element_name("prismatic joint", spec.name, first_row);
  require_two_ends(spec.a.body, spec.b.body, user);
  const double axis_length = spec.axis.norm();
  if (!(axis_length > 0.0) || !std::isfinite(axis_length)) {
    throw Error("the axis must be a finite, non-zero vector", user, "give e.g. axis = [1, 0]");
  }
  const detail::BodyPoint origin = body_point(spec.a, user);
  const detail::BodyPoint tip = body_point({spec.a.body, spec.a.local + spec.axis}, user);
  const detail::BodyPoint slider = body_point(spec.b, user);
  const AnglePair angles = angle_pair(*this, spec.a.body, spec.b.body, user);
  add_constraint_element(std::make_unique<detail::PrismaticConstraint>(user + " (normal)", origin,
                                                                       tip, slider, axis_length));
  add_constraint_element(std::make_unique<detail::RelativeAngleConstraint>(
      user + " (angle)", angles.a, angles.b, angles.initial_difference));
  return first_row;
}

int Model::add_clamp(const ClampSpec& spec) {
  const int first_row = constraint_count();
  const std::string user = element_name("clamp", spec.name, first_row);
  const AnglePair angles =
      body_first_angle_pair(*this, spec.body, spec.to, user, "the clamped body is the ground",
                            "clamp a body to the ground or a body");
  const RigidBody2DSpec& clamped = body(spec.body);
  // The clamped body's centre of mass in the frame of `to` (world frame for the ground).
  Eigen::Vector2d seen_from_to = clamped.position;
  if (spec.to != kGround) {
    const RigidBody2DSpec& holder = body(spec.to);
    seen_from_to =
        Eigen::Rotation2Dd(holder.angle).inverse() * (clamped.position - holder.position);
  }
  const detail::BodyPoint centre = body_point({spec.body, Eigen::Vector2d::Zero()}, user);
  const detail::BodyPoint held = body_point({spec.to, seen_from_to}, user);
  for (int axis = 0; axis < 2; ++axis) {
    add_constraint_element(std::make_unique<detail::PointConstraint>(
        user + (axis == 0 ? " (x)" : " (y)"), centre, held, axis));
  }
  add_constraint_element(std::make_unique<detail::RelativeAngleConstraint>(
      user + " (angle)", angles.a, angles.b, angles.initial_difference));
  return first_row;
}

namespace {

// The angles of a rotational element between a and b and its rest angle, checked.
struct RotationalEnds {
  int a = -1;
  int b = -1;
  double rest = 0.0;
};

RotationalEnds rotational_ends(const Model& model, BodyId a, BodyId b,
                               const std::optional<double>& rest_angle, const std::string& user) {
  const AnglePair angles = body_first_angle_pair(model, a, b, user, "body a is the ground",
                                                 "put the ground, if any, at end b");
  const double rest = rest_angle.value_or(angles.initial_difference);
  if (!std::isfinite(rest)) throw Error("the rest angle is not finite", user, "check rest_angle");
  return {angles.a, angles.b, rest};
}

}  // namespace

int Model::add_rotational_spring_damper(const RotationalSpringDamperSpec& spec) {
  const int index = force_element_count();
  const std::string user = element_name("rotational spring-damper", spec.name, index);
  const RotationalEnds ends = rotational_ends(*this, spec.a, spec.b, spec.rest_angle, user);
  if (!non_negative(spec.stiffness) || !non_negative(spec.damping)) {
    throw Error("stiffness and damping must be finite and non-negative", user,
                "check stiffness and damping");
  }
  add_force_element(std::make_unique<detail::RotationalSpringDamper>(
      user, ends.a, ends.b, ends.rest,
      std::make_shared<detail::LinearTension>(spec.stiffness, spec.damping)));
  return index;
}

int Model::add_nonlinear_rotational_spring_damper(const NonlinearRotationalSpringDamperSpec& spec) {
  const int index = force_element_count();
  const std::string user = element_name("nonlinear rotational spring-damper", spec.name, index);
  if (!spec.torque) throw Error("no torque function", user, "give torque(rotation, rate, time)");
  const RotationalEnds ends = rotational_ends(*this, spec.a, spec.b, spec.rest_angle, user);
  add_force_element(std::make_unique<detail::RotationalSpringDamper>(
      user, ends.a, ends.b, ends.rest, std::make_shared<detail::UserTension>(spec.torque)));
  return index;
}

int Model::add_nonlinear_spring_damper(const NonlinearSpringDamperSpec& spec) {
  const int index = force_element_count();
  const std::string user = element_name("nonlinear spring-damper", spec.name, index);
  require_two_ends(spec.a.body, spec.b.body, user);
  if (!spec.tension)
    throw Error("no tension function", user, "give tension(elongation, rate, time)");
  const detail::BodyPoint a = body_point(spec.a, user);
  const detail::BodyPoint b = body_point(spec.b, user);
  const double rest = detail::rest_length_of(
      spec.rest_length, (initial_point_position(spec.b) - initial_point_position(spec.a)).norm(),
      user);
  add_force_element(std::make_unique<detail::PointToPointForce>(
      user, a, b, rest, std::make_shared<detail::UserTension>(spec.tension)));
  return index;
}

int Model::add_spring_actor(const SpringActorSpec& spec) {
  const int index = force_element_count();
  const std::string user = element_name("spring actor", spec.name, index);
  require_two_ends(spec.a.body, spec.b.body, user);
  const auto& table = spec.characteristic;
  if (table.size() < 2) {
    throw Error(
        "the characteristic has " + std::to_string(table.size()) + " points, it needs at least 2",
        user, "give (elongation, tension) points, e.g. [[-0.01, 0], [0, 0], [0.01, 50]]");
  }
  for (std::size_t k = 0; k < table.size(); ++k) {
    if (!table[k].allFinite() || (k > 0 && !(table[k].x() > table[k - 1].x()))) {
      throw Error("characteristic point " + std::to_string(k) +
                      " is not finite or its elongation does not increase",
                  user, "list the points with strictly increasing elongations");
    }
  }
  if (!non_negative(spec.damping)) {
    throw Error("damping must be finite and non-negative", user, "check damping");
  }
  const detail::BodyPoint a = body_point(spec.a, user);
  const detail::BodyPoint b = body_point(spec.b, user);
  const double rest = detail::rest_length_of(
      spec.rest_length, (initial_point_position(spec.b) - initial_point_position(spec.a)).norm(),
      user);
  add_force_element(std::make_unique<detail::PointToPointForce>(
      user, a, b, rest, std::make_shared<detail::PiecewiseLinearTension>(table, spec.damping)));
  return index;
}

int Model::add_point_force(const PointForceSpec& spec) {
  const int index = force_element_count();
  const std::string user = element_name("point force", spec.name, index);
  detail::check_time_load(spec.point.body == kGround, static_cast<bool>(spec.force), false, user);
  add_force_element(
      std::make_unique<detail::PointForce>(user, body_point(spec.point, user), spec.force));
  return index;
}

int Model::add_torque(const TorqueSpec& spec) {
  const int index = force_element_count();
  const std::string user = element_name("torque", spec.name, index);
  detail::check_time_load(spec.body == kGround, static_cast<bool>(spec.torque), true, user);
  add_force_element(
      std::make_unique<detail::Torque>(user, angle_index(*this, spec.body, user), spec.torque));
  return index;
}

// --- readouts ---

namespace {

// Whether an element writes any entry into one row of its derivatives.
class RowWatch final : public MatrixSink {
 public:
  explicit RowWatch(int row) : row_(row) {}
  void add(int row, int, double) override { seen_ = seen_ || row == row_; }
  bool seen() const { return seen_; }

 private:
  int row_;
  bool seen_ = false;
};

}  // namespace

std::string Model::equation_of_motion_note(int index, double time, const Eigen::VectorXd& q,
                                           const Eigen::VectorXd& v) const {
  std::string names;
  for (int k = 0; k < force_element_count(); ++k) {
    if (!force_element(k).user_law()) continue;
    RowWatch by_position(index), by_velocity(index);
    force_element(k).add_jacobian_entries(time, q, v, by_position, by_velocity);
    if (by_position.seen() || by_velocity.seen())
      names += (names.empty() ? "" : ", ") + force_element(k).description();
  }
  if (names.empty()) return {};
  return "; a user's law acts on it (" + names +
         "): if a law jumps in its elongation (rotation) or rate, no step size gets Newton past "
         "the jump - make it continuous, a kink is fine (docs/user-guide.md, \"Write user laws "
         "continuous\")";
}

std::string Model::non_finite_source(double time, const Eigen::VectorXd& q,
                                     const Eigen::VectorXd& v) const {
  for (int i = 0; i < coordinate_count(); ++i) {
    if (!std::isfinite(q(i)) || !std::isfinite(v(i))) return coordinate_description(i);
  }
  // A force element's force, or its derivatives where it gives them (they enter the Newton
  // matrix).
  Eigen::VectorXd force;
  Eigen::MatrixXd by_position, by_velocity;
  for (int k = 0; k < force_element_count(); ++k) {
    force.setZero(coordinate_count());
    force_element(k).add_force(time, q, v, force);
    if (!force.allFinite()) {
      const std::string reason = force_element(k).non_finite_reason(time, q, v);
      return force_element(k).description() + (reason.empty() ? "" : ": " + reason);
    }
    by_position.setZero(coordinate_count(), coordinate_count());
    by_velocity.setZero(coordinate_count(), coordinate_count());
    if (force_element(k).add_jacobians(time, q, v, by_position, by_velocity) &&
        (!by_position.allFinite() || !by_velocity.allFinite())) {
      return force_element(k).description() + " (its derivatives)";
    }
  }
  const auto loads = point_loads();
  for (std::size_t k = 0; k < loads.size(); ++k) {
    if (!std::isfinite(loads[k])) return "point load on marker " + std::to_string(k / 2);
  }
  Eigen::VectorXd residual;
  constraint_residual(time, q, v, residual);
  Eigen::MatrixXd jacobian;
  constraint_jacobian(time, q, jacobian);
  for (int k = 0; k < constraint_count(); ++k) {
    if (!std::isfinite(residual(k)) || !jacobian.row(k).allFinite())
      return constraint_description(k);
  }
  return {};
}

}  // namespace fsi::mbd
