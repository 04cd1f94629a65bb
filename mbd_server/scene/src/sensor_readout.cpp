// The sensors a coupled run and an --mbd-only run share: everything the multibody state
// determines.

#include <Eigen/Geometry>

#include "fsi/common/error.hpp"
#include "fsi/mbd/readouts.hpp"
#include "fsi/scene/scene.hpp"

namespace fsi::scene {

namespace {

// A planar position or velocity sensor read in the axes of its frame body f: the point's
// d = p - r_f turned back, R(phi_f)^T d, its rate R^T (v - v_f - omega_f x d); an angle less the
// frame's, a rate less its rate.
double in_frame(const mbd::Model& model, const SensorSpec& sensor, const mbd::State& state) {
  const bool position = sensor.type == SensorType::Position;
  const mbd::BodyId f = *sensor.frame;
  using C = mbd::Coordinate;
  if (sensor.component == C::Angle) {
    const double own =
        sensor.point ? (position ? beam_tangent_angle(model, state, sensor.body, (*sensor.point)[0])
                                 : beam_tangent_rate(model, state, sensor.body, (*sensor.point)[0]))
                     : (position ? model.coordinate(state, sensor.body, C::Angle)
                                 : model.velocity(state, sensor.body, C::Angle));
    return own -
           (position ? model.coordinate(state, f, C::Angle) : model.velocity(state, f, C::Angle));
  }
  Eigen::Vector2d p, v;
  if (sensor.point) {
    const mbd::BodyPointSpec point{sensor.body, {(*sensor.point)[0], (*sensor.point)[1]}};
    p = point_position(model, state, point).head<2>();
    v = point_velocity(model, state, point).head<2>();
  } else {
    p = {model.coordinate(state, sensor.body, C::X), model.coordinate(state, sensor.body, C::Y)};
    v = {model.velocity(state, sensor.body, C::X), model.velocity(state, sensor.body, C::Y)};
  }
  const Eigen::Vector2d r_f(model.coordinate(state, f, C::X), model.coordinate(state, f, C::Y));
  const Eigen::Vector2d v_f(model.velocity(state, f, C::X), model.velocity(state, f, C::Y));
  const double omega = model.velocity(state, f, C::Angle);
  const Eigen::Rotation2Dd back(-model.coordinate(state, f, C::Angle));
  const Eigen::Vector2d d = p - r_f;
  const Eigen::Vector2d value =
      position ? Eigen::Vector2d(back * d)
               : Eigen::Vector2d(back * (v - v_f - omega * Eigen::Vector2d(-d.y(), d.x())));
  return value(sensor.component == C::X ? 0 : 1);
}

// A force sensor's torque about the body point `about` instead of the centre of mass G:
// tau_P = tau_G + (r_G - r_P) x F (planar: the z component).
mbd::Wrench about_point(const mbd::Model& model, const mbd::State& state, const SensorSpec& sensor,
                        mbd::Wrench wrench) {
  if (!sensor.about) return wrench;
  const auto& about = *sensor.about;
  Eigen::Vector3d centre, point;
  if (model.dimension() == 3) {
    centre =
        point_position(model, state, mbd::SpatialPointSpec{sensor.body, Eigen::Vector3d::Zero()});
    point = point_position(model, state,
                           mbd::SpatialPointSpec{sensor.body, {about[0], about[1], about[2]}});
  } else {
    centre = point_position(model, state, mbd::BodyPointSpec{sensor.body, {0.0, 0.0}});
    point = point_position(model, state, mbd::BodyPointSpec{sensor.body, {about[0], about[1]}});
  }
  wrench.torque += (centre - point).cross(wrench.force);
  return wrench;
}

// The planar constraint force on a rigid body as a wrench (x, y and the torque about G).
mbd::Wrench constraint_wrench(const mbd::Model& model, const mbd::State& state, mbd::BodyId body) {
  using C = mbd::Coordinate;
  mbd::Wrench wrench;
  wrench.force = {constraint_force(model, state, body, C::X),
                  constraint_force(model, state, body, C::Y), 0.0};
  wrench.torque.z() = constraint_force(model, state, body, C::Angle);
  return wrench;
}

}  // namespace

double structure_sensor_value(const mbd::Model& model, const SensorSpec& sensor,
                              const mbd::State& state) {
  const int component = static_cast<int>(sensor.component);
  if (model.dimension() == 3) {
    const mbd::SpatialPointSpec centre{
        sensor.body,
        sensor.point ? Eigen::Vector3d((*sensor.point)[0], (*sensor.point)[1], (*sensor.point)[2])
                     : Eigen::Vector3d::Zero()};
    switch (sensor.type) {
      case SensorType::Position:
        return point_position(model, state, centre)(sensor.axis);
      case SensorType::Velocity:
        return point_velocity(model, state, centre)(sensor.axis);
      case SensorType::FluidForce:
        return about_point(model, state, sensor, point_load_resultant(model, state, sensor.body))
            .stacked()(sensor.axis);
      case SensorType::JointForce:
        // The drive row's multiplier is its torque on body_a about the axis (RevoluteJoint3DSpec).
        if (sensor.axis == kDriveTorqueAxis)
          return state.lambda(sensor.first_row + sensor.rows - 1);
        return about_point(model, state, sensor,
                           joint_reaction(model, state, sensor.first_row, sensor.rows, sensor.body))
            .stacked()(sensor.axis);
      case SensorType::Power:
        return force_element_power(model, state, sensor.force_element);
      default:
        break;  // energies below; the builder refuses the rest in 3D
    }
  }
  if (sensor.frame &&
      (sensor.type == SensorType::Position || sensor.type == SensorType::Velocity)) {
    return in_frame(model, sensor, state);
  }
  if (sensor.point && sensor.component == mbd::Coordinate::Angle &&
      (sensor.type == SensorType::Position || sensor.type == SensorType::Velocity)) {
    // A beam's cross-section at s (the builder allows an angle with a point on beams only).
    return sensor.type == SensorType::Position
               ? beam_tangent_angle(model, state, sensor.body, (*sensor.point)[0])
               : beam_tangent_rate(model, state, sensor.body, (*sensor.point)[0]);
  }
  if (sensor.point &&
      (sensor.type == SensorType::Position || sensor.type == SensorType::Velocity)) {
    const mbd::BodyPointSpec point{sensor.body, {(*sensor.point)[0], (*sensor.point)[1]}};
    return (sensor.type == SensorType::Position ? point_position(model, state, point)
                                                : point_velocity(model, state, point))(sensor.axis);
  }
  switch (sensor.type) {
    case SensorType::Position:
      return model.coordinate(state, sensor.body, sensor.component);
    case SensorType::Velocity:
      return model.velocity(state, sensor.body, sensor.component);
    case SensorType::FluidForce:
      return about_point(model, state, sensor, point_load_resultant(model, state, sensor.body))
          .planar()(component);
    case SensorType::ConstraintForce:
      if (sensor.about) {
        return about_point(model, state, sensor, constraint_wrench(model, state, sensor.body))
            .planar()(component);
      }
      return constraint_force(model, state, sensor.body, sensor.component);
    case SensorType::JointForce:
      if (sensor.beam_point) {
        return beam_joint_reaction(model, state, sensor.first_row, sensor.rows, sensor.body,
                                   {(*sensor.beam_point)[0], (*sensor.beam_point)[1]})
            .planar()(component);
      }
      return about_point(model, state, sensor,
                         joint_reaction(model, state, sensor.first_row, sensor.rows, sensor.body))
          .planar()(component);
    case SensorType::SpringForce:
      return force_element_force(model, state, sensor.force_element);
    case SensorType::Power:
      return force_element_power(model, state, sensor.force_element);
    case SensorType::KineticEnergy:
      return kinetic_energy(model, state);
    case SensorType::PotentialEnergy:
      return potential_energy(model, state);
    case SensorType::StrainEnergy:
      return strain_energy(model, state);
    case SensorType::ChordDeflection: {
      const mbd::AncfBeamSpec& beam = model.beam(sensor.body);
      const double length = (beam.end - beam.start).norm();
      auto at = [&](double s, double eta) {
        return point_position(model, state, mbd::BodyPointSpec{sensor.body, {s, eta}});
      };
      const Eigen::Vector3d start = at(0.0, 0.0), end = at(length, 0.0);
      const Eigen::Vector3d p = at((*sensor.point)[0], (*sensor.point)[1]);
      const Eigen::Vector2d chord = (end - start).head<2>();
      const Eigen::Vector2d normal(-chord.y(), chord.x());
      return normal.dot((p - start).head<2>()) / chord.norm();
    }
    case SensorType::TotalFluidForce:
    case SensorType::Work:
      break;
  }
  FSI_ASSERT(false, "sensor '" + sensor.name +
                        "' needs the fluid forces of the coupled run or the run's history");
  return 0.0;
}

}  // namespace fsi::scene
