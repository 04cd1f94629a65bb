// Sensors: the columns of sensors.csv. A sensor reads a body (position, velocity, fluid and
// constraint forces), a named joint or spring, or the whole system (energies, total fluid
// force).

#include "fsi/common/error.hpp"
#include "scene_builder.hpp"

namespace fsi::scene::detail {
namespace {

// What a sensor type takes, declared once for planar and spatial scenes: each key required,
// forbidden or optional, whether it has a 3D form, its units (planar: per unit depth; the
// rotational unit is that of angle or torque components, empty when it has none).
enum class Use { Required, Forbidden, Optional };

struct SensorVariant {
  std::string_view type;
  SensorType kind;
  Use body, joint, element, component, point;
  bool spatial;
  std::string_view planar_unit, planar_rotational_unit;
  std::string_view spatial_unit, spatial_torque_unit;

  bool kinematic() const { return kind == SensorType::Position || kind == SensorType::Velocity; }
};

constexpr Use R = Use::Required, F = Use::Forbidden, O = Use::Optional;
//                 type, kind, body, joint, element, component, point, 3D, planar units, 3D units
constexpr SensorVariant kSensorVariants[] = {
    {"position", SensorType::Position, R, F, F, R, O, true, "m", "rad", "m", ""},
    {"velocity", SensorType::Velocity, R, F, F, R, O, true, "m/s", "rad/s", "m/s", ""},
    {"fluid_force", SensorType::FluidForce, R, F, F, R, F, true, "N/m", "N m/m", "N", "N m"},
    {"constraint_force", SensorType::ConstraintForce, R, F, F, R, F, false, "N/m", "N m/m", "", ""},
    {"total_fluid_force", SensorType::TotalFluidForce, F, F, F, R, F, true, "N/m", "", "N", ""},
    {"joint_force", SensorType::JointForce, F, R, F, R, F, true, "N/m", "N m/m", "N", "N m"},
    {"spring_force", SensorType::SpringForce, F, F, R, F, F, true, "N/m", "N m/m", "N", "N m"},
    {"power", SensorType::Power, F, F, R, F, F, true, "W/m", "", "W", ""},
    {"work", SensorType::Work, F, F, R, F, F, true, "J/m", "", "J", ""},
    {"kinetic_energy", SensorType::KineticEnergy, F, F, F, F, F, true, "J/m", "", "J", ""},
    {"potential_energy", SensorType::PotentialEnergy, F, F, F, F, F, true, "J/m", "", "J", ""},
    {"strain_energy", SensorType::StrainEnergy, F, F, F, F, F, true, "J/m", "", "J", ""},
    {"chord_deflection", SensorType::ChordDeflection, R, F, F, F, R, false, "m", "", "", ""},
};

std::vector<std::string> sensor_types() {
  std::vector<std::string> types;
  for (const SensorVariant& variant : kSensorVariants)
    types.emplace_back(variant.type);
  return types;
}

const SensorVariant& variant_of(const std::string& type) {
  for (const SensorVariant& variant : kSensorVariants) {
    if (variant.type == type) return variant;
  }
  FSI_ASSERT(false, "sensor type '" + type + "' passed the schema but has no variant");
  return kSensorVariants[0];
}

std::vector<BlockSpec> sensor_blocks() {
  return {
      block_spec(
          "Sensor", "A column of sensors.csv, written every Output.sensor_every_steps steps.",
          {text("name", "column name"),
           text("type",
                "what is measured (total_fluid_force: on every boundary, walls included; "
                "joint_force: what the joint exerts on its body_a (Clamp: body; the torque about "
                "its centre of mass, on an AncfBeam2D about the joint's point on it, a "
                "BeamClamp's node); spring_force: "
                "tension, or torque of a (Nonlinear)RotationalSpringDamper(3D) on body_a; power: "
                "the rate of "
                "work a "
                "named spring or damper does on the bodies, Q . v (a damper's is minus what it "
                "dissipates, -c omega^2: a power take-off absorbs minus its mean); work: the "
                "time integral of that power from t = 0, integrated by the integrator over each "
                "of its own steps (a damper's "
                "is minus the energy it has dissipated, a power take-off's minus what it has "
                "absorbed); "
                "energies of the whole system, "
                "potential = gravity + springs, strain = the beams' and cables' elastic "
                "deformation; chord_deflection: the distance of an AncfBeam2D's point from the "
                "chord through its end nodes, positive to the left of start -> end, the "
                "deflection of a flexible link whatever its rigid motion)")
               .one_of(sensor_types()),
           text("body",
                "name of a RigidBody2D (position, velocity, fluid and constraint forces), or of "
                "an AncfBeam2D (fluid_force; position and velocity of a beam point)")
               .optional(),
           per_dimension(vector("point", 2, "m",
                                "position, velocity: a point of the body instead of its centre of "
                                "mass (body coordinates; [s, eta] on an AncfBeam2D, where "
                                "component angle reads the cross-section's angle, the centre "
                                "line's tangent at s, in (-pi, pi] (a rigid body's angle runs "
                                "on: unwrap a spinning beam's column, numpy.unwrap); 3D: "
                                "[x, y, z], [s, 0, 0] on a cable)"))
               .optional(),
           per_dimension(vector("about", 2, "m",
                                "fluid_force, joint_force, constraint_force of a rigid body: "
                                "the torque about this point of the body (body coordinates; 3D: "
                                "[x, y, z]) instead of about its centre of mass, tau_P = tau_G + "
                                "(r_G - r_P) x F: a gate's or a flap's moment about its hinge; "
                                "the force components are unchanged"))
               .optional(),
           text("frame",
                "position, velocity (2D): the name of a RigidBody2D whose axes the components "
                "are read in, from its centre of mass (angle: relative to its angle; velocity: "
                "as seen turning with it); absent: the world's. A tip's displacement in a "
                "moving tank, say")
               .optional(),
           text("joint", "joint_force: the name of a joint block").optional(),
           text("element", "spring_force, power, work: the name of a spring or damper block")
               .optional(),
           text("component",
                "x, y, angle (torque for forces); 3D: x, y, z, and torque_x, torque_y, torque_z "
                "(about the centre of mass) for fluid_force and joint_force, and torque for the "
                "joint_force of a RevoluteJoint3D with a rate (the drive torque on body_a about "
                "the axis); not for spring_force and energies")
               .one_of({"x", "y", "z", "angle", "torque", "torque_x", "torque_y", "torque_z"})
               .optional()})
          .as_list()};
}

// Builds one Sensor block by its variant: one path for planar and spatial scenes, the
// dimension deciding only the components, units and what a body point is.
class SensorBuilder {
 public:
  SensorBuilder(SceneBuilder& builder_, const View& block_)
      : builder(builder_), s(block_), variant(variant_of(block_.string("type"))) {}

  void build();

 private:
  bool keys_fit();
  bool component_fits();
  bool body_fits();
  bool joint_fits();
  bool spring_fits();
  bool frame_fits();
  bool about_fits();
  std::string unit() const;
  void problem(const SourceLocation& where, const std::string& message, const std::string& fix) {
    builder.problem(where, message, fix);
    complete = false;
  }

  SceneBuilder& builder;
  const View& s;
  const SensorVariant& variant;
  SensorSpec sensor;
  std::string component;
  bool complete = true;
};

void SensorBuilder::build() {
  sensor.name = s.string("name");
  sensor.type = variant.kind;
  const std::string type(variant.type);
  component = s.has("component") ? s.string("component") : std::string();
  if (builder.spatial() && !variant.spatial) {
    return problem(s.location("type"), "a " + type + " sensor has no 3D form yet",
                   "use joint_force (the force a named joint exerts) or fluid_force");
  }
  if (!builder.spatial() && component == "z") {
    return problem(s.location("component"), "component z needs a 3D scene (dimension = 2 here)",
                   "write x or y, or set dimension = 3");
  }
  for (const SensorSpec& other : builder.scene.sensors) {
    if (other.name == sensor.name)
      problem(s.location("name"), "a second sensor is named '" + sensor.name + "'", "rename it");
  }
  // A planar sensor's component is judged even when a key is wrong (every mistake at once); a
  // spatial one's only with the keys right.
  const bool keys = keys_fit();
  if (!keys && builder.spatial()) return;
  if (!component_fits() || !keys) return;
  sensor.unit = unit();
  if (!body_fits() || !joint_fits() || !spring_fits() || !frame_fits() || !about_fits() ||
      !complete)
    return;
  builder.scene.sensors.push_back(sensor);
}

// The body point a force sensor's torque is taken about.
bool SensorBuilder::about_fits() {
  if (!s.has("about")) return true;
  const std::string type(variant.type);
  const bool force = variant.kind == SensorType::FluidForce ||
                     variant.kind == SensorType::JointForce ||
                     variant.kind == SensorType::ConstraintForce;
  if (!force) {
    problem(s.location("about"),
            "about is for the torque of fluid_force, joint_force and constraint_force sensors, "
            "not a " +
                type + " sensor",
            variant.kinematic() ? "remove about (a body point of a position or velocity: point)"
                                : "remove about");
    return false;
  }
  const mbd::Model& model = builder.model;
  const bool rigid = sensor.body != mbd::kGround && !model.is_beam(sensor.body) &&
                     !(builder.spatial() && model.is_cable(sensor.body));
  if (!rigid) {
    problem(s.location("about"),
            "about needs a rigid body; sensor '" + sensor.name + "' reads " +
                (sensor.body == mbd::kGround ? std::string("the ground")
                                             : "the " + model.body_kind(sensor.body) + " '" +
                                                   model.body_name(sensor.body) + "'"),
            "remove about (a joint on a beam is read about the joint's point already)");
    return false;
  }
  const bool torque = builder.spatial() ? (sensor.axis >= 3 && sensor.axis <= 5)
                                        : sensor.component == mbd::Coordinate::Angle;
  if (!torque) {
    problem(s.location("about"),
            "about changes only the torque, and sensor '" + sensor.name + "' reads component " +
                component,
            builder.spatial() ? "write component = \"torque_x\" (or _y, _z), or remove about"
                              : "write component = \"torque\", or remove about");
    return false;
  }
  const auto point = builder.dimension_vector(s, "about", builder.dimension);
  if (!point) return false;
  try {
    const std::string user = "sensor '" + sensor.name + "'";
    if (builder.spatial()) {
      model.check_spatial_point({sensor.body, {(*point)[0], (*point)[1], (*point)[2]}}, user);
    } else {
      model.check_point({sensor.body, {(*point)[0], (*point)[1]}}, user);
    }
  } catch (const Error& error) {
    problem(s.location("about"), error.fault(), error.remedy());
    return false;
  }
  sensor.about =
      std::array<double, 3>{(*point)[0], (*point)[1], builder.spatial() ? (*point)[2] : 0.0};
  return true;
}

// The rigid body a planar position or velocity is read in the axes of.
bool SensorBuilder::frame_fits() {
  if (!s.has("frame")) return true;
  const std::string type(variant.type);
  if (!variant.kinematic() || builder.spatial()) {
    problem(s.location("frame"),
            "frame is for position and velocity sensors of 2D scenes, not a " +
                std::string(builder.spatial() ? "3D " : "") + type + " sensor",
            "remove frame");
    return false;
  }
  const mbd::BodyId frame = builder.find_body(s, "frame");
  if (builder.model.is_beam(frame)) {
    problem(s.location("frame"),
            "frame '" + s.string("frame") + "' is an AncfBeam2D; a frame is a RigidBody2D",
            "name a RigidBody2D (a beam's own bending: type = \"chord_deflection\")");
    return false;
  }
  if (frame == sensor.body && !sensor.point) {
    problem(s.location("frame"), "a body's centre of mass in its own frame does not move",
            "name another body, or give a point");
    return false;
  }
  sensor.frame = frame;
  return true;
}

// Every key the variant forbids is absent, every key it requires present.
bool SensorBuilder::keys_fit() {
  const std::string type(variant.type);
  auto forbid = [&](const char* key, Use use, const std::string& fix) {
    if (use == Use::Forbidden && s.has(key))
      problem(s.location(key), "a " + type + " sensor takes no " + key, fix);
  };
  auto need = [&](const char* key, Use use, const std::string& example) {
    if (use == Use::Required && !s.has(key)) {
      problem(s.location("name"), "sensor '" + sensor.name + "' needs " + key,
              std::string("add ") + key + " = " + example);
    }
  };
  const bool total = variant.kind == SensorType::TotalFluidForce;
  const bool planar = !builder.spatial();
  forbid("body", variant.body,
         total && planar ? "remove body, or use type = \"fluid_force\"" : "remove it");
  forbid("joint", variant.joint, "remove it");
  forbid("element", variant.element, "remove it");
  forbid("component", variant.component, "remove it");
  forbid("point", variant.point,
         planar ? "remove it (point is for position and velocity sensors)" : "remove it");
  if (planar && component.rfind("torque_", 0) == 0) {
    problem(s.location("component"), "torque_x, torque_y and torque_z are components of 3D sensors",
            "write torque");
  }
  need("component", variant.component, "\"x\"");
  need("body", variant.body, "\"...\"");
  need("joint", variant.joint, "\"...\" (a joint's name)");
  need("element", variant.element,
       planar ? "\"...\" (a spring's name)" : "\"...\" (a spatial spring's name)");
  return complete;
}

// The component among the variant's: planar x, y and angle (torque for forces); spatial x, y, z
// and torque_x, torque_y, torque_z where the variant has a torque unit.
bool SensorBuilder::component_fits() {
  if (component.empty() || variant.component == Use::Forbidden) return true;
  const std::string type(variant.type);
  const bool spatial_torque = component.rfind("torque_", 0) == 0;
  const bool force = !variant.kinematic();
  if (builder.spatial()) {
    const bool takes_torque = !variant.spatial_torque_unit.empty();
    if (component == "torque" && variant.kind == SensorType::JointForce) {
      sensor.axis = kDriveTorqueAxis;  // joint_fits checks the joint has a drive
      return true;
    }
    if ((component != "x" && component != "y" && component != "z" && !spatial_torque) ||
        (spatial_torque && !takes_torque)) {
      problem(s.location("component"),
              "a 3D " + type + " sensor has components x, y or z" +
                  (takes_torque ? " (or torque_x, torque_y, torque_z)" : "") +
                  (variant.kind == SensorType::JointForce
                       ? " (and torque: a driven RevoluteJoint3D's drive torque)"
                       : ""),
              "write x, y or z (angles of 3D bodies are not sensors yet)");
      return false;
    }
  } else {
    // Reported, and the sensor still read further: its other mistakes come in the same run.
    if (force && component == "angle") {
      builder.problem(s.location("component"), "a force sensor has components x, y or torque",
                      "write torque");
    }
    if (!force && component == "torque") {
      builder.problem(s.location("component"), "a " + type + " sensor has components x, y or angle",
                      "write angle");
    }
    if (force && component == "torque" && variant.planar_rotational_unit.empty()) {
      builder.problem(s.location("component"), "total_fluid_force has components x and y",
                      "write x or y");
    }
    sensor.component = coordinate_of(component);
  }
  const char last = component.back();
  sensor.axis = (last == 'z' ? 2 : last == 'y' ? 1 : 0) + (spatial_torque ? 3 : 0);
  return true;
}

std::string SensorBuilder::unit() const {
  if (builder.spatial()) {
    return std::string(component.rfind("torque", 0) == 0 ? variant.spatial_torque_unit
                                                         : variant.spatial_unit);
  }
  const bool rotational = !component.empty() && sensor.component == mbd::Coordinate::Angle;
  return std::string(rotational ? variant.planar_rotational_unit : variant.planar_unit);
}

// The body a position, velocity or force sensor reads, and its point if one is given.
bool SensorBuilder::body_fits() {
  if (variant.body != Use::Required) return true;
  const std::string type(variant.type);
  mbd::Model& model = builder.model;
  sensor.body = builder.find_body(s, "body");
  if (variant.kind == SensorType::ChordDeflection) {
    if (!model.is_beam(sensor.body)) {
      problem(s.location("body"),
              "a chord_deflection sensor reads an AncfBeam2D, and '" + s.string("body") +
                  "' is a " + model.body_kind(sensor.body),
              "name a beam, or read a rigid body's position");
      return false;
    }
    const auto point = s.vector("point");
    try {
      model.check_point({sensor.body, {point[0], point[1]}}, "sensor '" + sensor.name + "'");
    } catch (const Error& error) {
      problem(s.location("point"), error.fault(), error.remedy());
      return false;
    }
    sensor.point = std::array<double, 3>{point[0], point[1], 0.0};
    return true;
  }
  const bool rotational = !builder.spatial() && sensor.component == mbd::Coordinate::Angle;
  if (variant.kinematic() && s.has("point")) {
    // On a beam a point's angle is its cross-section's: the tangent of the centre line at s.
    if (rotational && !model.is_beam(sensor.body)) {
      problem(s.location("component"),
              "a point of a rigid body has components x and y, no angle of its own",
              "write x or y, or remove point for the body's angle");
      return false;
    }
    const auto point = builder.dimension_vector(s, "point", builder.dimension);
    if (!point) return false;
    sensor.point =
        std::array<double, 3>{(*point)[0], (*point)[1], builder.spatial() ? (*point)[2] : 0.0};
    const std::string user = "sensor '" + sensor.name + "'";
    try {
      if (builder.spatial()) {
        model.check_spatial_point({sensor.body, {(*point)[0], (*point)[1], (*point)[2]}}, user);
      } else {
        model.check_point({sensor.body, {(*point)[0], (*point)[1]}}, user);
      }
    } catch (const Error& error) {
      problem(s.location("point"), error.fault(), error.remedy());
      return false;
    }
  }
  if (builder.spatial() && variant.kinematic() && !sensor.point && model.is_cable(sensor.body)) {
    problem(s.location("body"),
            "a " + type + " sensor reads a centre of mass, and '" + s.string("body") +
                "' is an AncfCable3D",
            "give a centre-line point = [s, 0, 0], or use type = \"fluid_force\"");
    return false;
  }
  if (!builder.spatial() && model.is_beam(sensor.body) && sensor.type != SensorType::FluidForce &&
      !sensor.point) {
    problem(s.location("type"),
            "a " + type + " sensor reads rigid-body coordinates, and '" + s.string("body") +
                "' is an AncfBeam2D",
            "give a beam point = [s, eta] (component x, y, or angle: the cross-section's), or "
            "use type = \"fluid_force\"");
    return false;
  }
  return true;
}

// The rows of the named joint and the body its reaction is read on.
bool SensorBuilder::joint_fits() {
  if (variant.joint != Use::Required) return true;
  const std::string& name = s.string("joint");
  const auto found = builder.names.joints.find(name);
  if (found == builder.names.joints.end() && builder.element_skipped(name))
    throw AlreadyReported(s.location("joint"));  // its own problem is reported
  if (found == builder.names.joints.end()) {
    problem(s.location("joint"), "no joint named '" + name + "'",
            "give the joint block name = \"" + name + "\"");
    return false;
  }
  const NamedJoint& joint = found->second;
  sensor.body = joint.body;
  const mbd::Model& model = builder.model;
  if (builder.spatial() && (sensor.body == mbd::kGround || model.is_cable(sensor.body))) {
    problem(s.location("joint"),
            "joint '" + name + "' has no rigid body or point mass as its first body",
            "give the joint a RigidBody3D or PointMass as body_a (body of a FixedJoint3D)");
    return false;
  }
  if (!builder.spatial() && sensor.body != mbd::kGround && model.is_beam(sensor.body) &&
      !joint.beam_point) {
    problem(s.location("joint"),
            "joint '" + name +
                "' holds an AncfBeam2D as its first body; joint_force reads a rigid body's force "
                "and torque",
            "give the joint a rigid body as body_a, measure a BeamClamp, RevoluteJoint or "
            "DistanceConstraint on the beam (force on it, moment about the joint's point), or "
            "measure the beam with a fluid_force sensor");
    return false;
  }
  if (sensor.axis == kDriveTorqueAxis && !joint.drive) {
    problem(s.location("component"),
            "component torque of a 3D joint_force sensor is the drive torque of a "
            "RevoluteJoint3D with a rate, and joint '" +
                name + "' has no drive",
            "give the joint a rate, or read torque_x, torque_y or torque_z");
    return false;
  }
  sensor.first_row = joint.first_row;
  sensor.rows = joint.rows;
  sensor.beam_point = joint.beam_point;
  return true;
}

// The named spring; a rotational one measures a torque.
bool SensorBuilder::spring_fits() {
  if (variant.element != Use::Required) return true;
  const std::string& name = s.string("element");
  const auto found = builder.names.force_elements.find(name);
  if (found == builder.names.force_elements.end() && builder.element_skipped(name))
    throw AlreadyReported(s.location("element"));  // its own problem is reported
  if (found == builder.names.force_elements.end() || found->second < 0) {
    problem(s.location("element"), "no spring named '" + name + "'",
            "give the " +
                std::string(builder.spatial() ? "SpringDamper3D, NonlinearSpringDamper3D or "
                                                "(Nonlinear)RotationalSpringDamper3D block"
                                              : "spring block") +
                " name = \"" + name + "\"");
    return false;
  }
  sensor.force_element = found->second;
  if (variant.kind == SensorType::SpringForce && builder.names.rotational[name])
    sensor.unit = std::string(builder.spatial() ? variant.spatial_torque_unit
                                                : variant.planar_rotational_unit);
  return true;
}

void build_sensors(SceneBuilder& builder) {
  builder.each("Sensor", [&](const View& s) { SensorBuilder(builder, s).build(); });
}

}  // namespace

ElementFamily sensors_family() {
  return {"sensors", sensor_blocks, {build_sensors}};
}

}  // namespace fsi::scene::detail
