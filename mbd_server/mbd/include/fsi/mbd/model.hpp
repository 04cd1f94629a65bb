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
// (src/body.hpp, src/constraint.hpp) so that later element types plug in without changing the
// integrator.

#include <Eigen/Dense>
#include <Eigen/SparseCore>

#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "fsi/mbd/constraint_element.hpp"
#include "fsi/mbd/force_element.hpp"
#include "fsi/mbd/matrix_sink.hpp"

namespace fsi::mbd {

using BodyId = int;
// Markers on the ground are fixed in the inertial frame (static geometry).
inline constexpr BodyId kGround = -1;

// Coordinates of a planar rigid body: the centre of mass (x, y) and the rotation angle phi.
enum class Coordinate { X = 0, Y = 1, Angle = 2 };
std::string_view name(Coordinate coordinate);

struct State {
  double time = 0.0;
  Eigen::VectorXd q;       // generalised coordinates
  Eigen::VectorXd v;       // their time derivatives
  Eigen::VectorXd lambda;  // one multiplier per constraint row (see the sign convention above)
};

struct RigidBody2DSpec {
  std::string name;
  double mass = 0.0;     // [kg] (2D: per unit depth, kg/m)
  double inertia = 0.0;  // about the centre of mass [kg m^2] (2D: kg m)
  Eigen::Vector2d position = Eigen::Vector2d::Zero();  // centre of mass [m]
  double angle = 0.0;                                  // [rad]
  Eigen::Vector2d velocity = Eigen::Vector2d::Zero();  // [m/s]
  double angular_velocity = 0.0;                       // [rad/s]
};

// A planar ANCF beam (Gerstmayr & Irschik 2008, "ANCF cable 2D") of element_count equal
// elements along the straight, stress-free line start -> end, initially at rest there. Per node
// four coordinates: position (x, y) and slope r' = dr/ds (x, y), s the arc length of the
// undeformed line; cubic Hermite elements. Axial strain eps = |r'| - 1, curvature
// kappa = (r' x r'') / |r'|^2; EA and EI per unit depth in 2D. Equations: docs/theory.md.
// Material points (markers, joint points) have local = (s, eta): s in [0, L] along the undeformed
// centre line, eta along the deformed line's unit normal n = e_z x r' / |r'| (left of start ->
// end), so eta = +-h/2 follow the two faces of a beam of thickness h.
struct AncfBeamSpec {
  std::string name;
  Eigen::Vector2d start = Eigen::Vector2d::Zero();  // [m]
  Eigen::Vector2d end = Eigen::Vector2d::UnitX();   // [m]
  int element_count = 1;
  double axial_stiffness = 0.0;    // EA [N] (2D: per unit depth, N/m)
  double bending_stiffness = 0.0;  // EI [N m^2] (2D: N m)
  double mass_per_length = 0.0;    // rho A [kg/m] (2D: kg/m^2)
  // Viscous structural damping: N = EA eps + axial_damping deps/dt,
  // M = EI kappa + bending_damping dkappa/dt.
  double axial_damping = 0.0;    // [N s] (2D: N s/m)
  double bending_damping = 0.0;  // [N m^2 s] (2D: N m s)
};

// The four coordinates of a beam node.
enum class BeamNodeCoordinate { X = 0, Y = 1, SlopeX = 2, SlopeY = 3 };

// How add_beam_clamp holds a node's slope (its position is always held).
enum class BeamClamp {
  // The slope's direction is held (n_0 . r' = 0, n_0 the initial normal), its length |r'| = 1 +
  // eps is free: the wall fixes the cross-section's position and rotation but not the axial
  // strain of the extensible beam there (Gerstmayr & Irschik's clamp, 3 rows).
  Direction,
  // Both slope components are held at their initial values (4 rows): also eps = 0 at the node.
  Full,
};

// A material point of a body at body-fixed local coordinates, or, with body = kGround, a fixed
// point of the world at `local`.
struct BodyPointSpec {
  BodyId body = kGround;
  Eigen::Vector2d local = Eigen::Vector2d::Zero();
};

// Linear spring-damper along the line between two points: tension
// T = stiffness (l - rest_length) + damping dl/dt pulls a stretched spring's points together.
struct SpringDamperSpec {
  BodyPointSpec a;
  BodyPointSpec b;
  double stiffness = 0.0;             // [N/m]
  double damping = 0.0;               // [N s/m]
  std::optional<double> rest_length;  // [m]; default: the initial distance
};

// Prismatic joint (2D): point b slides along the line through point a in the direction `axis`
// (body-fixed on a; a world direction if a is on the ground), and the relative rotation of the
// two bodies stays at its initial value. Two rows: the offset of b normal to the line,
// (axis x (r_b - r_a)) / |axis| (lambda: the force normal to the axis [N]), then the relative
// angle (lambda: the torque [N m]). Point b must lie on the line initially.
struct PrismaticJointSpec {
  std::string name;  // in messages; default "prismatic joint <row>"
  BodyPointSpec a;
  BodyPointSpec b;
  Eigen::Vector2d axis = Eigen::Vector2d::UnitX();  // any non-zero length
};

// Rigid clamp: `body` keeps its initial position and angle relative to `to` (another planar
// rigid body, or kGround). Three rows: x and y of the clamped body's centre of mass seen from
// `to`, then the relative angle.
struct ClampSpec {
  std::string name;  // in messages; default "clamp <row>"
  BodyId body = kGround;
  BodyId to = kGround;
};

// Rotational spring-damper between the angles of two planar rigid bodies (b = kGround: angle 0):
// torque on a = -stiffness (phi_a - phi_b - rest_angle) - damping (omega_a - omega_b), the
// opposite torque on b.
struct RotationalSpringDamperSpec {
  std::string name;  // in messages and sensors; default "rotational spring-damper <k>"
  BodyId a = kGround;
  BodyId b = kGround;
  double stiffness = 0.0;                           // [N m/rad]
  double damping = 0.0;                             // [N m s/rad]
  std::optional<double> rest_angle = std::nullopt;  // [rad]; default: the initial relative angle
};

// Spring-damper along the line between two points whose tension is a user function of the
// elongation l - rest_length [m] and its rate dl/dt [m/s]; positive tension pulls the points
// together (as SpringDamperSpec). Its derivatives are taken by central differences of the
// function; its energy (potential_energy) is the integral of tension(s, 0) ds from 0.
using TensionFunction = std::function<double(double elongation, double rate)>;
struct NonlinearSpringDamperSpec {
  std::string name;  // default "nonlinear spring-damper <k>"
  BodyPointSpec a;
  BodyPointSpec b;
  TensionFunction tension;
  std::optional<double> rest_length = std::nullopt;  // [m]; default: the initial distance
};

// The "spring actor" of thesis §6.5: a passive control element along the line between two
// points whose tension is a piecewise-linear function of the elongation, given as a table of
// (elongation [m], tension [N]) points in increasing elongation and continued beyond its ends
// with the end segments' slopes, plus linear damping. Its equilibrium is at rest_length (the
// closed valve). A one-sided actor (acting in compression only, like the thesis' actor 2, or a
// stiff stop in tension, like actor 1) has a zero-tension segment on the other side.
struct SpringActorSpec {
  std::string name;  // default "spring actor <k>"
  BodyPointSpec a;
  BodyPointSpec b;
  std::vector<Eigen::Vector2d> characteristic;       // at least 2 points, elongations increasing
  double damping = 0.0;                              // [N s/m]
  std::optional<double> rest_length = std::nullopt;  // [m]; default: the initial distance
};

// A coordinate of a planar rigid body driven along a prescribed motion s(t): the position row
// q_i - s(t) = 0 (lambda: the drive's force or torque), with its rate ds/dt given by the caller
// (the row's time derivative enters the Newton iteration and the initial check, so it must be
// exact, not a difference quotient; Model::add_prescribed_coordinate compares it with central
// differences of s at `check_times` and refuses a mismatch). d^2s/dt^2, needed only for the
// consistent initial multipliers, is the central difference of the rate.
struct PrescribedMotionSpec {
  std::string name;  // in messages; default "prescribed motion on <body>.<coordinate>"
  BodyId body = kGround;
  Coordinate coordinate = Coordinate::X;
  std::function<double(double time)> position;  // s(t) [m or rad]
  std::function<double(double time)> rate;      // ds/dt [m/s or rad/s]
  std::vector<double> check_times = {0.0};      // [s]
};

// A world-frame force that is a function of time, at a body point (evaluated at every stage
// time of the integrator, not held over the step like the fluid's point loads).
struct PointForceSpec {
  std::string name;  // default "point force <k>"
  BodyPointSpec point;
  std::function<Eigen::Vector2d(double time)> force;  // [N]
};

// A torque on a planar rigid body that is a function of time (evaluated at stage times).
struct TorqueSpec {
  std::string name;  // default "torque <k>"
  BodyId body = kGround;
  std::function<double(double time)> torque;  // [N m]
};

// --- spatial (3D) bodies and connectors (src/model_spatial.cpp) ---
// A model holds planar bodies (above) or spatial ones (below), not both; the first body or
// marker decides. Spatial bodies have constant mass matrices and material points linear in
// their coordinates (docs/theory.md, "Spatial bodies").

// A material point of a spatial body at body-fixed local coordinates, or with body = kGround a
// fixed point of space at `local`. On a rigid body, local is in its body frame relative to the
// centre of mass; on a cable local = (s, 0, 0), s along the undeformed centre line.
struct SpatialPointSpec {
  BodyId body = kGround;
  Eigen::Vector3d local = Eigen::Vector3d::Zero();
};

// A rigid body in space in natural coordinates: q = (r, e1, e2, e3), the centre of mass and the
// world components of the three body axes (12 coordinates), with the six orthonormality rows
// e_i . e_j = delta_ij added as constraints ("rigid body 'x' orthonormality (e1.e2)"). A body
// point is r + p1 e1 + p2 e2 + p3 e3, linear in q, and the mass matrix is constant:
// diag(m I, E (x) I) with E = tr(J)/2 I - J the second moment of the mass. Singularity-free for
// every orientation, unlike Euler angles; an alternative to Euler parameters with a constant
// mass matrix, which the stage equations of the integrator need.
struct RigidBody3DSpec {
  std::string name;
  double mass = 0.0;                                          // [kg]
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();          // about the centre of mass, body axes
  Eigen::Vector3d position = Eigen::Vector3d::Zero();         // centre of mass [m]
  Eigen::Matrix3d orientation = Eigen::Matrix3d::Identity();  // columns: body axes in the world
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();         // [m/s]
  Eigen::Vector3d angular_velocity = Eigen::Vector3d::Zero();  // world frame [rad/s]
};

// A point mass in space: q = (x, y, z), one material point (local = 0).
struct PointMassSpec {
  std::string name;
  double mass = 0.0;                                   // [kg]
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  // [m]
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();  // [m/s]
};

// A spatial ANCF cable (Gerstmayr & Shabana 2006): element_count cubic Hermite elements along
// the straight, stress-free line start -> end, per node the position r and the slope r' (6
// coordinates, 12 per element). Axial strain eps = |r'| - 1, curvature vector
// kappa = (r' x r'') / |r'|^2, energy 1/2 EA eps^2 + 1/2 EI |kappa|^2 per length (isotropic
// bending, no torsion: the cable has no cross-section orientation). A planar cable bends exactly
// as AncfBeamSpec. Material points lie on the centre line: local = (s, 0, 0).
struct AncfCableSpec {
  std::string name;
  Eigen::Vector3d start = Eigen::Vector3d::Zero();  // [m]
  Eigen::Vector3d end = Eigen::Vector3d::UnitX();   // [m]
  int element_count = 1;
  double axial_stiffness = 0.0;    // EA [N]
  double bending_stiffness = 0.0;  // EI [N m^2]
  double mass_per_length = 0.0;    // rho A [kg/m]
  double axial_damping = 0.0;      // [N s]
  double bending_damping = 0.0;    // [N m^2 s]
};

// Revolute joint in space: the points coincide (three rows x, y, z) and the axis, fixed in
// body a (in a's body frame; a world direction if a is the ground), stays normal to two
// directions of body b that are normal to it initially (two rows), so b turns about the axis
// only. The bodies must be rigid bodies (or the ground).
struct RevoluteJoint3DSpec {
  std::string name;  // in messages; default "revolute joint <row>"
  SpatialPointSpec a;
  SpatialPointSpec b;
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();
};

// Fixed joint in space: `body` (a RigidBody3D) keeps its initial position and orientation
// relative to `to` (another RigidBody3D, or kGround). Six rows: x, y, z of the body's centre of
// mass seen from `to` (spherical rows), then e1 . e2', e1 . e3', e2 . e3' with e_k' the body's
// initial axes fixed in `to` (perpendicularity rows).
struct FixedJoint3DSpec {
  std::string name;  // in messages; default "fixed joint <row>"
  BodyId body = kGround;
  BodyId to = kGround;
};

// Linear spring-damper between two points of spatial bodies (or a fixed point): tension
// k (l - l0) + c dl/dt along the line, as SpringDamperSpec.
struct SpatialSpringDamperSpec {
  std::string name;  // in messages; default "spring-damper <k>"
  SpatialPointSpec a;
  SpatialPointSpec b;
  double stiffness = 0.0;                            // [N/m]
  double damping = 0.0;                              // [N s/m]
  std::optional<double> rest_length = std::nullopt;  // [m]; default: the initial distance
};

// A world-frame force that is a function of time at a point of a spatial body (evaluated at the
// stage times, like PointForceSpec).
struct SpatialPointForceSpec {
  std::string name;  // default "point force <k>"
  SpatialPointSpec point;
  std::function<Eigen::Vector3d(double time)> force;  // [N]
};

// A world-frame torque that is a function of time on a spatial rigid body. In natural
// coordinates its generalised force is 1/2 tau x e_k on each axis e_k (virtual work
// tau . delta theta with delta e_k = delta theta x e_k).
struct SpatialTorqueSpec {
  std::string name;  // default "torque <k>"
  BodyId body = kGround;
  std::function<Eigen::Vector3d(double time)> torque;  // [N m]
};

namespace detail {
class BodyPoint;
}

class Model {
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
  const Eigen::Vector3d& spatial_gravity() const;
  // A marker on a spatial body (or a fixed one with kGround); returns its index. Point loads then
  // have three values (x, y, z) per marker.
  int add_spatial_marker(BodyId body, const Eigen::Vector3d& local_coordinates);
  // Spherical joint: r_a - r_b = 0, three rows (x, y, z); returns the index of the x row.
  int add_spherical_joint(const SpatialPointSpec& a, const SpatialPointSpec& b,
                          const std::string& name = {});
  int add_revolute_joint_3d(const RevoluteJoint3DSpec& spec);
  int add_fixed_joint_3d(const FixedJoint3DSpec& spec);
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
  int add_spatial_torque(const SpatialTorqueSpec& spec);

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
  Eigen::Vector3d spatial_marker_position(const State& state, int marker) const;
  Eigen::Vector3d spatial_marker_velocity(const State& state, int marker) const;
  const Eigen::Vector3d& spatial_marker_local_coordinates(int marker) const;
  // dr/dq (3 x n); zero for ground markers.
  Eigen::MatrixXd spatial_marker_jacobian(const Eigen::VectorXd& q, int marker) const;
  Eigen::Vector3d spatial_point_position(const State& state, const SpatialPointSpec& point) const;
  Eigen::Vector3d spatial_point_velocity(const State& state, const SpatialPointSpec& point) const;
  // The rotation matrix [e1 e2 e3] of a spatial rigid body (orthonormal up to the constraint
  // drift) and its angular velocity in the world frame, from dR/dt = [omega]x R.
  Eigen::Matrix3d orientation(const State& state, BodyId body) const;
  Eigen::Vector3d angular_velocity(const State& state, BodyId body) const;
  // Resultant of the point loads on a spatial body: force (x, y, z), then the torque about its
  // centre of mass.
  Eigen::Matrix<double, 6, 1> spatial_point_load_resultant(const State& state, BodyId body) const;
  // The force and the torque about the centre of mass that the rows first_row .. first_row +
  // rows - 1 exert on a spatial rigid body or point mass: its part of -G^T lambda (force: the
  // centre-of-mass components; torque: sum_k e_k x Q_(e_k)).
  Eigen::Matrix<double, 6, 1> spatial_joint_reaction(const State& state, int first_row, int rows,
                                                     BodyId body) const;

  // --- structure ---
  int coordinate_count() const;
  int constraint_count() const;
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
  const Eigen::Vector2d& marker_local_coordinates(int marker) const;
  std::string constraint_description(int constraint) const;  // "velocity constraint on piston.y"
  ConstraintLevel constraint_level(int constraint) const;
  const Eigen::Vector2d& gravity() const;
  int force_element_count() const;
  const ForceElement& force_element(int element) const;
  // "body 'link' coordinate angle" (planar rigid bodies) or "body 'beam' coordinate 4".
  std::string coordinate_description(int index) const;
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

  // --- assembly of the DAE (used by the integrators) ---
  // Every matrix is assembled element by element into a MatrixSink (fsi/mbd/matrix_sink.hpp);
  // the dense forms (small systems, static analysis, IDA) and the sparse forms (the Newton
  // matrix of large systems, O(size) work) are wrappers around that.
  // Constant for all current element types. The dense one is built on first use only.
  const Eigen::MatrixXd& mass_matrix() const;
  const Eigen::SparseMatrix<double>& sparse_mass_matrix() const;
  const Eigen::VectorXd& mass_diagonal() const;
  // F(t, q, v): gravity, point loads (held constant), the bodies' internal (elastic) forces and
  // force elements.
  void applied_force(double time, const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                     Eigen::VectorXd& force) const;
  // dF/dq and dF/dv: analytic for gravity, point loads and internal forces, analytic or central
  // differences for force elements (ForceElement::add_jacobian_entries, whose default forwards
  // the dense add_jacobians).
  void applied_force_derivatives(double time, const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                                 Eigen::MatrixXd& by_position, Eigen::MatrixXd& by_velocity) const;
  void applied_force_derivatives(double time, const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                                 Eigen::SparseMatrix<double>& by_position,
                                 Eigen::SparseMatrix<double>& by_velocity) const;
  // Adds the entries (sinks sized n x n).
  void add_applied_force_derivatives(double time, const Eigen::VectorXd& q,
                                     const Eigen::VectorXd& v, MatrixSink& by_position,
                                     MatrixSink& by_velocity) const;
  // C(q, t) for position-level rows, G v - g(t) for velocity-level rows (size m).
  void constraint_residual(double time, const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                           Eigen::VectorXd& residual) const;
  // The constraints on velocity level (size m): G v + C_t for position-level rows (the time
  // derivative of C along the motion) and G v - g(t) for velocity-level rows. Used by the
  // index-2 (GGL) formulation of the IDA integrator.
  void constraint_rate(double time, const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                       Eigen::VectorXd& rate) const;
  // The acceleration-free part of the constraints' second time derivative (size m), so that
  // d^2C/dt^2 = G a + remainder (position rows) and d(G v - g)/dt = G a + remainder (velocity
  // rows): the right-hand side of consistent multipliers.
  void constraint_acceleration_remainder(double time, const Eigen::VectorXd& q,
                                         const Eigen::VectorXd& v,
                                         Eigen::VectorXd& remainder) const;
  // G (m x n): dC/dq for position-level rows, d(G v - g)/dv for velocity-level rows.
  void constraint_jacobian(double time, const Eigen::VectorXd& q, Eigen::MatrixXd& jacobian) const;
  void constraint_jacobian(double time, const Eigen::VectorXd& q,
                           Eigen::SparseMatrix<double>& jacobian) const;
  void add_constraint_jacobian(double time, const Eigen::VectorXd& q, MatrixSink& jacobian) const;
  // d/dq (G(q)^T lambda) (n x n); zero while all constraints are linear in q.
  void constraint_force_derivative(double time, const Eigen::VectorXd& q,
                                   const Eigen::VectorXd& lambda,
                                   Eigen::MatrixXd& derivative) const;
  void constraint_force_derivative(double time, const Eigen::VectorXd& q,
                                   const Eigen::VectorXd& lambda,
                                   Eigen::SparseMatrix<double>& derivative) const;
  // d/dq (G(q) v) at fixed v (m x n), entries added: row k is v^T times the Hessian of C_k (the
  // Newton matrix of the index-2 form). Velocity-level rows add nothing (G independent of q).
  void add_constraint_velocity_derivative(double time, const Eigen::VectorXd& q,
                                          const Eigen::VectorXd& v, MatrixSink& derivative) const;
  void add_constraint_force_derivative(double time, const Eigen::VectorXd& q,
                                       const Eigen::VectorXd& lambda, MatrixSink& derivative) const;

  // --- point loads: world-frame forces on markers, held constant over a step ---
  // Two values (x, y) per marker, in marker order. Loads on ground markers are ignored.
  void set_point_loads(std::span<const double> loads);
  std::span<const double> point_loads() const;

  // --- markers ---
  Eigen::Vector2d marker_position(const State& state, int marker) const;
  Eigen::Vector2d marker_velocity(const State& state, int marker) const;
  // dr/dq (2 x n); zero for ground markers.
  Eigen::MatrixXd marker_jacobian(const Eigen::VectorXd& q, int marker) const;
  // All markers at once: x0, y0, x1, y1, ... (size 2 * marker_count()).
  void marker_positions(const State& state, std::span<double> xy) const;
  void marker_velocities(const State& state, std::span<double> xy) const;

  // --- readouts for sensors ---
  double coordinate(const State& state, BodyId body, Coordinate coordinate) const;
  double velocity(const State& state, BodyId body, Coordinate coordinate) const;
  // -G^T lambda, the generalised force of all constraints on the bodies (size n).
  Eigen::VectorXd generalised_constraint_force(const State& state) const;
  // One component of it: the constraint force (x, y) or torque (angle) on a body.
  double constraint_force(const State& state, BodyId body, Coordinate coordinate) const;
  // Resultant of the point loads on a body: force x, force y, torque about the centre of mass.
  Eigen::Vector3d point_load_resultant(const State& state, BodyId body) const;
  double kinetic_energy(const State& state) const;
  // Gravity (zero at the origin) plus the elastic energy of the force elements
  // (ForceElement::potential_energy).
  double potential_energy(const State& state) const;
  // What a force element measures (src/model_elements.cpp): the tension of a spring-damper
  // along its line [N] (linear, nonlinear, spring actor), the torque on body a of a rotational
  // spring-damper [N m]; throws fsi::Error for elements that measure nothing (loads).
  double force_element_force(const State& state, int element) const;
  // The force (x, y) and the torque about the centre of mass that the constraint rows
  // first_row .. first_row + rows - 1 (one joint) exert on `body`: its part of -G^T lambda.
  Eigen::Vector3d joint_reaction(const State& state, int first_row, int rows, BodyId body) const;
  // The first element whose contribution is not finite at (t, q, v): a force element, a point
  // load or a constraint row, by description; empty when all are finite. For error messages.
  std::string non_finite_source(double time, const Eigen::VectorXd& q,
                                const Eigen::VectorXd& v) const;
  double strain_energy(const State& state) const;  // of the beams' elastic deformation
  // World position and velocity of a body point in `state` (on a beam local = (s, eta)); throws
  // fsi::Error for an unknown body or a point outside a beam. Readouts such as the VTK centre
  // lines of beams.
  Eigen::Vector2d point_position(const State& state, const BodyPointSpec& point) const;
  // Throws fsi::Error naming `user` if the point is not a point of its body (unknown body,
  // planar/spatial mismatch, outside a beam or cable, off a cable's centre line).
  void check_point(const BodyPointSpec& point, const std::string& user) const;
  void check_spatial_point(const SpatialPointSpec& point, const std::string& user) const;
  Eigen::Vector2d point_velocity(const State& state, const BodyPointSpec& point) const;
  // Largest |C| over position-level rows.
  double position_constraint_drift(const State& state) const;
  // Largest velocity-level residual: |G v - g| of velocity rows and |G v + C_t| of position rows.
  double velocity_constraint_drift(const State& state) const;

 private:
  // A body point as the elements see it; throws naming `user` (src/model_elements.cpp).
  detail::BodyPoint body_point(const BodyPointSpec& spec, const std::string& user) const;
  // World position of a body point in the bodies' initial state.
  Eigen::Vector2d initial_point_position(const BodyPointSpec& spec) const;

  struct Data;
  std::unique_ptr<Data> data_;
};

}  // namespace fsi::mbd
