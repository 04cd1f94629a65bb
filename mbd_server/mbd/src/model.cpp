#include "fsi/mbd/model.hpp"

#include <Eigen/OrderingMethods>
#include <Eigen/SparseLU>
#include <Eigen/SparseQR>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "coordinate_rows.hpp"
#include "direction_rows.hpp"
#include "fsi/common/error.hpp"
#include "fsi/common/text.hpp"
#include "model_data.hpp"
#include "point_rows.hpp"
#include "point_to_point_force.hpp"
#include "rigid_body_3d.hpp"

namespace fsi::mbd {

namespace {

using detail::Marker;

// Up to this n + m the initial state is checked and lambda_0 solved with dense matrices (as the
// dense Newton matrix, cheaper for small systems); above it with sparse ones, whose cost grows
// about linearly with the size for chains and beams.
constexpr int kDenseInitialStateSize = 300;

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

Model::Model() : data_(std::make_unique<Data>()) {}
Model::~Model() = default;
Model::Model(Model&&) noexcept = default;
Model& Model::operator=(Model&&) noexcept = default;

// --- building ---

BodyId Model::add_rigid_body(const RigidBody2DSpec& spec) {
  return data_->add_body(std::make_unique<detail::RigidBody2D>(spec), "rigid body");
}

BodyId Model::add_ancf_beam(const AncfBeamSpec& spec) {
  return data_->add_body(std::make_unique<detail::AncfBeam2D>(spec), "ANCF beam");
}

void Model::set_gravity(const Eigen::Vector2d& acceleration) {
  if (!acceleration.allFinite()) {
    throw Error("gravity is not finite", "multibody model", "give a finite acceleration vector");
  }
  data_->gravity = acceleration;
}

int Model::add_marker(BodyId body, const Eigen::Vector2d& local_coordinates) {
  if (body != kGround) (void)data_->point({body, Eigen::Vector2d::Zero()}, "a marker");
  data_->require_dimension(2, "a planar marker");
  if (!local_coordinates.allFinite()) {
    throw Error("marker coordinates are not finite", "multibody model", "check the mesh points");
  }
  if (body != kGround) data_->bodies[body]->check_local_coordinates(local_coordinates, "a marker");
  data_->markers.push_back({body, local_coordinates});
  data_->point_loads.resize(2 * data_->markers.size(), 0.0);
  return static_cast<int>(data_->markers.size()) - 1;
}

int Model::add_coordinate_constraint(BodyId body, Coordinate coordinate,
                                     std::optional<double> value) {
  const auto& rigid = data_->rigid_body(body, "a coordinate constraint");
  const double held = value.value_or(rigid.initial_coordinate(coordinate));
  const std::string target = rigid.name() + "." + std::string(name(coordinate));
  if (!std::isfinite(held)) {
    throw Error("the prescribed value is not finite", "coordinate constraint on " + target,
                "give a finite value or none (the initial coordinate is held)");
  }
  data_->constraints.push_back(std::make_unique<detail::CoordinateConstraint>(
      "coordinate constraint on " + target, coordinate_index(body, coordinate), held));
  return static_cast<int>(data_->constraints.size()) - 1;
}

int Model::add_beam_clamp(BodyId beam_id, int node, BeamClamp clamp) {
  const auto& beam = data_->beam_node(beam_id, node, "a beam clamp");
  const Eigen::VectorXd reference = beam.reference_coordinates();
  const std::string target = beam.name() + " node " + std::to_string(node);
  auto index = [&](BeamNodeCoordinate c) { return beam_coordinate_index(beam_id, node, c); };
  auto initial = [&](BeamNodeCoordinate c) { return reference(4 * node + static_cast<int>(c)); };
  const int first = constraint_count();
  for (const auto c : {BeamNodeCoordinate::X, BeamNodeCoordinate::Y}) {
    data_->constraints.push_back(std::make_unique<detail::CoordinateConstraint>(
        "beam clamp on " + target + (c == BeamNodeCoordinate::X ? " (x)" : " (y)"), index(c),
        initial(c)));
  }
  if (clamp == BeamClamp::Full) {
    for (const auto c : {BeamNodeCoordinate::SlopeX, BeamNodeCoordinate::SlopeY}) {
      data_->constraints.push_back(std::make_unique<detail::CoordinateConstraint>(
          "beam clamp on " + target +
              (c == BeamNodeCoordinate::SlopeX ? " (slope x)" : " (slope y)"),
          index(c), initial(c)));
    }
    return first;
  }
  // n_0 . r' = 0 with the initial normal n_0 = (-t_y, t_x).
  Eigen::VectorXi indices(2);
  indices << index(BeamNodeCoordinate::SlopeX), index(BeamNodeCoordinate::SlopeY);
  Eigen::VectorXd weights(2);
  weights << -initial(BeamNodeCoordinate::SlopeY), initial(BeamNodeCoordinate::SlopeX);
  data_->constraints.push_back(std::make_unique<detail::LinearCoordinateConstraint>(
      "beam clamp on " + target + " (slope direction)", indices, weights, 0.0));
  return first;
}

int Model::add_beam_clamp(BodyId beam_id, int node, BeamClamp clamp, BodyId to) {
  if (to == kGround) return add_beam_clamp(beam_id, node, clamp);
  const auto& beam = data_->beam_node(beam_id, node, "a beam clamp");
  const auto& holder = data_->rigid_body(to, "a beam clamp");
  const Eigen::VectorXd reference = beam.reference_coordinates();
  const std::string target = "beam clamp on " + beam.name() + " node " + std::to_string(node) +
                             " to '" + holder.name() + "'";
  const Eigen::Vector2d node_position = reference.segment<2>(4 * node);
  const Eigen::Vector2d slope = reference.segment<2>(4 * node + 2);
  const Eigen::Rotation2Dd to_body = Eigen::Rotation2Dd(holder.spec().angle).inverse();
  const detail::BodyPoint on_beam =
      data_->point({beam_id, {node * beam.element_length(), 0.0}}, target);
  const detail::BodyPoint on_body =
      data_->point({to, to_body * (node_position - holder.spec().position)}, target);
  const int first = constraint_count();
  for (int axis = 0; axis < 2; ++axis) {
    data_->constraints.push_back(std::make_unique<detail::PointConstraint>(
        target + (axis == 0 ? " (x)" : " (y)"), on_beam, on_body, axis));
  }
  auto index = [&](BeamNodeCoordinate c) { return beam_coordinate_index(beam_id, node, c); };
  const int sx = index(BeamNodeCoordinate::SlopeX), sy = index(BeamNodeCoordinate::SlopeY);
  const int angle = coordinate_index(to, Coordinate::Angle);
  if (clamp == BeamClamp::Full) {
    for (int k = 0; k < 2; ++k) {
      data_->constraints.push_back(std::make_unique<detail::SlopeOnBodyConstraint>(
          target + (k == 0 ? " (slope x)" : " (slope y)"), sx, sy, angle, to_body * slope, k));
    }
    return first;
  }
  const Eigen::Vector2d normal(-slope.y(), slope.x());
  data_->constraints.push_back(std::make_unique<detail::SlopeOnBodyConstraint>(
      target + " (slope direction)", sx, sy, angle, to_body * normal, -1));
  return first;
}

int Model::add_velocity_constraint(BodyId body, Coordinate coordinate, double velocity) {
  const auto& rigid = data_->rigid_body(body, "a velocity constraint");
  const std::string target = rigid.name() + "." + std::string(name(coordinate));
  if (!std::isfinite(velocity)) {
    throw Error("the prescribed velocity is not finite", "velocity constraint on " + target,
                "give a finite velocity");
  }
  data_->constraints.push_back(std::make_unique<detail::VelocityConstraint>(
      "velocity constraint on " + target, coordinate_index(body, coordinate), velocity));
  return static_cast<int>(data_->constraints.size()) - 1;
}

int Model::add_velocity_constraint(BodyId body, Coordinate coordinate,
                                   std::function<double(double)> velocity) {
  const auto& rigid = data_->rigid_body(body, "a velocity constraint");
  const std::string target = rigid.name() + "." + std::string(name(coordinate));
  if (!velocity) {
    throw Error("no velocity function", "velocity constraint on " + target, "give velocity(t)");
  }
  data_->constraints.push_back(std::make_unique<detail::TimeVelocityConstraint>(
      "velocity constraint on " + target, coordinate_index(body, coordinate), std::move(velocity)));
  return static_cast<int>(data_->constraints.size()) - 1;
}

int Model::add_prescribed_motion(const PrescribedMotionSpec& spec) {
  const auto& rigid = data_->rigid_body(spec.body, "a prescribed motion");
  const std::string target = rigid.name() + "." + std::string(name(spec.coordinate));
  const std::string user = spec.name.empty() ? "prescribed motion on " + target
                                             : "prescribed motion '" + spec.name + "'";
  if (!spec.position || !spec.rate) {
    throw Error("the position or its rate is missing", user, "give both s(t) and ds/dt");
  }
  // The rate enters the Newton iteration as the row's exact time derivative: a wrong one is a
  // mistake in the scene, found here by central differences of s (4th order, relative 1e-6). A
  // fast drive (omega h >~ 0.1 at the first step) needs shorter steps: h is cut by 4 up to six
  // times, and the rate is accepted at the first step whose difference agrees within 1e-6 plus
  // the difference's rounding error; a wrong rate agrees at none.
  for (const double t : spec.check_times) {
    const double s = spec.position(t);
    const double given = spec.rate(t);
    if (!std::isfinite(s) || !std::isfinite(given)) {
      throw Error("s(t) or ds/dt is not finite at t = " + significant(t, 9), user,
                  "check the expressions");
    }
    double closest = std::numeric_limits<double>::quiet_NaN();
    bool agrees = false;
    for (int cut = 0; cut <= 6 && !agrees; ++cut) {
      const double h = 1e-3 * (1.0 + std::abs(t)) / std::pow(4.0, cut);
      const double difference = (8.0 * (spec.position(t + h) - spec.position(t - h)) -
                                 (spec.position(t + 2 * h) - spec.position(t - 2 * h))) /
                                (12.0 * h);
      const double rounding = 1e-14 * (1.0 + std::abs(s)) / h;
      agrees = std::abs(given - difference) <= 1e-6 * (1.0 + std::abs(difference)) + rounding;
      if (!(std::abs(given - difference) >= std::abs(given - closest))) closest = difference;
    }
    if (!agrees) {
      throw Error("the rate " + significant(given, 9) + " at t = " + significant(t, 9) +
                      " is not the derivative of the position (central difference " +
                      significant(closest, 9) + ", the closest of steps 1e-3 to 2.4e-7 (1 + |t|))",
                  user, "give rate = ds/dt of the position expression");
    }
  }
  data_->constraints.push_back(std::make_unique<detail::PrescribedCoordinate>(
      user, coordinate_index(spec.body, spec.coordinate), spec.position, spec.rate));
  return static_cast<int>(data_->constraints.size()) - 1;
}

void Model::add_force_element(std::unique_ptr<ForceElement> element) {
  FSI_ASSERT(element != nullptr, "add_force_element got no element");
  data_->force_elements.push_back(std::move(element));
}

int Model::add_revolute_joint(const BodyPointSpec& a, const BodyPointSpec& b,
                              const std::string& joint_name) {
  const std::string user = joint_name.empty()
                               ? "revolute joint " + std::to_string(constraint_count())
                               : "revolute joint '" + joint_name + "'";
  const detail::BodyPoint first = data_->point(a, user);
  const detail::BodyPoint second = data_->point(b, user);
  data_->check_pair(a, b, user);
  const std::string name =
      (joint_name.empty() ? "revolute joint " + data_->point_name(a) + "-" + data_->point_name(b)
                          : user) +
      " (";
  const int x_row = constraint_count();
  for (int axis = 0; axis < 2; ++axis) {
    data_->constraints.push_back(std::make_unique<detail::PointConstraint>(
        name + (axis == 0 ? "x)" : "y)"), first, second, axis));
  }
  return x_row;
}

int Model::add_distance_constraint(const BodyPointSpec& a, const BodyPointSpec& b,
                                   std::optional<double> length,
                                   const std::string& constraint_name) {
  const std::string user = constraint_name.empty()
                               ? "distance constraint " + std::to_string(constraint_count())
                               : "distance constraint '" + constraint_name + "'";
  const detail::BodyPoint first = data_->point(a, user);
  const detail::BodyPoint second = data_->point(b, user);
  data_->check_pair(a, b, user);
  const double rod =
      length.value_or((data_->initial_position(b) - data_->initial_position(a)).norm());
  if (!(rod > 0.0) || !std::isfinite(rod)) {
    throw Error("the length must be positive and finite, got " + significant(rod, 9), user,
                "give a positive length, or place the points apart initially");
  }
  data_->constraints.push_back(std::make_unique<detail::DistanceConstraint>(
      constraint_name.empty()
          ? "distance constraint " + data_->point_name(a) + "-" + data_->point_name(b)
          : user,
      first, second, rod));
  return constraint_count() - 1;
}

int Model::add_constraint_element(std::unique_ptr<ConstraintElement> element) {
  FSI_ASSERT(element != nullptr, "add_constraint_element got no element");
  data_->constraints.push_back(std::move(element));
  return constraint_count() - 1;
}

void Model::set_release_time(int row, double time) {
  if (row < 0 || row >= constraint_count()) {
    throw Error("release of constraint row " + std::to_string(row) + ", but the model has " +
                    std::to_string(constraint_count()) + " rows",
                "multibody model", "release a row that has been added");
  }
  // Before the start the row would never have held: the initial state would then have to satisfy
  // a constraint that does not exist, so a negative time is refused rather than guessed at.
  if (!(time >= 0.0)) {
    throw Error("release time " + significant(time, 9) + " s is negative or not a number",
                data_->constraints[row]->description(),
                "give a release time >= 0 s (0: held at the start only, released at once)");
  }
  if (data_->release_times.size() <= static_cast<std::size_t>(row))
    data_->release_times.resize(static_cast<std::size_t>(row) + 1,
                                std::numeric_limits<double>::infinity());
  data_->release_times[static_cast<std::size_t>(row)] = time;
}

double Model::release_time(int row) const {
  FSI_ASSERT(row >= 0 && row < constraint_count(), "constraint row out of range");
  const auto index = static_cast<std::size_t>(row);
  return index < data_->release_times.size() ? data_->release_times[index]
                                             : std::numeric_limits<double>::infinity();
}

void Model::add_spring_damper(const SpringDamperSpec& spec) {
  const std::string user = "spring-damper " + std::to_string(data_->force_elements.size());
  const detail::BodyPoint first = data_->point(spec.a, user);
  const detail::BodyPoint second = data_->point(spec.b, user);
  data_->check_pair(spec.a, spec.b, user);
  const double rest = spec.rest_length.value_or(
      (data_->initial_position(spec.b) - data_->initial_position(spec.a)).norm());
  detail::check_spring_values(spec.stiffness, spec.damping, rest, user);
  data_->force_elements.push_back(std::make_unique<detail::PointToPointForce>(
      user, first, second, rest,
      std::make_shared<detail::LinearTension>(spec.stiffness, spec.damping)));
}

// --- structure ---

int Model::coordinate_count() const {
  return data_->coordinates;
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
  return data_->rigid_body(body, "a body lookup").spec();
}

bool Model::is_beam(BodyId body) const {
  data_->check_body(body, "a body lookup");
  return dynamic_cast<const detail::AncfBeam2D*>(data_->bodies[body].get()) != nullptr;
}

const AncfBeamSpec& Model::beam(BodyId beam) const {
  return data_->ancf_beam(beam, "a beam lookup").spec();
}

int Model::beam_node_count(BodyId beam) const {
  return data_->ancf_beam(beam, "a beam lookup").node_count();
}

int Model::beam_coordinate_index(BodyId beam, int node, BeamNodeCoordinate coordinate) const {
  (void)data_->beam_node(beam, node, "a beam coordinate index");
  return data_->offsets[beam] + 4 * node + static_cast<int>(coordinate);
}

int Model::first_coordinate(BodyId body) const {
  data_->check_body(body, "a coordinate lookup");
  return data_->offsets[body];
}

int Model::body_coordinate_count(BodyId body) const {
  data_->check_body(body, "a coordinate lookup");
  return data_->bodies[body]->coordinate_count();
}

BodyId Model::find_body(std::string_view body_name) const {
  std::string known;
  for (std::size_t b = 0; b < data_->bodies.size(); ++b) {
    if (data_->bodies[b]->name() == body_name) return static_cast<BodyId>(b);
    known += (known.empty() ? "" : ", ") + data_->bodies[b]->name();
  }
  throw Error("no body named '" + std::string(body_name) + "'", "multibody model",
              known.empty() ? "define the body first" : "known bodies: " + known);
}

int Model::coordinate_index(BodyId body, Coordinate coordinate) const {
  (void)data_->rigid_body(body, "a coordinate index");
  return data_->offsets[body] + static_cast<int>(coordinate);
}

BodyId Model::marker_body(int marker) const {
  data_->check_marker(marker);
  return data_->markers[marker].body;
}

Eigen::Vector3d Model::marker_local_coordinates(int marker) const {
  data_->check_marker(marker);
  const Marker& m = data_->markers[marker];
  return data_->dimension == 3 ? m.spatial_local : Eigen::Vector3d(m.local.x(), m.local.y(), 0.0);
}

std::string Model::constraint_description(int constraint) const {
  FSI_ASSERT(constraint >= 0 && constraint < constraint_count(), "constraint index out of range");
  return data_->constraints[constraint]->description();
}

ConstraintLevel Model::constraint_level(int constraint) const {
  FSI_ASSERT(constraint >= 0 && constraint < constraint_count(), "constraint index out of range");
  return data_->constraints[constraint]->level();
}

Eigen::Vector3d Model::gravity() const {
  if (data_->dimension == 3) return data_->spatial_gravity;
  return {data_->gravity.x(), data_->gravity.y(), 0.0};
}

int Model::force_element_count() const {
  return static_cast<int>(data_->force_elements.size());
}

const ForceElement& Model::force_element(int element) const {
  FSI_ASSERT(element >= 0 && element < force_element_count(), "force element index out of range");
  return *data_->force_elements[element];
}

std::string Model::coordinate_description(int index) const {
  FSI_ASSERT(index >= 0 && index < coordinate_count(), "coordinate index out of range");
  std::size_t b = 0;
  while (b + 1 < data_->bodies.size() && data_->offsets[b + 1] <= index)
    ++b;
  const int local = index - data_->offsets[b];
  const bool rigid = dynamic_cast<const detail::RigidBody2D*>(data_->bodies[b].get()) != nullptr;
  const bool rigid_3d = dynamic_cast<const detail::RigidBody3D*>(data_->bodies[b].get()) != nullptr;
  static const char* kNatural[12] = {"x",    "y",    "z",    "e1.x", "e1.y", "e1.z",
                                     "e2.x", "e2.y", "e2.z", "e3.x", "e3.y", "e3.z"};
  // ANCF nodes: position, then the slope dr/ds (2D 4, 3D 6 coordinates per node).
  static const char* kNodal[6] = {"x", "y", "z", "slope x", "slope y", "slope z"};
  const int body = static_cast<int>(b);
  const int per_node = is_beam(body) ? 4 : is_cable(body) ? 6 : 0;
  const auto nodal = [&] {
    const int component = local % per_node;
    return "node " + std::to_string(local / per_node) + " " +
           (per_node == 4 ? std::string(kNodal[component < 2 ? component : component + 1])
                          : std::string(kNodal[component]));
  };
  return "body '" + data_->bodies[b]->name() + "' coordinate " +
         (rigid      ? std::string(name(static_cast<Coordinate>(local)))
          : rigid_3d ? std::string(kNatural[local])
          : per_node ? nodal()
                     : std::to_string(local));
}

detail::BodyPoint Model::body_point(const BodyPointSpec& spec, const std::string& user) const {
  return data_->point(spec, user);
}

void Model::check_point(const BodyPointSpec& point, const std::string& user) const {
  (void)data_->point(point, user);
}

Eigen::Vector2d Model::initial_point_position(const BodyPointSpec& spec) const {
  return data_->initial_position(spec);
}

// --- initial state and its consistency ---

State Model::initial_configuration() const {
  const int n = coordinate_count();
  State state;
  state.lambda = Eigen::VectorXd::Zero(constraint_count());
  if (data_->initial_configuration) {
    if (data_->initial_configuration->first.size() != n) {
      throw Error("the installed initial configuration has " +
                      std::to_string(data_->initial_configuration->first.size()) +
                      " coordinates but the model now has " + std::to_string(n),
                  "multibody model", "install the configuration after the last body is added");
    }
    state.q = data_->initial_configuration->first;
    state.v = data_->initial_configuration->second;
    return state;
  }
  state.q.resize(n);
  state.v.resize(n);
  for (std::size_t b = 0; b < data_->bodies.size(); ++b) {
    const int nb = data_->bodies[b]->coordinate_count();
    data_->bodies[b]->initial_state(state.q.segment(data_->offsets[b], nb),
                                    state.v.segment(data_->offsets[b], nb));
  }
  return state;
}

void Model::set_initial_configuration(const Eigen::VectorXd& q, const Eigen::VectorXd& v) {
  const int n = coordinate_count();
  if (q.size() != n || v.size() != n || !q.allFinite() || !v.allFinite()) {
    throw Error("an initial configuration needs " + std::to_string(n) +
                    " finite coordinates and velocities (got " + std::to_string(q.size()) +
                    " and " + std::to_string(v.size()) + ")",
                "multibody model", "pass q and v of this model");
  }
  data_->initial_configuration.emplace(q, v);
}

State Model::initial_state() const {
  const int n = coordinate_count();
  const int m = constraint_count();
  State state = initial_configuration();
  check_consistency(state);
  if (m == 0) return state;

  // Multipliers consistent with the accelerations: M a + G^T lambda = F, G a = -remainder.
  Eigen::VectorXd force;
  applied_force(state.time, state.q, state.v, force);
  if (n + m > kDenseInitialStateSize) {
    // [M G^T; G 0] from triplets, SparseLU.
    TripletSink system;
    for (std::size_t b = 0; b < data_->bodies.size(); ++b) {
      OffsetSink block(system, data_->offsets[b], data_->offsets[b]);
      data_->bodies[b]->mass_matrix(block);
    }
    Eigen::SparseMatrix<double> jacobian;
    constraint_jacobian(state.time, state.q, jacobian);
    for (int c = 0; c < jacobian.outerSize(); ++c) {
      for (Eigen::SparseMatrix<double>::InnerIterator it(jacobian, c); it; ++it) {
        system.add(n + static_cast<int>(it.row()), c, it.value());
        system.add(c, n + static_cast<int>(it.row()), it.value());
      }
    }
    Eigen::SparseMatrix<double> matrix;
    system.to_matrix(n + m, n + m, matrix);
    Eigen::VectorXd right(n + m);
    right.head(n) = force;
    for (int k = 0; k < m; ++k)
      right(n + k) = -data_->constraints[k]->acceleration_remainder(state.time, state.q, state.v);
    Eigen::SparseLU<Eigen::SparseMatrix<double>, Eigen::COLAMDOrdering<int>> lu(matrix);
    state.lambda = Eigen::VectorXd(lu.solve(right)).tail(m);
    return state;
  }
  Eigen::MatrixXd jacobian;
  constraint_jacobian(state.time, state.q, jacobian);
  Eigen::MatrixXd system = Eigen::MatrixXd::Zero(n + m, n + m);
  system.topLeftCorner(n, n) = mass_matrix();
  system.topRightCorner(n, m) = jacobian.transpose();
  system.bottomLeftCorner(m, n) = jacobian;
  Eigen::VectorXd right(n + m);
  right.head(n) = force;
  for (int k = 0; k < m; ++k)
    right(n + k) = -data_->constraints[k]->acceleration_remainder(state.time, state.q, state.v);
  state.lambda = Eigen::PartialPivLU<Eigen::MatrixXd>(system).solve(right).tail(m);
  return state;
}

void Model::check_consistency(const State& state) const {
  const int n = coordinate_count();
  const int m = constraint_count();
  FSI_ASSERT(state.q.size() == n && state.v.size() == n, "state does not match the model");
  std::string problems;
  if (!state.q.allFinite() || !state.v.allFinite()) {
    problems += "\n  the state has non-finite coordinates or velocities";
  }
  const double position_tolerance = 1e-12 * (1.0 + state.q.lpNorm<Eigen::Infinity>());
  const double velocity_tolerance = 1e-12 * (1.0 + state.v.lpNorm<Eigen::Infinity>());
  const bool dense = n + m <= kDenseInitialStateSize;
  Eigen::MatrixXd jacobian;
  Eigen::SparseMatrix<double> sparse_jacobian;
  Eigen::VectorXd jacobian_v;
  if (dense) {
    constraint_jacobian(state.time, state.q, jacobian);
    jacobian_v = jacobian * state.v;
  } else {
    constraint_jacobian(state.time, state.q, sparse_jacobian);
    jacobian_v = sparse_jacobian * state.v;
  }
  for (int k = 0; k < m; ++k) {
    const auto& constraint = *data_->constraints[k];
    const double residual = constraint.residual(state.time, state.q, state.v);
    if (constraint.level() == ConstraintLevel::Position) {
      if (!(std::abs(residual) <= position_tolerance)) {
        problems += "\n  " + constraint.description() +
                    ": position residual C = " + significant(residual, 9) +
                    " at t = " + significant(state.time, 9);
      }
      const double rate = jacobian_v(k) + constraint.explicit_time_derivative(state.time, state.q);
      if (!(std::abs(rate) <= velocity_tolerance)) {
        problems += "\n  " + constraint.description() +
                    ": velocity residual dC/dt = " + significant(rate, 9) +
                    " (the constrained coordinate has a velocity)";
      }
    } else if (!(std::abs(residual) <= velocity_tolerance)) {
      problems += "\n  " + constraint.description() +
                  ": velocity residual = " + significant(residual, 9) +
                  " at t = " + significant(state.time, 9);
    }
  }
  // Incremental rank: a row that does not raise the rank of the rows before it is redundant
  // and makes the Newton matrix singular. Large systems: a sparse QR of G^T in the natural
  // column order moves exactly such rows (columns of G^T) behind the rank.
  if (!dense && m > 0) {
    const Eigen::SparseMatrix<double> transposed = sparse_jacobian.transpose();
    Eigen::SparseQR<Eigen::SparseMatrix<double>, Eigen::NaturalOrdering<int>> qr(transposed);
    const auto rank = static_cast<int>(qr.rank());
    std::vector<int> redundant;
    for (int k = rank; k < m; ++k)
      redundant.push_back(qr.colsPermutation().indices()(k));
    std::sort(redundant.begin(), redundant.end());
    for (const int k : redundant) {
      problems += "\n  " + data_->constraints[k]->description() +
                  ": redundant (linearly dependent on the constraints before it)";
    }
  }
  int rank = 0;
  for (int k = 0; dense && k < m; ++k) {
    const int with_row =
        static_cast<int>(Eigen::FullPivLU<Eigen::MatrixXd>(jacobian.topRows(k + 1)).rank());
    if (with_row == rank) {
      problems += "\n  " + data_->constraints[k]->description() +
                  ": redundant (linearly dependent on the constraints before it)";
    }
    rank = with_row;
  }
  if (!problems.empty()) {
    throw Error("the initial state is inconsistent with the constraints:" + problems,
                "multibody model",
                "set the bodies' initial positions and velocities to what the constraints "
                "prescribe (a held coordinate needs zero velocity, a driven one the drive's "
                "velocity; a body turned about a pin away from its centre of mass also moves "
                "that centre), or let an Assembly block find them (docs/user-guide.md, "
                "\"Initial assembly\"), and constrain each coordinate once");
  }
}

// --- assembly ---

const Eigen::MatrixXd& Model::mass_matrix() const {
  if (!data_->mass_valid) {
    const int n = coordinate_count();
    data_->mass = Eigen::MatrixXd::Zero(n, n);
    DenseMatrixSink sink(data_->mass);
    for (std::size_t b = 0; b < data_->bodies.size(); ++b) {
      OffsetSink block(sink, data_->offsets[b], data_->offsets[b]);
      data_->bodies[b]->mass_matrix(block);
    }
    data_->mass_valid = true;
  }
  return data_->mass;
}

const Eigen::SparseMatrix<double>& Model::sparse_mass_matrix() const {
  if (!data_->sparse_mass_valid) {
    const int n = coordinate_count();
    TripletSink sink;
    for (std::size_t b = 0; b < data_->bodies.size(); ++b) {
      OffsetSink block(sink, data_->offsets[b], data_->offsets[b]);
      data_->bodies[b]->mass_matrix(block);
    }
    sink.to_matrix(n, n, data_->sparse_mass);
    data_->mass_diagonal = data_->sparse_mass.diagonal();
    data_->sparse_mass_valid = true;
  }
  return data_->sparse_mass;
}

const Eigen::VectorXd& Model::mass_diagonal() const {
  (void)sparse_mass_matrix();
  return data_->mass_diagonal;
}

void Model::applied_force(double time, const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                          Eigen::VectorXd& force) const {
  force.setZero(coordinate_count());
  for (std::size_t b = 0; b < data_->bodies.size(); ++b) {
    const auto& body = *data_->bodies[b];
    const int o = data_->offsets[b];
    const int nb = body.coordinate_count();
    if (const auto* spatial = data_->as_spatial(static_cast<BodyId>(b))) {
      spatial->add_spatial_gravity_force(data_->spatial_gravity, force.segment(o, nb));
    } else {
      body.add_gravity_force(data_->gravity, force.segment(o, nb));
    }
    body.add_internal_force(q.segment(o, nb), v.segment(o, nb), force.segment(o, nb));
  }
  if (data_->dimension == 3) {
    for (std::size_t k = 0; k < data_->markers.size(); ++k) {
      const Marker& marker = data_->markers[k];
      const Eigen::Vector3d load(data_->point_loads[3 * k], data_->point_loads[3 * k + 1],
                                 data_->point_loads[3 * k + 2]);
      if (marker.body == kGround || load.isZero(0.0)) continue;
      const auto& body = *data_->as_spatial(marker.body);
      body.add_spatial_point_load(
          data_->segment(q, marker.body), marker.spatial_local, load,
          force.segment(data_->offsets[marker.body], body.coordinate_count()));
    }
  }
  for (std::size_t k = 0; data_->dimension != 3 && k < data_->markers.size(); ++k) {
    const Marker& marker = data_->markers[k];
    const Eigen::Vector2d load(data_->point_loads[2 * k], data_->point_loads[2 * k + 1]);
    if (marker.body == kGround || (load.x() == 0.0 && load.y() == 0.0)) continue;
    const auto& body = *data_->bodies[marker.body];
    body.add_point_load(data_->segment(q, marker.body), marker.local, load,
                        force.segment(data_->offsets[marker.body], body.coordinate_count()));
  }
  for (const auto& element : data_->force_elements)
    element->add_force(time, q, v, force);
}

void Model::add_applied_force_derivatives(double time, const Eigen::VectorXd& q,
                                          const Eigen::VectorXd& v, MatrixSink& by_position,
                                          MatrixSink& by_velocity) const {
  const int n = coordinate_count();
  for (std::size_t b = 0; b < data_->bodies.size(); ++b) {
    const auto& body = *data_->bodies[b];
    const int o = data_->offsets[b];
    const int nb = body.coordinate_count();
    OffsetSink position_block(by_position, o, o), velocity_block(by_velocity, o, o);
    body.add_internal_force_derivatives(q.segment(o, nb), v.segment(o, nb), position_block,
                                        velocity_block);
  }
  for (std::size_t k = 0; data_->dimension == 3 && k < data_->markers.size(); ++k) {
    const Marker& marker = data_->markers[k];
    const Eigen::Vector3d load(data_->point_loads[3 * k], data_->point_loads[3 * k + 1],
                               data_->point_loads[3 * k + 2]);
    if (marker.body == kGround || load.isZero(0.0)) continue;
    const auto& body = *data_->as_spatial(marker.body);
    const int o = data_->offsets[marker.body];
    OffsetSink block(by_position, o, o);
    body.add_spatial_point_load_derivative(data_->segment(q, marker.body), marker.spatial_local,
                                           load, block);
  }
  for (std::size_t k = 0; data_->dimension != 3 && k < data_->markers.size(); ++k) {
    const Marker& marker = data_->markers[k];
    const Eigen::Vector2d load(data_->point_loads[2 * k], data_->point_loads[2 * k + 1]);
    if (marker.body == kGround || (load.x() == 0.0 && load.y() == 0.0)) continue;
    const auto& body = *data_->bodies[marker.body];
    const int o = data_->offsets[marker.body];
    OffsetSink block(by_position, o, o);
    body.add_point_load_derivative(data_->segment(q, marker.body), marker.local, load, block);
  }
  // Central differences for elements without analytic derivatives; the step balances
  // truncation (~step^2) against cancellation (~eps/step). O(n) force evaluations per element.
  const double step_factor = std::cbrt(std::numeric_limits<double>::epsilon());
  Eigen::VectorXd plus(n), minus(n), shifted_q, shifted_v;
  // Column j of d(force)/d(shifted): `shifted` is q or v and `force_at` evaluates the element's
  // force with it in place; shifted(j) is restored afterwards.
  auto add_difference_column = [&](MatrixSink& sink, int j, const Eigen::VectorXd& base,
                                   Eigen::VectorXd& shifted, const auto& force_at) {
    const double step = step_factor * std::max(1.0, std::abs(base(j)));
    plus.setZero();
    minus.setZero();
    shifted(j) = base(j) + step;
    force_at(plus);
    shifted(j) = base(j) - step;
    force_at(minus);
    shifted(j) = base(j);
    const Eigen::VectorXd column = (plus - minus) / (2.0 * step);
    for (Eigen::Index i = 0; i < column.size(); ++i) {
      if (column(i) != 0.0) sink.add(static_cast<int>(i), j, column(i));
    }
  };
  for (const auto& element : data_->force_elements) {
    if (element->add_jacobian_entries(time, q, v, by_position, by_velocity)) continue;
    shifted_q = q;
    shifted_v = v;
    for (int j = 0; j < n; ++j) {
      add_difference_column(by_position, j, q, shifted_q, [&](Eigen::VectorXd& force) {
        element->add_force(time, shifted_q, v, force);
      });
      add_difference_column(by_velocity, j, v, shifted_v, [&](Eigen::VectorXd& force) {
        element->add_force(time, q, shifted_v, force);
      });
    }
  }
}

void Model::constraint_residual(double time, const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                                Eigen::VectorXd& residual) const {
  residual.resize(constraint_count());
  for (int k = 0; k < constraint_count(); ++k)
    residual(k) = data_->constraints[k]->residual(time, q, v);
}

void Model::constraint_rate(double time, const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                            Eigen::VectorXd& rate) const {
  Eigen::SparseMatrix<double> jacobian;
  constraint_jacobian(time, q, jacobian);
  const Eigen::VectorXd jacobian_v = jacobian * v;
  rate.resize(constraint_count());
  for (int k = 0; k < constraint_count(); ++k) {
    const auto& constraint = *data_->constraints[k];
    rate(k) = constraint.level() == ConstraintLevel::Position
                  ? jacobian_v(k) + constraint.explicit_time_derivative(time, q)
                  : constraint.residual(time, q, v);
  }
}

void Model::constraint_acceleration_remainder(double time, const Eigen::VectorXd& q,
                                              const Eigen::VectorXd& v,
                                              Eigen::VectorXd& remainder) const {
  remainder.resize(constraint_count());
  for (int k = 0; k < constraint_count(); ++k)
    remainder(k) = data_->constraints[k]->acceleration_remainder(time, q, v);
}

void Model::add_constraint_jacobian(double time, const Eigen::VectorXd& q,
                                    MatrixSink& jacobian) const {
  for (int k = 0; k < constraint_count(); ++k)
    data_->constraints[k]->add_jacobian_entries(time, q, k, jacobian);
}

namespace {

// Receives the Hessian H of one row (entries (i, j)) and adds v_i H_ij at (row, j): the row of
// d(G v)/dq.
class ContractingSink final : public MatrixSink {
 public:
  ContractingSink(MatrixSink& target, int row, const Eigen::VectorXd& v)
      : target_(target), row_(row), v_(v) {}
  void add(int i, int j, double value) override { target_.add(row_, j, v_(i) * value); }

 private:
  MatrixSink& target_;
  int row_;
  const Eigen::VectorXd& v_;
};

}  // namespace

void Model::add_constraint_velocity_derivative(double time, const Eigen::VectorXd& q,
                                               const Eigen::VectorXd& v,
                                               MatrixSink& derivative) const {
  for (int k = 0; k < constraint_count(); ++k) {
    if (data_->constraints[k]->level() != ConstraintLevel::Position) continue;
    ContractingSink row(derivative, k, v);
    data_->constraints[k]->add_force_derivative_entries(time, q, 1.0, row);
  }
}

void Model::add_constraint_force_derivative(double time, const Eigen::VectorXd& q,
                                            const Eigen::VectorXd& lambda,
                                            MatrixSink& derivative) const {
  for (int k = 0; k < constraint_count(); ++k)
    data_->constraints[k]->add_force_derivative_entries(time, q, lambda(k), derivative);
}

// --- point loads ---

void Model::set_point_loads(std::span<const double> loads) {
  if (loads.size() != data_->point_loads.size()) {
    throw Error("got " + std::to_string(loads.size()) + " point-load values for " +
                    std::to_string(data_->markers.size()) + " markers",
                "multibody model",
                data_->dimension == 3 ? "pass (x, y, z) per marker, in marker order"
                                      : "pass one (x, y) pair per marker, in marker order");
  }
  std::copy(loads.begin(), loads.end(), data_->point_loads.begin());
}

std::span<const double> Model::point_loads() const {
  return data_->point_loads;
}

// --- markers ---

Eigen::MatrixXd Model::marker_jacobian(const Eigen::VectorXd& q, int marker) const {
  data_->check_marker(marker);
  const Marker& m = data_->markers[marker];
  Eigen::MatrixXd jacobian = Eigen::MatrixXd::Zero(dimension(), coordinate_count());
  if (m.body == kGround) return jacobian;
  const auto& body = *data_->bodies[m.body];
  auto columns = jacobian.middleCols(data_->offsets[m.body], body.coordinate_count());
  if (const auto* spatial = data_->as_spatial(m.body)) {
    spatial->spatial_position_jacobian(data_->segment(q, m.body), m.spatial_local, columns);
  } else {
    body.position_jacobian(data_->segment(q, m.body), m.local, columns);
  }
  return jacobian;
}

// --- readouts ---

double Model::coordinate(const State& state, BodyId body, Coordinate c) const {
  return state.q(coordinate_index(body, c));
}

double Model::velocity(const State& state, BodyId body, Coordinate c) const {
  return state.v(coordinate_index(body, c));
}

}  // namespace fsi::mbd
