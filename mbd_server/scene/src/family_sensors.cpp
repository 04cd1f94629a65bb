// Sensors: the columns of sensors.csv. A sensor reads a body (position, velocity, fluid and
// constraint forces), a named joint or spring, or the whole system (energies, total fluid
// force).

#include "fsi/common/error.hpp"
#include "scene_builder.hpp"

namespace fsi::scene::detail {
namespace {

// The old declaration helpers, kept for the Sensor block's declaration below.
ParameterSpec optional(ParameterSpec p) {
  return p.optional();
}
ParameterSpec choice(ParameterSpec p, std::vector<std::string> choices) {
  return p.one_of(std::move(choices));
}
BlockSpec repeated(BlockSpec b) {
  return b.as_list();
}
BlockSpec block(std::string name, std::string doc, std::vector<ParameterSpec> parameters) {
  return block_spec(std::move(name), std::move(doc), std::move(parameters));
}

std::vector<BlockSpec> sensor_blocks() {
  return {repeated(block(
      "Sensor", "A column of sensors.csv, written every Output.sensor_every_steps steps.",
      {text("name", "column name"),
       choice(text("type",
                   "what is measured (total_fluid_force: on every boundary, walls included; "
                   "joint_force: what the joint exerts on its body_a (Clamp: body); spring_force: "
                   "tension, or torque of a RotationalSpringDamper; energies of the whole system, "
                   "potential = gravity + springs)"),
              {"position", "velocity", "fluid_force", "constraint_force", "total_fluid_force",
               "joint_force", "spring_force", "kinetic_energy", "potential_energy"}),
       optional(text("body",
                     "name of a RigidBody2D (position, velocity, fluid and constraint "
                     "forces), or of an AncfBeam2D (fluid_force)")),
       optional(per_dimension(
           vector("point", 2, "m",
                  "position, velocity: a point of the body instead of its centre of mass (body "
                  "coordinates; [s, eta] on an AncfBeam2D; 3D: [x, y, z], [s, 0, 0] on a cable)"))),
       optional(text("joint", "joint_force: the name of a joint block")),
       optional(text("element", "spring_force: the name of a spring block")),
       optional(choice(text("component",
                            "x, y, angle (torque for forces); 3D: x, y, z, and torque_x, "
                            "torque_y, torque_z (about the centre of mass) for fluid_force and "
                            "joint_force; not for spring_force and energies"),
                       {"x", "y", "z", "angle", "torque", "torque_x", "torque_y", "torque_z"}))}))};
}

class SensorBuilder {
 public:
  explicit SensorBuilder(SceneBuilder& builder_) : builder(builder_) {}

  void build(const View& s);

 private:
  void build_spatial(const View& s, const std::string& type, const std::string& component,
                     SensorSpec& sensor);
  void build_planar(const View& s, const std::string& type, const std::string& component,
                    SensorSpec& sensor);
  // The joint or spring a sensor names; a problem at its key (and nullptr) when there is none.
  const NamedJoint* named_joint(const View& s);
  std::optional<int> named_spring(const View& s, const std::string& block);
  void problem(const Problem& found) { builder.problem(found.location, found.message, found.fix); }

  SceneBuilder& builder;
};

const NamedJoint* SensorBuilder::named_joint(const View& s) {
  const auto found = builder.names.joints.find(s.string("joint"));
  if (found != builder.names.joints.end()) return &found->second;
  problem({s.location("joint"), "no joint named '" + s.string("joint") + "'",
           "give the joint block name = \"" + s.string("joint") + "\""});
  return nullptr;
}

std::optional<int> SensorBuilder::named_spring(const View& s, const std::string& block) {
  const auto found = builder.names.force_elements.find(s.string("element"));
  if (found != builder.names.force_elements.end() && found->second >= 0) return found->second;
  problem({s.location("element"), "no spring named '" + s.string("element") + "'",
           "give the " + block + " name = \"" + s.string("element") + "\""});
  return std::nullopt;
}

void SensorBuilder::build(const View& s) {
  SensorSpec sensor;
  sensor.name = s.string("name");
  const std::string type = s.string("type");
  const std::string component = s.has("component") ? s.string("component") : std::string();
  sensor.type = type == "position"           ? SensorType::Position
                : type == "velocity"         ? SensorType::Velocity
                : type == "fluid_force"      ? SensorType::FluidForce
                : type == "constraint_force" ? SensorType::ConstraintForce
                : type == "joint_force"      ? SensorType::JointForce
                : type == "spring_force"     ? SensorType::SpringForce
                : type == "kinetic_energy"   ? SensorType::KineticEnergy
                : type == "potential_energy" ? SensorType::PotentialEnergy
                                             : SensorType::TotalFluidForce;
  if (builder.spatial()) {
    build_spatial(s, type, component, sensor);
  } else {
    build_planar(s, type, component, sensor);
  }
}

// A sensor of a 3D scene: components x, y, z of the centre of mass (position, velocity of a
// RigidBody3D or PointMass) or of a force (fluid_force on any spatial body, joint_force on
// its body_a, total_fluid_force), or an energy.
void SensorBuilder::build_spatial(const View& s, const std::string& type,
                                  const std::string& component, SensorSpec& sensor) {
  if (sensor.type == SensorType::ConstraintForce) {
    problem({s.location("type"), "a " + type + " sensor has no 3D form yet",
             "use joint_force (the force a named joint exerts) or fluid_force"});
    return;
  }
  const bool spring = sensor.type == SensorType::SpringForce;
  const bool energy =
      sensor.type == SensorType::KineticEnergy || sensor.type == SensorType::PotentialEnergy;
  const bool on_body = sensor.type == SensorType::Position || sensor.type == SensorType::Velocity ||
                       sensor.type == SensorType::FluidForce;
  bool complete = true;
  auto check_key = [&](const char* key, bool wanted, const std::string& example) {
    if (wanted && !s.has(key)) {
      problem({s.location("name"), "sensor '" + sensor.name + "' needs " + key,
               std::string("add ") + key + " = " + example});
      complete = false;
    } else if (!wanted && s.has(key)) {
      problem({s.location(key), "a " + type + " sensor takes no " + key, "remove it"});
      complete = false;
    }
  };
  check_key("body", on_body, "\"...\"");
  check_key("joint", sensor.type == SensorType::JointForce, "\"...\" (a joint's name)");
  check_key("element", spring, "\"...\" (a SpringDamper3D's name)");
  check_key("component", !energy && !spring, "\"x\"");
  const bool kinematic = sensor.type == SensorType::Position || sensor.type == SensorType::Velocity;
  if (!kinematic && s.has("point")) check_key("point", false, "");
  if (!complete) return;
  const bool torque = component.rfind("torque_", 0) == 0;
  if (!energy && !spring) {
    const bool takes_torque =
        sensor.type == SensorType::FluidForce || sensor.type == SensorType::JointForce;
    if ((component != "x" && component != "y" && component != "z" && !torque) ||
        (torque && !takes_torque)) {
      problem({s.location("component"),
               "a 3D " + type + " sensor has components x, y or z" +
                   (takes_torque ? " (or torque_x, torque_y, torque_z)" : ""),
               "write x, y or z (angles of 3D bodies are not sensors yet)"});
      return;
    }
    const char last = component.back();
    sensor.axis = (last == 'z' ? 2 : last == 'y' ? 1 : 0) + (torque ? 3 : 0);
  }
  sensor.unit = sensor.type == SensorType::Position   ? "m"
                : sensor.type == SensorType::Velocity ? "m/s"
                : energy                              ? "J"
                : torque                              ? "N m"
                                                      : "N";
  if (on_body) sensor.body = builder.find_body(s, "body");
  if (kinematic && s.has("point")) {
    const auto point = builder.dimension_vector(s, "point", 3);
    if (!point) return;
    sensor.point = std::array<double, 3>{(*point)[0], (*point)[1], (*point)[2]};
    try {
      builder.model.check_spatial_point({sensor.body, {(*point)[0], (*point)[1], (*point)[2]}},
                                        "sensor '" + sensor.name + "'");
    } catch (const Error& error) {
      problem({s.location("point"), error.fault(), error.remedy()});
      return;
    }
  }
  if (kinematic && !sensor.point && builder.model.is_cable(sensor.body)) {
    problem({s.location("body"),
             "a " + type + " sensor reads a centre of mass, and '" + s.string("body") +
                 "' is an AncfCable3D",
             "give a centre-line point = [s, 0, 0], or use type = \"fluid_force\""});
    return;
  }
  if (spring) {
    const std::optional<int> element = named_spring(s, "SpringDamper3D block");
    if (!element) return;
    sensor.force_element = *element;
  }
  if (sensor.type == SensorType::JointForce) {
    const NamedJoint* joint = named_joint(s);
    if (joint == nullptr) return;
    sensor.body = joint->body;
    if (sensor.body == mbd::kGround || builder.model.is_cable(sensor.body)) {
      problem(
          {s.location("joint"),
           "joint '" + s.string("joint") + "' has no rigid body or point mass as its first body",
           "give the joint a RigidBody3D or PointMass as body_a (body of a "
           "FixedJoint3D)"});
      return;
    }
    sensor.first_row = joint->first_row;
    sensor.rows = joint->rows;
  }
  for (const auto& other : builder.scene.sensors) {
    if (other.name == sensor.name) {
      problem({s.location("name"), "a second sensor is named '" + sensor.name + "'", "rename it"});
      return;
    }
  }
  builder.scene.sensors.push_back(sensor);
}

void SensorBuilder::build_planar(const View& s, const std::string& type,
                                 const std::string& component, SensorSpec& sensor) {
  if (component == "z") {
    problem({s.location("component"), "component z needs a 3D scene (dimension = 2 here)",
             "write x or y, or set dimension = 3"});
    return;
  }
  sensor.axis = component == "z" ? 2 : component == "y" ? 1 : 0;
  for (const auto& other : builder.scene.sensors) {
    if (other.name == sensor.name) {
      problem({s.location("name"), "a second sensor is named '" + sensor.name + "'", "rename it"});
    }
  }
  // Which of body, joint, element and component the type takes.
  const bool on_body = sensor.type == SensorType::Position || sensor.type == SensorType::Velocity ||
                       sensor.type == SensorType::FluidForce ||
                       sensor.type == SensorType::ConstraintForce;
  const bool energy =
      sensor.type == SensorType::KineticEnergy || sensor.type == SensorType::PotentialEnergy;
  const bool has_component = !energy && sensor.type != SensorType::SpringForce;
  const bool force = sensor.type != SensorType::Position && sensor.type != SensorType::Velocity;
  bool complete = true;
  auto forbid = [&](const char* key, const std::string& fix) {
    if (!s.has(key)) return;
    problem({s.location(key), "a " + type + " sensor takes no " + key, fix});
    complete = false;
  };
  auto need = [&](const char* key, const std::string& example) {
    if (s.has(key)) return;
    problem({s.location("name"), "sensor '" + sensor.name + "' needs " + key,
             std::string("add ") + key + " = " + example});
    complete = false;
  };
  if (!on_body)
    forbid("body", sensor.type == SensorType::TotalFluidForce
                       ? "remove body, or use type = \"fluid_force\""
                       : "remove it");
  if (sensor.type != SensorType::JointForce) forbid("joint", "remove it");
  if (sensor.type != SensorType::SpringForce) forbid("element", "remove it");
  if (!has_component) forbid("component", "remove it");
  const bool kinematic = sensor.type == SensorType::Position || sensor.type == SensorType::Velocity;
  if (!kinematic) forbid("point", "remove it (point is for position and velocity sensors)");
  if (component.rfind("torque_", 0) == 0) {
    problem({s.location("component"),
             "torque_x, torque_y and torque_z are components of 3D sensors", "write torque"});
    complete = false;
  }
  if (has_component) need("component", "\"x\"");
  if (on_body) need("body", "\"...\"");
  if (sensor.type == SensorType::JointForce) need("joint", "\"...\" (a joint's name)");
  if (sensor.type == SensorType::SpringForce) need("element", "\"...\" (a spring's name)");
  if (has_component && !component.empty()) {
    if (force && component == "angle") {
      problem({s.location("component"), "a force sensor has components x, y or torque",
               "write torque"});
    }
    if (!force && component == "torque") {
      problem({s.location("component"), "a " + type + " sensor has components x, y or angle",
               "write angle"});
    }
    if (sensor.type == SensorType::TotalFluidForce && component == "torque") {
      problem(
          {s.location("component"), "total_fluid_force has components x and y", "write x or y"});
    }
    sensor.component = coordinate_of(component);
  }
  if (!complete) return;
  const bool rotational = sensor.component == mbd::Coordinate::Angle;
  sensor.unit = sensor.type == SensorType::Position   ? (rotational ? "rad" : "m")
                : sensor.type == SensorType::Velocity ? (rotational ? "rad/s" : "m/s")
                : energy                              ? "J/m"
                                                      : (rotational ? "N m/m" : "N/m");
  if (on_body) sensor.body = builder.find_body(s, "body");
  if (kinematic && s.has("point")) {
    if (rotational) {
      problem({s.location("component"), "a point has components x and y, no angle",
               "write x or y, or remove point for the body's angle"});
      return;
    }
    const auto point = builder.dimension_vector(s, "point", 2);
    if (!point) return;
    sensor.point = std::array<double, 3>{(*point)[0], (*point)[1], 0.0};
    try {
      builder.model.check_point({sensor.body, {(*point)[0], (*point)[1]}},
                                "sensor '" + sensor.name + "'");
    } catch (const Error& error) {
      problem({s.location("point"), error.fault(), error.remedy()});
      return;
    }
    sensor.axis = sensor.component == mbd::Coordinate::Y ? 1 : 0;
  }
  if (on_body && builder.model.is_beam(sensor.body) && sensor.type != SensorType::FluidForce &&
      !sensor.point) {
    problem({s.location("type"),
             "a " + type + " sensor reads rigid-body coordinates, and '" + s.string("body") +
                 "' is an AncfBeam2D",
             "give a beam point = [s, eta], or use type = \"fluid_force\""});
    return;
  }
  if (sensor.type == SensorType::JointForce) {
    const NamedJoint* joint = named_joint(s);
    if (joint == nullptr) return;
    sensor.body = joint->body;
    if (sensor.body != mbd::kGround && builder.model.is_beam(sensor.body)) {
      problem({s.location("joint"),
               "joint '" + s.string("joint") +
                   "' holds an AncfBeam2D as its first body; joint_force reads a "
                   "rigid body's force and torque",
               "give the joint a rigid body as body_a, or measure the beam with "
               "a fluid_force sensor"});
      return;
    }
    sensor.first_row = joint->first_row;
    sensor.rows = joint->rows;
  }
  if (sensor.type == SensorType::SpringForce) {
    const std::optional<int> element = named_spring(s, "spring block");
    if (!element) return;
    sensor.force_element = *element;
    if (builder.names.rotational[s.string("element")]) sensor.unit = "N m/m";
  }
  builder.scene.sensors.push_back(sensor);
}

void build_sensors(SceneBuilder& builder) {
  SensorBuilder sensors(builder);
  for (const View& s : builder.blocks("Sensor"))
    builder.guard(s.location(), [&] { sensors.build(s); });
}

}  // namespace

ElementFamily sensors_family() {
  return {"sensors", sensor_blocks, build_sensors};
}

}  // namespace fsi::scene::detail
