#pragma once
// The multibody model (thesis §2.1.2): generalised coordinates q, velocities v = dq/dt and
// Lagrange multipliers lambda of the constraints, with the equations of motion
//     M(q) dv/dt = F(t, q, v) - C_q^T lambda,      C(q, t) = 0  (position level, index 3)
//                                                   B v - g(t) = 0 (velocity level, index 2)
// Sign convention: the generalised constraint force acting on the bodies is -C_q^T lambda.
//
// This version has planar rigid bodies (x, y, phi of the centre of mass), gravity, point loads on
// material points ("markers": the boundary-mesh vertices of the coupling), force elements, and
// coordinate constraints on position or velocity level. Point loads become generalised forces
// by virtual work, Q = (dr/dq)^T f (thesis eq. 2.6-2.8).

#include <Eigen/Dense>

#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace fsi::mbd {

using BodyId = int;
inline constexpr BodyId kGround = -1;

enum class Coordinate { X = 0, Y = 1, Angle = 2 };
std::string_view name(Coordinate coordinate);

struct State {
  double time = 0.0;
  Eigen::VectorXd q;
  Eigen::VectorXd v;
  Eigen::VectorXd lambda;
};

struct RigidBody2DSpec {
  std::string name;
  double mass = 0.0;     // [kg] (2D: per unit depth)
  double inertia = 0.0;  // about the centre of mass [kg m^2]
  Eigen::Vector2d position = Eigen::Vector2d::Zero();
  double angle = 0.0;
  Eigen::Vector2d velocity = Eigen::Vector2d::Zero();
  double angular_velocity = 0.0;
};

// A generalised force that depends on t, q and v (springs, dampers; later issues).
class ForceElement {
 public:
  virtual ~ForceElement() = default;
  // Adds this element's generalised force to `force` (size n).
  virtual void add_force(double time, const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                         Eigen::VectorXd& force) const = 0;
};

enum class ConstraintLevel { Position, Velocity };

struct ConstraintInfo {
  std::string description;  // e.g. "coordinate constraint on piston.y"
  ConstraintLevel level;
  int coordinate;  // index into q
  double value;    // prescribed coordinate (position level) or velocity (velocity level)
};

class Model {
 public:
  Model();
  ~Model();
  Model(Model&&) noexcept;
  Model& operator=(Model&&) noexcept;

  // --- building ---
  BodyId add_rigid_body(const RigidBody2DSpec& spec);  // throws fsi::Error on bad values
  void set_gravity(const Eigen::Vector2d& acceleration);
  // A material point fixed in the body frame (local coordinates), or in the inertial frame for
  // kGround. Returns the marker index.
  int add_marker(BodyId body, const Eigen::Vector2d& coordinates);
  // Holds q at `value` (default: the initial coordinate).
  int add_coordinate_constraint(BodyId body, Coordinate coordinate,
                                std::optional<double> value = std::nullopt);
  // Prescribes dq/dt = velocity.
  int add_velocity_constraint(BodyId body, Coordinate coordinate, double velocity);
  void add_force_element(std::unique_ptr<ForceElement> element);

  // --- structure ---
  int coordinate_count() const;
  int constraint_count() const;
  int body_count() const;
  int marker_count() const;
  const RigidBody2DSpec& body(BodyId body) const;
  // Body index by name; throws fsi::Error listing the known names.
  BodyId find_body(std::string_view name) const;
  int coordinate_index(BodyId body, Coordinate coordinate) const;
  BodyId marker_body(int marker) const;
  const std::vector<ConstraintInfo>& constraints() const;
  const Eigen::Vector2d& gravity() const;

  // Initial state from the body specs; throws fsi::Error naming every constraint the initial
  // state violates.
  State initial_state() const;

  // --- evaluation (used by the integrator) ---
  // Mass matrix (constant and diagonal for rigid bodies).
  const Eigen::MatrixXd& mass_matrix() const;
  // Applied generalised forces: gravity, point loads and force elements.
  void applied_force(double time, const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                     Eigen::VectorXd& force) const;
  // Rows of position-level constraints and velocity-level constraints.
  void constraint_residual(double time, const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                           Eigen::VectorXd& residual) const;
  // C_q: constant for coordinate constraints (one unit entry per row).
  const Eigen::MatrixXd& constraint_jacobian() const;

  // --- point loads (held constant over a step) ---
  // Two values (x, y) per marker, in marker order. Loads on ground markers are ignored.
  void set_point_loads(std::span<const double> loads);
  std::span<const double> point_loads() const;

  // --- readouts ---
  void marker_positions(const State& state, std::span<double> xy) const;
  void marker_velocities(const State& state, std::span<double> xy) const;
  double coordinate(const State& state, BodyId body, Coordinate coordinate) const;
  double velocity(const State& state, BodyId body, Coordinate coordinate) const;
  // Component of -C_q^T lambda on the body coordinate (sum over all constraints).
  double constraint_force(const State& state, BodyId body, Coordinate coordinate) const;
  // Resultant of the point loads on a body: force x, force y, torque about the centre of mass.
  Eigen::Vector3d point_load_resultant(const State& state, BodyId body) const;
  double kinetic_energy(const State& state) const;
  double potential_energy(const State& state) const;  // gravity
  // Largest |C| of position-level and |B v - g| of velocity-level constraints.
  double position_constraint_drift(const State& state) const;
  double velocity_constraint_drift(const State& state) const;

 private:
  struct Data;
  std::unique_ptr<Data> data_;
};

}  // namespace fsi::mbd
