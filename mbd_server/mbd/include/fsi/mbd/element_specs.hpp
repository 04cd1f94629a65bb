#pragma once
// What a user describes to build a multibody model: one plain struct per element (bodies,
// joints, springs, loads), planar ones first, then the spatial ones. Model::add_* takes them and
// checks them (fsi/mbd/model.hpp); the equations behind each are in docs/theory.md.

#include <Eigen/Dense>

#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace fsi::mbd {

using BodyId = int;
// Markers on the ground are fixed in the inertial frame (static geometry).
inline constexpr BodyId kGround = -1;

// Coordinates of a planar rigid body: the centre of mass (x, y) and the rotation angle phi.
enum class Coordinate { X = 0, Y = 1, Angle = 2 };
std::string_view name(Coordinate coordinate);

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
  // The initial rigid motion: the start's velocity and the angular velocity about the start
  // (every point r moves at velocity + angular_velocity z x (r - start)); default at rest.
  Eigen::Vector2d velocity = Eigen::Vector2d::Zero();  // [m/s]
  double angular_velocity = 0.0;                       // [rad/s]
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
// elongation l - rest_length [m], its rate dl/dt [m/s] and the time t [s]; positive tension pulls
// the points together (as SpringDamperSpec). Its derivatives are taken by central differences of
// the function; its energy (potential_energy) is the integral of tension(s, 0, t) ds from 0 (a
// law that changes in time changes its stored energy by itself: what drives it does work).
using TensionFunction = std::function<double(double elongation, double rate, double time)>;
struct NonlinearSpringDamperSpec {
  std::string name;  // default "nonlinear spring-damper <k>"
  BodyPointSpec a;
  BodyPointSpec b;
  TensionFunction tension;
  std::optional<double> rest_length = std::nullopt;  // [m]; default: the initial distance
};

// A rotational spring-damper whose resisting torque is a user function of the twist
// phi_a - phi_b - rest_angle [rad], its rate [rad/s] and the time [s]: the torque on a is
// -torque(twist, rate, t), the opposite on b (as RotationalSpringDamperSpec, whose law is
// k twist + c rate). Derivatives by central differences; its energy is the integral of
// torque(s, 0, t) ds from 0.
struct NonlinearRotationalSpringDamperSpec {
  std::string name;  // default "nonlinear rotational spring-damper <k>"
  BodyId a = kGround;
  BodyId b = kGround;
  TensionFunction torque;
  std::optional<double> rest_angle = std::nullopt;  // [rad]; default: the initial relative angle
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
// With a rate, a drive (motor): a sixth row turns body a relative to body b about the axis by the
// angle rate * t from the initial configuration (right-handed about the axis; with the ground as
// b, a's angular velocity about the axis is rate). Its multiplier is the drive torque about the
// axis on body a [N m] (RotationDriveConstraint, direction_rows.hpp). The initial velocities
// must agree: a's angular velocity relative to b about the axis is rate at t = 0.
struct RevoluteJoint3DSpec {
  std::string name;  // in messages; default "revolute joint <row>"
  SpatialPointSpec a;
  SpatialPointSpec b;
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();
  std::optional<double> rate = std::nullopt;  // [rad/s]; absent: a free hinge (5 rows)
};

// Prismatic joint in space: point b stays on the line through point a along `axis` (body a's
// frame) and the relative orientation of the two bodies is locked: body a slides along body b (or
// the ground). RigidBody3D bodies or kGround. Five rows: (r_b - r_a) . n1 and . n2 with n1, n2
// normals of the axis fixed in a (the normal forces), then e1 . e2', e1 . e3', e2 . e3' with e_k
// a's axes and e_k' the directions of b that coincide with them initially (perpendicularity rows).
struct PrismaticJoint3DSpec {
  std::string name;  // in messages; default "prismatic joint <row>"
  SpatialPointSpec a;
  SpatialPointSpec b;
  Eigen::Vector3d axis = Eigen::Vector3d::UnitX();
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

// A rotational spring-damper between two spatial rigid bodies about `axis` (in body a's axes):
// the torque resisting the twist, T = k twist + c rate or a user's law torque(twist, rate, t),
// acts on a as -T about the axis and on b as +T. The twist is a's rotation relative to b about
// the axis from the initial configuration, less rest_angle, measured within half a turn (a law
// that depends on it stops the run beyond +-170 degrees; a pure damper turns freely). With a
// RevoluteJoint3D about the same axis it is the hinge angle (the spatial RotationalSpringDamper);
// otherwise the angle of b's projection on the plane normal to the axis
// (spatial_rotational_spring.hpp).
struct SpatialRotationalSpringDamperSpec {
  std::string name;    // default "rotational spring-damper <k>"
  BodyId a = kGround;  // a RigidBody3D
  BodyId b = kGround;  // a RigidBody3D, or kGround
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();
  double stiffness = 0.0;  // [N m/rad], the linear law (torque empty)
  double damping = 0.0;    // [N m s/rad]
  TensionFunction torque;  // a user's law of (twist [rad], rate [rad/s], t [s]); then k = c = 0
  std::optional<double> rest_angle = std::nullopt;  // [rad]; default 0: relaxed initially
};

// A spatial point-to-point force whose tension is a user function of the elongation
// l - rest_length [m], its rate [m/s] and the time [s] (as NonlinearSpringDamperSpec, planar): a
// one-sided stop, a preload, a hardening mooring line, an actuator. Derivatives by central
// differences; its energy is the integral of tension(s, 0, t) ds from 0.
struct SpatialNonlinearSpringDamperSpec {
  std::string name;  // default "nonlinear spring-damper <k>"
  SpatialPointSpec a;
  SpatialPointSpec b;
  TensionFunction tension;
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

// One side of a contact: the surface mesh of one body (or of the ground) as contact sees it.
// Vertices are body-fixed local coordinates (planar: x, y with z ignored; a beam: s, eta; the
// ground: world positions); elements are 2 (planar segments) or 3 (spatial triangles) vertex
// indices each. Which side is outside (docs/theory.md, "Contact between structures"): a closed
// outline (every vertex starts one segment and ends one; every edge of a triangle shared by
// another, traversed the other way) is oriented by its signed area or volume, so either winding
// works; an open planar polyline acts to the LEFT of its direction of travel (a tank drawn
// counter-clockwise around the space it holds: down the left wall, along the floor, up the right
// wall), an open triangle surface to the side of its right-hand-rule normal.
struct ContactSurfaceSpec {
  std::string name;  // in messages ("box", "ground")
  BodyId body = kGround;
  std::vector<Eigen::Vector3d> vertices;
  std::vector<int> elements;
};

// Penalty contact between two surfaces, both ways (the vertices of each against the elements of
// the other). A vertex that lies behind an element by 0 < delta <= depth_limit and projects onto
// it feels f_n = max(0, stiffness delta + c(delta) d(delta)/dt) along the element's outward normal
// (the element with the smallest delta when several qualify), c = damping, ramped in linearly
// over the first damping_onset_depth of delta (0: from first touch), and regularised Coulomb
// friction f_t = -mu f_n tanh(|u_t| / regularisation_speed) u_t / |u_t| (u_t the tangential
// relative velocity); the element's vertices take the reaction by the projection's barycentric
// weights. Planar models: per unit depth, like every planar force.
struct ContactSpec {
  std::string name;  // default "contact <k>"
  ContactSurfaceSpec first;
  ContactSurfaceSpec second;
  double stiffness = 0.0;              // [N/m] per vertex in contact
  double damping = 0.0;                // [N s/m] per vertex in contact
  double friction_coefficient = 0.0;   // mu
  double regularisation_speed = 1e-3;  // [m/s], > 0 when mu > 0
  double depth_limit = 0.0;            // [m], > 0: deeper vertices have passed the element
  double damping_onset_depth = 0.0;    // [m], in [0, depth_limit)
};

}  // namespace fsi::mbd
