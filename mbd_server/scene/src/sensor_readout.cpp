// The sensors a coupled run and an --mbd-only run share: everything the multibody state
// determines.

#include "fsi/common/error.hpp"
#include "fsi/mbd/readouts.hpp"
#include "fsi/scene/scene.hpp"

namespace fsi::scene {

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
        return point_load_resultant(model, state, sensor.body).stacked()(sensor.axis);
      case SensorType::JointForce:
        // The drive row's multiplier is its torque on body_a about the axis (RevoluteJoint3DSpec).
        if (sensor.axis == kDriveTorqueAxis)
          return state.lambda(sensor.first_row + sensor.rows - 1);
        return joint_reaction(model, state, sensor.first_row, sensor.rows, sensor.body)
            .stacked()(sensor.axis);
      default:
        break;  // energies below; the builder refuses the rest in 3D
    }
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
      return point_load_resultant(model, state, sensor.body).planar()(component);
    case SensorType::ConstraintForce:
      return constraint_force(model, state, sensor.body, sensor.component);
    case SensorType::JointForce:
      if (sensor.beam_point) {
        return beam_joint_reaction(model, state, sensor.first_row, sensor.rows, sensor.body,
                                   {(*sensor.beam_point)[0], (*sensor.beam_point)[1]})
            .planar()(component);
      }
      return joint_reaction(model, state, sensor.first_row, sensor.rows, sensor.body)
          .planar()(component);
    case SensorType::SpringForce:
      return force_element_force(model, state, sensor.force_element);
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
      break;
  }
  FSI_ASSERT(false, "sensor '" + sensor.name + "' needs the fluid forces of the coupled run");
  return 0.0;
}

}  // namespace fsi::scene
