#include "fsi/mbd/model.hpp"

#include <cmath>

#include "fsi/common/error.hpp"

namespace fsi::mbd {
namespace {

struct Marker {
  BodyId body;
  Eigen::Vector2d local;  // body frame, or world frame for kGround
};

// dr/dphi for a body-fixed point p at angle phi: R'(phi) p.
Eigen::Vector2d rotated_derivative(double phi, const Eigen::Vector2d& p) {
  const double c = std::cos(phi);
  const double s = std::sin(phi);
  return {-s * p.x() - c * p.y(), c * p.x() - s * p.y()};
}

Eigen::Vector2d rotated(double phi, const Eigen::Vector2d& p) {
  const double c = std::cos(phi);
  const double s = std::sin(phi);
  return {c * p.x() - s * p.y(), s * p.x() + c * p.y()};
}

}  // namespace

std::string_view name(Coordinate coordinate) {
  switch (coordinate) {
    case Coordinate::X:
      return "x";
    case Coordinate::Y:
      return "y";
    case Coordinate::Angle:
      return "angle";
  }
  return "?";
}

struct Model::Data {
  std::vector<RigidBody2DSpec> bodies;
  std::vector<Marker> markers;
  std::vector<ConstraintInfo> constraints;
  std::vector<std::unique_ptr<ForceElement>> force_elements;
  Eigen::Vector2d gravity = Eigen::Vector2d::Zero();
  std::vector<double> point_loads;
  // Derived when the structure changes.
  mutable bool dirty = true;
  mutable Eigen::MatrixXd mass;
  mutable Eigen::MatrixXd jacobian;

  void refresh() const {
    if (!dirty) return;
    const int n = static_cast<int>(bodies.size()) * 3;
    mass = Eigen::MatrixXd::Zero(n, n);
    for (std::size_t b = 0; b < bodies.size(); ++b) {
      const int i = static_cast<int>(b) * 3;
      mass(i, i) = bodies[b].mass;
      mass(i + 1, i + 1) = bodies[b].mass;
      mass(i + 2, i + 2) = bodies[b].inertia;
    }
    jacobian = Eigen::MatrixXd::Zero(static_cast<int>(constraints.size()), n);
    for (std::size_t k = 0; k < constraints.size(); ++k) {
      jacobian(static_cast<int>(k), constraints[k].coordinate) = 1.0;
    }
    dirty = false;
  }

  void check_body(BodyId body, const char* what) const {
    if (body < 0 || body >= static_cast<BodyId>(bodies.size())) {
      throw Error(std::string(what) + " refers to body index " + std::to_string(body) +
                      ", the model has " + std::to_string(bodies.size()) + " bodies",
                  "model", "refer to a body that exists");
    }
  }
};

Model::Model() : data_(std::make_unique<Data>()) {}
Model::~Model() = default;
Model::Model(Model&&) noexcept = default;
Model& Model::operator=(Model&&) noexcept = default;

BodyId Model::add_rigid_body(const RigidBody2DSpec& spec) {
  const std::string where = "rigid body '" + spec.name + "'";
  auto finite = [](double x) { return std::isfinite(x); };
  if (!(finite(spec.mass) && spec.mass > 0.0)) {
    throw Error("mass must be positive and finite, got " + std::to_string(spec.mass), where,
                "give the body a positive mass (2D: per unit depth)");
  }
  if (!(finite(spec.inertia) && spec.inertia > 0.0)) {
    throw Error("inertia must be positive and finite, got " + std::to_string(spec.inertia), where,
                "give the moment of inertia about the centre of mass");
  }
  if (!spec.position.allFinite() || !spec.velocity.allFinite() || !finite(spec.angle) ||
      !finite(spec.angular_velocity)) {
    throw Error("initial position, angle or velocity is not finite", where, "check the values");
  }
  for (const auto& other : data_->bodies) {
    if (other.name == spec.name) {
      throw Error("a second body is named '" + spec.name + "'", where,
                  "give every body its own name");
    }
  }
  data_->bodies.push_back(spec);
  data_->dirty = true;
  return static_cast<BodyId>(data_->bodies.size()) - 1;
}

void Model::set_gravity(const Eigen::Vector2d& acceleration) {
  data_->gravity = acceleration;
}

int Model::add_marker(BodyId body, const Eigen::Vector2d& coordinates) {
  if (body != kGround) data_->check_body(body, "a marker");
  data_->markers.push_back({body, coordinates});
  data_->point_loads.resize(data_->markers.size() * 2, 0.0);
  return static_cast<int>(data_->markers.size()) - 1;
}

int Model::add_coordinate_constraint(BodyId body, Coordinate coordinate,
                                     std::optional<double> value) {
  data_->check_body(body, "a coordinate constraint");
  const int index = coordinate_index(body, coordinate);
  const auto& spec = data_->bodies[body];
  const double initial = coordinate == Coordinate::X   ? spec.position.x()
                         : coordinate == Coordinate::Y ? spec.position.y()
                                                       : spec.angle;
  data_->constraints.push_back(
      {"coordinate constraint on " + spec.name + "." + std::string(name(coordinate)),
       ConstraintLevel::Position, index, value.value_or(initial)});
  data_->dirty = true;
  return static_cast<int>(data_->constraints.size()) - 1;
}

int Model::add_velocity_constraint(BodyId body, Coordinate coordinate, double velocity) {
  data_->check_body(body, "a velocity constraint");
  if (!std::isfinite(velocity)) {
    throw Error("prescribed velocity is not finite", "velocity constraint", "check the value");
  }
  const auto& spec = data_->bodies[body];
  data_->constraints.push_back(
      {"velocity constraint on " + spec.name + "." + std::string(name(coordinate)),
       ConstraintLevel::Velocity, coordinate_index(body, coordinate), velocity});
  data_->dirty = true;
  return static_cast<int>(data_->constraints.size()) - 1;
}

void Model::add_force_element(std::unique_ptr<ForceElement> element) {
  data_->force_elements.push_back(std::move(element));
}

int Model::coordinate_count() const {
  return static_cast<int>(data_->bodies.size()) * 3;
}
int Model::constraint_count() const {
  return static_cast<int>(data_->constraints.size());
}
int Model::body_count() const {
  return static_cast<int>(data_->bodies.size());
}
int Model::marker_count() const {
  return static_cast<int>(data_->markers.size());
}
const RigidBody2DSpec& Model::body(BodyId body) const {
  data_->check_body(body, "a body lookup");
  return data_->bodies[body];
}

BodyId Model::find_body(std::string_view body_name) const {
  std::string known;
  for (std::size_t b = 0; b < data_->bodies.size(); ++b) {
    if (data_->bodies[b].name == body_name) return static_cast<BodyId>(b);
    known += (known.empty() ? "" : ", ") + data_->bodies[b].name;
  }
  throw Error("no body named '" + std::string(body_name) + "'", "model",
              known.empty() ? "define the body first" : "known bodies: " + known);
}

int Model::coordinate_index(BodyId body, Coordinate coordinate) const {
  return body * 3 + static_cast<int>(coordinate);
}
BodyId Model::marker_body(int marker) const {
  return data_->markers.at(marker).body;
}
const std::vector<ConstraintInfo>& Model::constraints() const {
  return data_->constraints;
}
const Eigen::Vector2d& Model::gravity() const {
  return data_->gravity;
}

State Model::initial_state() const {
  const int n = coordinate_count();
  State state;
  state.q.resize(n);
  state.v.resize(n);
  state.lambda = Eigen::VectorXd::Zero(constraint_count());
  for (std::size_t b = 0; b < data_->bodies.size(); ++b) {
    const auto& spec = data_->bodies[b];
    const int i = static_cast<int>(b) * 3;
    state.q.segment<3>(i) << spec.position.x(), spec.position.y(), spec.angle;
    state.v.segment<3>(i) << spec.velocity.x(), spec.velocity.y(), spec.angular_velocity;
  }
  std::string problems;
  for (const auto& constraint : data_->constraints) {
    const double actual = constraint.level == ConstraintLevel::Position
                              ? state.q(constraint.coordinate)
                              : state.v(constraint.coordinate);
    const double tolerance = 1e-12 * (1.0 + std::abs(constraint.value));
    if (std::abs(actual - constraint.value) > tolerance) {
      problems += "\n  " + constraint.description + ": initial " +
                  (constraint.level == ConstraintLevel::Position ? "coordinate " : "velocity ") +
                  std::to_string(actual) + " but the constraint prescribes " +
                  std::to_string(constraint.value);
    }
  }
  if (!problems.empty()) {
    throw Error("the initial state violates constraints:" + problems, "model",
                "set the bodies' initial position/velocity to what the constraints prescribe");
  }
  return state;
}

const Eigen::MatrixXd& Model::mass_matrix() const {
  data_->refresh();
  return data_->mass;
}

void Model::applied_force(double time, const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                          Eigen::VectorXd& force) const {
  force.setZero(coordinate_count());
  for (std::size_t b = 0; b < data_->bodies.size(); ++b) {
    const int i = static_cast<int>(b) * 3;
    force(i) += data_->bodies[b].mass * data_->gravity.x();
    force(i + 1) += data_->bodies[b].mass * data_->gravity.y();
  }
  for (std::size_t k = 0; k < data_->markers.size(); ++k) {
    const Marker& marker = data_->markers[k];
    if (marker.body == kGround) continue;
    const double fx = data_->point_loads[2 * k];
    const double fy = data_->point_loads[2 * k + 1];
    if (fx == 0.0 && fy == 0.0) continue;
    const int i = marker.body * 3;
    const Eigen::Vector2d arm = rotated_derivative(q(i + 2), marker.local);
    force(i) += fx;
    force(i + 1) += fy;
    force(i + 2) += arm.x() * fx + arm.y() * fy;
  }
  for (const auto& element : data_->force_elements)
    element->add_force(time, q, v, force);
}

void Model::constraint_residual(double /*time*/, const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                                Eigen::VectorXd& residual) const {
  residual.resize(constraint_count());
  for (std::size_t k = 0; k < data_->constraints.size(); ++k) {
    const auto& c = data_->constraints[k];
    const double actual = c.level == ConstraintLevel::Position ? q(c.coordinate) : v(c.coordinate);
    residual(static_cast<int>(k)) = actual - c.value;
  }
}

const Eigen::MatrixXd& Model::constraint_jacobian() const {
  data_->refresh();
  return data_->jacobian;
}

void Model::set_point_loads(std::span<const double> loads) {
  if (loads.size() != data_->point_loads.size()) {
    throw Error("got " + std::to_string(loads.size() / 2) + " point loads for " +
                    std::to_string(data_->markers.size()) + " markers",
                "model", "pass one (x, y) load per marker");
  }
  std::copy(loads.begin(), loads.end(), data_->point_loads.begin());
}

std::span<const double> Model::point_loads() const {
  return data_->point_loads;
}

void Model::marker_positions(const State& state, std::span<double> xy) const {
  for (std::size_t k = 0; k < data_->markers.size(); ++k) {
    const Marker& marker = data_->markers[k];
    Eigen::Vector2d r = marker.local;
    if (marker.body != kGround) {
      const int i = marker.body * 3;
      r = state.q.segment<2>(i) + rotated(state.q(i + 2), marker.local);
    }
    xy[2 * k] = r.x();
    xy[2 * k + 1] = r.y();
  }
}

void Model::marker_velocities(const State& state, std::span<double> xy) const {
  for (std::size_t k = 0; k < data_->markers.size(); ++k) {
    const Marker& marker = data_->markers[k];
    Eigen::Vector2d u = Eigen::Vector2d::Zero();
    if (marker.body != kGround) {
      const int i = marker.body * 3;
      u = state.v.segment<2>(i) + state.v(i + 2) * rotated_derivative(state.q(i + 2), marker.local);
    }
    xy[2 * k] = u.x();
    xy[2 * k + 1] = u.y();
  }
}

double Model::coordinate(const State& state, BodyId body, Coordinate c) const {
  return state.q(coordinate_index(body, c));
}
double Model::velocity(const State& state, BodyId body, Coordinate c) const {
  return state.v(coordinate_index(body, c));
}

double Model::constraint_force(const State& state, BodyId body, Coordinate c) const {
  const int index = coordinate_index(body, c);
  double force = 0.0;
  const Eigen::MatrixXd& jacobian = constraint_jacobian();
  for (int k = 0; k < constraint_count(); ++k)
    force -= jacobian(k, index) * state.lambda(k);
  return force;
}

Eigen::Vector3d Model::point_load_resultant(const State& state, BodyId body) const {
  Eigen::Vector3d resultant = Eigen::Vector3d::Zero();
  const int i = body * 3;
  for (std::size_t k = 0; k < data_->markers.size(); ++k) {
    if (data_->markers[k].body != body) continue;
    const double fx = data_->point_loads[2 * k];
    const double fy = data_->point_loads[2 * k + 1];
    const Eigen::Vector2d arm = rotated(state.q(i + 2), data_->markers[k].local);
    resultant += Eigen::Vector3d(fx, fy, arm.x() * fy - arm.y() * fx);
  }
  return resultant;
}

double Model::kinetic_energy(const State& state) const {
  return 0.5 * state.v.dot(mass_matrix() * state.v);
}

double Model::potential_energy(const State& state) const {
  double energy = 0.0;
  for (std::size_t b = 0; b < data_->bodies.size(); ++b) {
    const int i = static_cast<int>(b) * 3;
    energy -= data_->bodies[b].mass * data_->gravity.dot(state.q.segment<2>(i));
  }
  return energy;
}

double Model::position_constraint_drift(const State& state) const {
  double drift = 0.0;
  for (const auto& c : data_->constraints) {
    if (c.level == ConstraintLevel::Position) {
      drift = std::max(drift, std::abs(state.q(c.coordinate) - c.value));
    }
  }
  return drift;
}

double Model::velocity_constraint_drift(const State& state) const {
  double drift = 0.0;
  for (const auto& c : data_->constraints) {
    if (c.level == ConstraintLevel::Velocity) {
      drift = std::max(drift, std::abs(state.v(c.coordinate) - c.value));
    }
  }
  return drift;
}

}  // namespace fsi::mbd
