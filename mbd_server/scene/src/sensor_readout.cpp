// The sensors a coupled run and an --mbd-only run share: everything the multibody state
// determines.

#include "fsi/common/error.hpp"
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
        return model.spatial_point_position(state, centre)(sensor.axis);
      case SensorType::Velocity:
        return model.spatial_point_velocity(state, centre)(sensor.axis);
      case SensorType::FluidForce:
        return model.spatial_point_load_resultant(state, sensor.body)(sensor.axis);
      case SensorType::JointForce:
        return model.spatial_joint_reaction(state, sensor.first_row, sensor.rows,
                                            sensor.body)(sensor.axis);
      default:
        break;  // energies below; the builder refuses the rest in 3D
    }
  }
  if (sensor.point &&
      (sensor.type == SensorType::Position || sensor.type == SensorType::Velocity)) {
    const mbd::BodyPointSpec point{sensor.body, {(*sensor.point)[0], (*sensor.point)[1]}};
    return (sensor.type == SensorType::Position ? model.point_position(state, point)
                                                : model.point_velocity(state, point))(sensor.axis);
  }
  switch (sensor.type) {
    case SensorType::Position:
      return model.coordinate(state, sensor.body, sensor.component);
    case SensorType::Velocity:
      return model.velocity(state, sensor.body, sensor.component);
    case SensorType::FluidForce:
      return model.point_load_resultant(state, sensor.body)(component);
    case SensorType::ConstraintForce:
      return model.constraint_force(state, sensor.body, sensor.component);
    case SensorType::JointForce:
      return model.joint_reaction(state, sensor.first_row, sensor.rows, sensor.body)(component);
    case SensorType::SpringForce:
      return model.force_element_force(state, sensor.force_element);
    case SensorType::KineticEnergy:
      return model.kinetic_energy(state);
    case SensorType::PotentialEnergy:
      return model.potential_energy(state);
    case SensorType::TotalFluidForce:
      break;
  }
  FSI_ASSERT(false, "sensor '" + sensor.name + "' needs the fluid forces of the coupled run");
  return 0.0;
}

}  // namespace fsi::scene
