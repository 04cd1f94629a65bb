#pragma once
// What sensors and outputs read from a state: energies, constraint drifts and forces, joint
// reactions, point-load resultants, spring forces, and the positions and velocities of markers
// and body points. One function serves planar and spatial models: points are 3-vectors with
// z = 0 in a planar model, and a reaction or a resultant is a Wrench (planar: force (x, y, 0),
// torque (0, 0, tau)). The numbers are those of the equations the integrators solve; nothing
// here changes a model or a state.

#include <Eigen/Dense>

#include <span>

#include "fsi/mbd/constrained_system.hpp"
#include "fsi/mbd/element_specs.hpp"
#include "fsi/mbd/model.hpp"

namespace fsi::mbd {

// A force and the torque about a body's centre of mass, world frame.
struct Wrench {
  Eigen::Vector3d force = Eigen::Vector3d::Zero();   // [N] (2D: per unit depth)
  Eigen::Vector3d torque = Eigen::Vector3d::Zero();  // [N m]

  // The six components of a spatial sensor: force x, y, z, torque x, y, z.
  Eigen::Matrix<double, 6, 1> stacked() const {
    Eigen::Matrix<double, 6, 1> components;
    components << force, torque;
    return components;
  }
  // The three components of a planar sensor: force x, y, torque (about z).
  Eigen::Vector3d planar() const { return {force.x(), force.y(), torque.z()}; }
};

// --- of any constrained system ---
// 1/2 v^T M v.
double kinetic_energy(const ConstrainedSystem& system, const State& state);
// -G^T lambda, the generalised force of all constraints on the bodies (size n).
Eigen::VectorXd generalised_constraint_force(const ConstrainedSystem& system, const State& state);
// Largest |C| over the position-level rows that hold at state.time (released rows are free).
double position_constraint_drift(const ConstrainedSystem& system, const State& state);
// Largest velocity-level residual of the rows that hold at state.time: |G v - g| of velocity
// rows and |G v + C_t| of position rows.
double velocity_constraint_drift(const ConstrainedSystem& system, const State& state);

// --- energies of a model ---
// Gravity (zero at the origin) plus the elastic energy of the force elements
// (ForceElement::potential_energy).
double potential_energy(const Model& model, const State& state);
// Of the bodies' elastic deformation (beams, cables).
double strain_energy(const Model& model, const State& state);

// --- forces ---
// One component of -G^T lambda: the constraint force (x, y) or torque (angle) on a planar rigid
// body.
double constraint_force(const Model& model, const State& state, BodyId body, Coordinate coordinate);
// The force and torque that the constraint rows first_row .. first_row + rows - 1 (one joint)
// exert on `body`: its part of -G^T lambda (spatial rigid body: force from the centre-of-mass
// components, torque sum_k e_k x Q_(e_k)). Zero for the ground.
Wrench joint_reaction(const Model& model, const State& state, int first_row, int rows, BodyId body);
// The same rows' force and torque on an AncfBeam2D, the torque about the beam's point `point`
// ([s, eta]: a BeamClamp's node gives the clamp's moment, a pin's own point ~0): the force is the
// sum of the generalised forces Q_r on the nodes' positions, the torque
// sum_j (r_j - r_p) x Q_r,j + s_j x Q_s,j (a moment M about z acts on a slope s as the
// generalised force M z x s / |s|^2). Throws fsi::Error if `beam` is not an AncfBeam2D or s lies
// off the beam.
Wrench beam_joint_reaction(const Model& model, const State& state, int first_row, int rows,
                           BodyId beam, const Eigen::Vector2d& point);
// The resultant of the point loads on a body's markers: their sum and their torque about the
// body's reference point (the centre of mass of a rigid body).
Wrench point_load_resultant(const Model& model, const State& state, BodyId body);
// What a force element measures: the tension of a spring-damper along its line [N] (linear,
// nonlinear, spring actor), the torque on body a of a rotational spring-damper [N m]; throws
// fsi::Error for elements that measure nothing (loads).
double force_element_force(const Model& model, const State& state, int element);
// The rate of work a force element does on the bodies, Q(t, q, v) . v [W; 2D W/m]: a damper's is
// minus what it dissipates (-c omega^2), a spring's minus the rate of its stored energy, a load's
// what it puts in.
double force_element_power(const Model& model, const State& state, int element);

// --- positions and velocities (world frame) ---
Eigen::Vector3d marker_position(const Model& model, const State& state, int marker);
Eigen::Vector3d marker_velocity(const Model& model, const State& state, int marker);
// All markers at once, dimension() values per marker in marker order (x0, y0, x1, y1, ... in
// 2D; x0, y0, z0, ... in 3D): the boundary vertices the fluid sees.
void marker_positions(const Model& model, const State& state, std::span<double> values);
void marker_velocities(const Model& model, const State& state, std::span<double> values);
// A body point (on a beam local = (s, eta), on a cable (s, 0, 0)); throws fsi::Error for an
// unknown body, a point of the other dimension or a point outside a beam or cable.
Eigen::Vector3d point_position(const Model& model, const State& state, const BodyPointSpec& point);
Eigen::Vector3d point_position(const Model& model, const State& state,
                               const SpatialPointSpec& point);
Eigen::Vector3d point_velocity(const Model& model, const State& state, const BodyPointSpec& point);
// An AncfBeam2D's cross-section at arc length s: the angle of its centre line's tangent r' from
// the x axis [rad, counter-clockwise, in (-pi, pi]] and its rate (r' x dr'/dt) / |r'|^2
// [rad/s]. Throws fsi::Error if `beam` is not an AncfBeam2D or s lies off it.
double beam_tangent_angle(const Model& model, const State& state, BodyId beam, double s);
double beam_tangent_rate(const Model& model, const State& state, BodyId beam, double s);
Eigen::Vector3d point_velocity(const Model& model, const State& state,
                               const SpatialPointSpec& point);
// The rotation matrix [e1 e2 e3] of a spatial rigid body (orthonormal up to the constraint
// drift) and its angular velocity in the world frame, from dR/dt = [omega]x R.
Eigen::Matrix3d orientation(const Model& model, const State& state, BodyId body);
Eigen::Vector3d angular_velocity(const Model& model, const State& state, BodyId body);

}  // namespace fsi::mbd
