#pragma once
// The multibody model (thesis §2.1.2): generalised coordinates q (n), velocities v = dq/dt (n)
// and one Lagrange multiplier per constraint row (m), with the equations of motion
//
//     M dv/dt = F(t, q, v) - G(q)^T lambda
//     C(q, t) = 0                 position-level constraint rows (index 3), G = dC/dq
//     G v - g(t) = 0              velocity-level constraint rows (index 2)
//
// SIGN CONVENTION: the generalised force the constraints exert on the bodies is -G^T lambda
// (thesis eq. 2.2 with lambda C_q on the left-hand side). For a body held at rest this force
// balances the applied forces, so -(constraint force) = gravity + loads: that is how the coupled
// run weighs the fluid through lambda (thesis §6.3).
//
// Applied forces F: gravity, point loads on markers and force elements. A point load f (world
// frame) on a material point r(q) contributes Q = (dr/dq)^T f (virtual work, thesis eq. 2.6-2.8).
//
// This version has planar rigid bodies (x, y, phi of the centre of mass, mass matrix
// diag(m, m, J)), planar ANCF beams (Gerstmayr & Irschik's elastic-line element: position and
// slope per node, constant consistent mass matrix, elastic forces inside F), coordinate
// constraints on position or velocity level, beam clamps, joints and force elements.
// Bodies and constraints are internal element classes behind narrow interfaces
// (src/body.hpp, the rows' base ConstraintRow in src/sink_elements.hpp). The element specs are in
// fsi/mbd/element_specs.hpp; the integrators see the model only as a ConstrainedSystem
// (fsi/mbd/constrained_system.hpp).

#include <Eigen/Dense>
#include <Eigen/SparseCore>

#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "fsi/mbd/constrained_system.hpp"
#include "fsi/mbd/constraint_element.hpp"
#include "fsi/mbd/element_specs.hpp"
#include "fsi/mbd/force_element.hpp"
#include "fsi/mbd/matrix_sink.hpp"

namespace fsi::mbd {

namespace detail {
class BodyPoint;
struct ModelAccess;
}  // namespace detail

class Model final : public ConstrainedSystem {
 public:
  Model();
  ~Model();
  Model(Model&&) noexcept;
  Model& operator=(Model&&) noexcept;

  // --- building ---
  // Throws fsi::Error naming the body if mass or inertia are not positive and finite, a value is
  // not finite, or the name is taken.
  BodyId add_rigid_body(const RigidBody2DSpec& spec);
  // Throws fsi::Error naming the beam for fewer than one element, non-positive EA, EI or rho A,
  // coincident or non-finite end points, or a taken name.
  BodyId add_ancf_beam(const AncfBeamSpec& spec);
  void set_gravity(const Eigen::Vector2d& acceleration);
  // A material point at body-fixed local coordinates p, r = x + R(phi) p; on a beam
  // p = (s, eta), r = r(s) + eta n(s) (AncfBeamSpec; throws for s outside [0, L]); for kGround, p
  // is the fixed world position. Returns the marker index (the boundary-mesh vertex index).
  int add_marker(BodyId body, const Eigen::Vector2d& local_coordinates);
  // Position level: q_i - value = 0; value defaults to the body's initial coordinate.
  int add_coordinate_constraint(BodyId body, Coordinate coordinate,
                                std::optional<double> value = std::nullopt);
  // Clamps node `node` of a beam to the ground in its initial position and slope direction
  // (BeamClamp): position-level rows x, y, then the slope row(s); returns the index of the first.
  // Throws fsi::Error for a body that is not a beam or a node out of range.
  int add_beam_clamp(BodyId beam, int node, BeamClamp clamp = BeamClamp::Direction);
  // The same clamp to a planar rigid body `to`: the node stays at its initial place in the body's
  // frame (two point rows) and its slope direction (or, BeamClamp::Full, the whole slope) turns
  // with the body (SlopeOnBody rows). Throws for `to` not a RigidBody2D.
  int add_beam_clamp(BodyId beam, int node, BeamClamp clamp, BodyId to);
  // Velocity level: dq_i/dt - velocity = 0 (thesis §6.3: the piston's dy/dt = v0).
  int add_velocity_constraint(BodyId body, Coordinate coordinate, double velocity);
  // Velocity level with a velocity that is a function of time: dq_i/dt - g(t) = 0.
  int add_velocity_constraint(BodyId body, Coordinate coordinate,
                              std::function<double(double time)> velocity);
  // Position level q_i - s(t) = 0 (PrescribedMotionSpec); throws fsi::Error naming the element
  // for a missing function, a non-finite value or a rate that is not the derivative of s.
  int add_prescribed_motion(const PrescribedMotionSpec& spec);
  void add_force_element(std::unique_ptr<ForceElement> element);
  // Joints between two body points (one of them may be on the ground). All throw fsi::Error
  // naming the joint for unknown bodies, two points on the same body or both on the ground, and
  // non-finite values. Whether the initial state satisfies them is checked by initial_state().
  // Revolute joint (2D): r_a - r_b = 0, two rows (x, then y); returns the index of the x row.
  // With b on the ground it fixes a body point in the world (ground joint).
  // `name` (optional) appears in messages: "revolute joint 'hinge' (x)".
  int add_revolute_joint(const BodyPointSpec& a, const BodyPointSpec& b,
                         const std::string& name = {});
  // Massless rod: |r_b - r_a| = length (default: the initial distance; must be positive).
  // One row, written (|d|^2 - length^2) / (2 length) so that lambda is the rod force, tension
  // positive. Returns its index.
  int add_distance_constraint(const BodyPointSpec& a, const BodyPointSpec& b,
                              std::optional<double> length = std::nullopt,
                              const std::string& name = {});
  // A user's constraint row (e.g. a prescribed time-dependent motion); returns its index.
  int add_constraint_element(std::unique_ptr<ConstraintElement> element);
  // Releases constraint row `row` at `time` [s] (>= 0): it holds until then and is removed from
  // then on, its multiplier zero (ConstrainedSystem::release_time). Throws fsi::Error for a row
  // that does not exist or a time that is negative or not a number.
  void set_release_time(int row, double time);
  double release_time(int row) const override;
  // Throws fsi::Error for negative stiffness or damping or a negative rest length; the points
  // must never coincide (the direction of the force is undefined there).
  void add_spring_damper(const SpringDamperSpec& spec);

  // Connectors, force elements and time-dependent loads of planar rigid bodies
  // (src/model_elements.cpp). All throw fsi::Error naming the element for unknown bodies, bodies
  // that are not planar rigid bodies where an angle is needed, both ends on the same body, and
  // invalid or non-finite values. Joints return the index of their first row, force elements
  // their index among the force elements.
  int add_prismatic_joint(const PrismaticJointSpec& spec);
  int add_clamp(const ClampSpec& spec);
  int add_rotational_spring_damper(const RotationalSpringDamperSpec& spec);
  int add_nonlinear_spring_damper(const NonlinearSpringDamperSpec& spec);
  int add_nonlinear_rotational_spring_damper(const NonlinearRotationalSpringDamperSpec& spec);
  int add_spring_actor(const SpringActorSpec& spec);
  int add_point_force(const PointForceSpec& spec);
  int add_torque(const TorqueSpec& spec);

  // --- spatial bodies and connectors (src/model_spatial.cpp) ---
  // Throw fsi::Error naming the body for invalid values (non-positive mass, an inertia that is
  // not symmetric positive definite or violates the triangle inequality, an orientation that is
  // not a rotation, ...), a taken name, or a model of planar bodies.
  BodyId add_rigid_body_3d(const RigidBody3DSpec& spec);
  BodyId add_point_mass(const PointMassSpec& spec);
  BodyId add_ancf_cable(const AncfCableSpec& spec);
  // Holds node `node` of a cable in its initial position (x, y, z rows) and slope direction (two
  // rows: the slope stays normal to two initial normals; its length, the axial strain, is free).
  int add_cable_clamp(BodyId cable, int node);
  void set_spatial_gravity(const Eigen::Vector3d& acceleration);
  // A marker on a spatial body (or a fixed one with kGround); returns its index. Point loads then
  // have three values (x, y, z) per marker.
  int add_spatial_marker(BodyId body, const Eigen::Vector3d& local_coordinates);
  // Spherical joint: r_a - r_b = 0, three rows (x, y, z); returns the index of the x row.
  int add_spherical_joint(const SpatialPointSpec& a, const SpatialPointSpec& b,
                          const std::string& name = {});
  int add_revolute_joint_3d(const RevoluteJoint3DSpec& spec);
  int add_fixed_joint_3d(const FixedJoint3DSpec& spec);
  // Throws for a zero axis, a body that is not a RigidBody3D, both ends on one body or point_b off
  // the sliding line initially. Returns the first of its five rows.
  int add_prismatic_joint_3d(const PrismaticJoint3DSpec& spec);
  // A boundary vertex on the tube of radius `radius` around a cable: the centre-line point at s
  // plus radius (cos(angle) n1 + sin(angle) n2), (n1, n2) the normals of the straight initial
  // cable carried along by the rotation that turns the initial tangent into the current one (the
  // cable has no torsion). Its velocity is the centre line's and its point load acts on the
  // centre line (the moment radius x f of a thin tube is neglected). Returns the marker index.
  int add_cable_surface_marker(BodyId cable, double s, double angle, double radius);
  // Massless rod |r_b - r_a| = length (default: the initial distance), lambda the rod force.
  int add_spatial_distance_constraint(const SpatialPointSpec& a, const SpatialPointSpec& b,
                                      std::optional<double> length = std::nullopt,
                                      const std::string& name = {});

  // Return the index among the force elements; throw for the ground, a missing function or a
  // body that is not of the needed kind.
  int add_spatial_point_force(const SpatialPointForceSpec& spec);
  // Throws for negative or non-finite values; the points must never coincide.
  int add_spatial_spring_damper(const SpatialSpringDamperSpec& spec);
  // Throws for a missing function, both points on one body, points that coincide initially or a
  // negative rest length.
  int add_spatial_nonlinear_spring_damper(const SpatialNonlinearSpringDamperSpec& spec);
  int add_spatial_torque(const SpatialTorqueSpec& spec);
  // Throws for a body a that is not a RigidBody3D, b neither one nor the ground, both on one
  // body, a zero or non-finite axis, negative or non-finite k or c, k or c beside a torque law,
  // a rest angle that is not finite or beyond +-170 degrees.
  int add_spatial_rotational_spring_damper(const SpatialRotationalSpringDamperSpec& spec);
  // Penalty contact between two surface meshes (ContactSpec; planar or spatial after the model's
  // dimension). Throws fsi::Error naming the contact for unknown bodies, cables (their tube
  // vertices are not material points), both surfaces on the same body, empty surfaces, element
  // indices out of range, degenerate elements, and negative, non-finite or missing values.
  // Returns the index among the force elements.
  int add_contact(const ContactSpec& spec);

  // Any body: its name, kind ("rigid_body_2d", "ancf_beam", "rigid_body_3d", "point_mass",
  // "ancf_cable") and total mass [kg] (2D: per unit depth).
  const std::string& body_name(BodyId body) const;
  std::string body_kind(BodyId body) const;
  double body_mass(BodyId body) const;

  // 2 for planar models, 3 for spatial ones (2 while the model is empty).
  int dimension() const;
  // Throw fsi::Error if the body is not of that kind.
  const RigidBody3DSpec& rigid_body_3d(BodyId body) const;
  const AncfCableSpec& cable(BodyId cable) const;
  bool is_cable(BodyId body) const;
  int cable_node_count(BodyId cable) const;
  // Index in q of component `component` (0-2: x, y, z; 3-5: slope x, y, z) of a cable node.
  int cable_coordinate_index(BodyId cable, int node, int component) const;

  // --- structure ---
  int coordinate_count() const override;
  int constraint_count() const override;
  int body_count() const;
  int marker_count() const;
  // Throws fsi::Error if the body is not a rigid body.
  const RigidBody2DSpec& body(BodyId body) const;
  bool is_beam(BodyId body) const;
  // Throws fsi::Error if the body is not an ANCF beam.
  const AncfBeamSpec& beam(BodyId beam) const;
  int beam_node_count(BodyId beam) const;
  // Index in q of one coordinate of a beam node; throws for other bodies or nodes out of range.
  int beam_coordinate_index(BodyId beam, int node, BeamNodeCoordinate coordinate) const;
  // Throws fsi::Error listing the known names.
  BodyId find_body(std::string_view name) const;
  int coordinate_index(BodyId body, Coordinate coordinate) const;
  BodyId marker_body(int marker) const;
  // Body-fixed local coordinates of a marker (planar: z = 0), the world position for the ground.
  Eigen::Vector3d marker_local_coordinates(int marker) const;
  std::string constraint_description(
      int constraint) const override;  // "velocity constraint on piston.y"
  ConstraintLevel constraint_level(int constraint) const override;
  // The acceleration of gravity of the model's dimension (planar: z = 0).
  Eigen::Vector3d gravity() const;
  int force_element_count() const;
  const ForceElement& force_element(int element) const;
  // "body 'link' coordinate angle" (planar rigid bodies) or "body 'beam' coordinate 4".
  std::string coordinate_description(int index) const override;
  // The coordinates of any body in q: first index and count.
  int first_coordinate(BodyId body) const;
  int body_coordinate_count(BodyId body) const;

  // --- initial state and its consistency ---
  // q and v from the body specs; lambda consistent with the accelerations at t = 0 (solves
  // [M G^T; G 0] [a; lambda] = [F; -remainder] with the current point loads). Calls
  // check_consistency first.
  State initial_state() const;
  // q and v as initial_state() starts from (the body specs, or what set_initial_configuration
  // installed), unchecked, lambda zero: the approximate configuration an assembly starts from.
  State initial_configuration() const;
  // Replaces the bodies' initial q and v (e.g. by an assembled configuration,
  // fsi/mbd/assembly.hpp); initial_state() checks it like the specs' own. Element defaults taken
  // from the initial positions when the elements were added (rest lengths, rest angles, clamp
  // poses) keep their values. Throws fsi::Error for a size that is not coordinate_count() or
  // non-finite values.
  void set_initial_configuration(const Eigen::VectorXd& q, const Eigen::VectorXd& v);
  // Throws one fsi::Error listing every problem: position constraints C(q, t) != 0, their time
  // derivative G v + C_t != 0 (a held coordinate with a velocity), velocity constraints violated,
  // and constraint rows that are redundant (linearly dependent on earlier rows). Velocities are
  // CHECKED, never projected: a silent change of the user's initial velocity would hide a
  // mistake in the scene. Tolerance: 1e-12 (1 + |q|_inf) on position level, 1e-12 (1 + |v|_inf)
  // on velocity level.
  void check_consistency(const State& state) const;

  // --- the constrained system the integrators see (fsi/mbd/constrained_system.hpp) ---
  // Assembled element by element into MatrixSinks; the dense and sparse forms are the
  // interface's wrappers. The mass matrix is constant for every element type; the dense one is
  // built on first use only. F holds gravity, the point loads, the bodies' internal (elastic)
  // forces and the force elements; their derivatives are analytic, or central differences for
  // force elements without add_jacobian_entries.
  const Eigen::MatrixXd& mass_matrix() const override;
  const Eigen::SparseMatrix<double>& sparse_mass_matrix() const override;
  const Eigen::VectorXd& mass_diagonal() const override;
  void applied_force(double time, const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                     Eigen::VectorXd& force) const override;
  void add_applied_force_derivatives(double time, const Eigen::VectorXd& q,
                                     const Eigen::VectorXd& v, MatrixSink& by_position,
                                     MatrixSink& by_velocity) const override;
  void constraint_residual(double time, const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                           Eigen::VectorXd& residual) const override;
  void constraint_rate(double time, const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                       Eigen::VectorXd& rate) const override;
  void constraint_acceleration_remainder(double time, const Eigen::VectorXd& q,
                                         const Eigen::VectorXd& v,
                                         Eigen::VectorXd& remainder) const override;
  void add_constraint_jacobian(double time, const Eigen::VectorXd& q,
                               MatrixSink& jacobian) const override;
  void add_constraint_velocity_derivative(double time, const Eigen::VectorXd& q,
                                          const Eigen::VectorXd& v,
                                          MatrixSink& derivative) const override;
  void add_constraint_force_derivative(double time, const Eigen::VectorXd& q,
                                       const Eigen::VectorXd& lambda,
                                       MatrixSink& derivative) const override;

  // --- point loads: world-frame forces on markers, held constant over a step ---
  // Two values (x, y) per marker, in marker order. Loads on ground markers are ignored.
  void set_point_loads(std::span<const double> loads);
  std::span<const double> point_loads() const override;

  // --- markers (positions, velocities and loads: fsi/mbd/readouts.hpp) ---
  // dr/dq (dimension() x n); zero for ground markers.
  Eigen::MatrixXd marker_jacobian(const Eigen::VectorXd& q, int marker) const;

  // --- coordinates of planar rigid bodies (every other readout: fsi/mbd/readouts.hpp) ---
  double coordinate(const State& state, BodyId body, Coordinate coordinate) const;
  double velocity(const State& state, BodyId body, Coordinate coordinate) const;
  // The first element whose contribution is not finite at (t, q, v): a force element, a point
  // load or a constraint row, by description; empty when all are finite. For error messages.
  std::string non_finite_source(double time, const Eigen::VectorXd& q,
                                const Eigen::VectorXd& v) const override;
  // The force elements with a user's law (ForceElement::user_law) acting on the coordinate, named,
  // with what such a law needs (continuity); empty when none acts on it.
  std::string equation_of_motion_note(int index, double time, const Eigen::VectorXd& q,
                                      const Eigen::VectorXd& v) const override;
  // Throws fsi::Error naming `user` if the point is not a point of its body (unknown body,
  // planar/spatial mismatch, outside a beam or cable, off a cable's centre line). Two names, not
  // overloads: a braced point {body, {x, y}} would convert to either spec (Eigen's vector
  // constructors are not constrained), so the call would be ambiguous.
  void check_point(const BodyPointSpec& point, const std::string& user) const;
  void check_spatial_point(const SpatialPointSpec& point, const std::string& user) const;

 private:
  // The readouts (src/readouts.cpp) read the storage directly.
  friend struct detail::ModelAccess;

  // A body point as the elements see it; throws naming `user` (src/model_elements.cpp).
  detail::BodyPoint body_point(const BodyPointSpec& spec, const std::string& user) const;
  // World position of a body point in the bodies' initial state.
  Eigen::Vector2d initial_point_position(const BodyPointSpec& spec) const;

  struct Data;
  std::unique_ptr<Data> data_;
};

}  // namespace fsi::mbd
