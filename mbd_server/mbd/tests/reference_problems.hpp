#pragma once
// Reference problems with known solutions, shared by the acceptance tests of every integrator
// and by bench/mbd_integrators.cpp:
//
// * the pendulum: a rigid body of 1 kg on a massless rod of L = 1 m (distance constraint from
//   the ground pivot at the origin to its centre of mass), g = 9.81 m/s^2, released from rest at
//   90 degrees; the rod acts at the centre of mass, so the body is exactly a point mass; period
//   4 sqrt(L/g) K(sin(pi/4)) = 2.3678419476 s.
// * the car axis problem of the IVP Test Set (Mazzia & Magherini), an index-3 DAE with 4
//   coordinates and 2 multipliers, eps = 1e-2, with its reference y(3)
//   (/work/shared/reference-data/ivp_testset_caraxis_crank_reference.dat, copied below).
//
// Car axis, test set form: K p'' = f(p, t) + G(p, t)^T lambda, 0 = phi(p, t), K = M eps^2 / 2 I,
//   f = spring origin-left wheel (stiffness 1, rest length L0) + spring (xb, yb)-right wheel
//       + gravity -K g on y,
//   phi_1 = xb(t) xl + yb(t) yl,  phi_2 = (xl - xr)^2 + (yl - yr)^2 - L^2,
//   yb = r sin(w t), xb = sqrt(L^2 - yb^2).
// In the engine: each wheel is a rigid body of mass K (its rotation is decoupled and stays at
// rest), the left spring is a spring-damper, the right one a force element whose anchor moves,
// phi_1 a user ConstraintElement, phi_2 the engine's distance constraint, which is written
// phi_2 / (2 L). With the engine's sign (-G^T lambda): lambda_1 = -lambda_1,ref and
// lambda_2 = -2 L lambda_2,ref.

#include <Eigen/Dense>

#include <array>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "fsi/mbd/model.hpp"

namespace fsi::mbd::reference {

// Least-squares slope of log(error) over log(step size).
inline double fitted_order(const std::vector<double>& steps, const std::vector<double>& errors) {
  const int count = static_cast<int>(steps.size());
  double mean_x = 0.0, mean_y = 0.0;
  for (int k = 0; k < count; ++k) {
    mean_x += std::log(steps[k]) / count;
    mean_y += std::log(errors[k]) / count;
  }
  double numerator = 0.0, denominator = 0.0;
  for (int k = 0; k < count; ++k) {
    const double dx = std::log(steps[k]) - mean_x;
    numerator += dx * (std::log(errors[k]) - mean_y);
    denominator += dx * dx;
  }
  return numerator / denominator;
}

// --- pendulum ---
inline constexpr double kPendulumLength = 1.0;
inline constexpr double kPendulumGravity = 9.81;
inline constexpr double kPendulumPeriod = 2.3678419476;

inline Model point_mass_pendulum() {
  Model model;
  RigidBody2DSpec bob;
  bob.name = "bob";
  bob.mass = 1.0;
  bob.inertia = 1.0;  // irrelevant: no torque acts on the body
  bob.position = {kPendulumLength, 0.0};
  const BodyId body = model.add_rigid_body(bob);
  model.set_gravity({0.0, -kPendulumGravity});
  model.add_distance_constraint({kGround, {0.0, 0.0}}, {body, {0.0, 0.0}});
  return model;
}

// The root of the cubic Hermite interpolant of x between two times (x and dx/dt at both ends),
// by bisection: the interpolation error is O(h^4), 1e-13 s at h = 1e-3.
inline double hermite_root(double t0, double h, double x0, double v0, double x1, double v1) {
  auto x = [&](double s) {
    const double s2 = s * s, s3 = s2 * s;
    return (2 * s3 - 3 * s2 + 1) * x0 + (s3 - 2 * s2 + s) * h * v0 + (-2 * s3 + 3 * s2) * x1 +
           (s3 - s2) * h * v1;
  };
  double low = 0.0, high = 1.0;
  for (int k = 0; k < 60; ++k) {
    const double mid = 0.5 * (low + high);
    if ((x(low) < 0) == (x(mid) < 0)) {
      low = mid;
    } else {
      high = mid;
    }
  }
  return t0 + 0.5 * (low + high) * h;
}

// --- rigid chain: `bodies` bars of 0.1 m and 0.1 kg in a horizontal line, each joined to the
// next by a revolute joint at their common end, the first to the ground at the origin; released
// from rest under gravity (3 coordinates and 2 joint rows per body) ---
inline Model rigid_chain(int bodies) {
  Model model;
  const double length = 0.1, mass = 0.1;
  model.set_gravity({0.0, -9.81});
  BodyId previous = kGround;
  for (int b = 0; b < bodies; ++b) {
    RigidBody2DSpec bar;
    bar.name = "bar " + std::to_string(b);
    bar.mass = mass;
    bar.inertia = mass * length * length / 12.0;
    bar.position = {(b + 0.5) * length, 0.0};
    const BodyId body = model.add_rigid_body(bar);
    const Eigen::Vector2d joint(b * length, 0.0);
    if (previous == kGround) {
      model.add_revolute_joint({body, {-0.5 * length, 0.0}}, {kGround, joint});
    } else {
      model.add_revolute_joint({body, {-0.5 * length, 0.0}}, {previous, {0.5 * length, 0.0}});
    }
    previous = body;
  }
  return model;
}

// --- car axis ---
namespace car_axis {

inline constexpr double kEpsilon = 1e-2, kAxleMass = 10.0, kLength = 1.0, kRestLength = 0.5;
inline constexpr double kRadius = 0.1, kOmega = 10.0, kGravity = 1.0;
inline constexpr double kWheelMass = kAxleMass * kEpsilon * kEpsilon / 2.0;
inline constexpr double kEndTime = 3.0;

// IVP Test Set reference y(3): xl, yl, xr, yr, their velocities, lambda_1, lambda_2.
inline constexpr std::array<double, 10> kReference = {
    0.493455784275402809122e-1, 0.496989460230171153861,     0.104174252488542151681e1,
    0.373911027265361256927,    -0.770583684040972357970e-1, 0.744686658723778553466e-2,
    0.175568157537232222276e-1, 0.770341043779251976443,     -0.473688659084893324729e-2,
    -0.110468033125734368808e-2};

// The moving end of the right spring, (xb, yb), with its first two time derivatives.
struct Anchor {
  Eigen::Vector2d position, velocity, acceleration;
};
inline Anchor anchor(double t) {
  const double y = kRadius * std::sin(kOmega * t);
  const double dy = kRadius * kOmega * std::cos(kOmega * t);
  const double ddy = -kOmega * kOmega * y;
  const double x = std::sqrt(kLength * kLength - y * y);
  const double dx = -y * dy / x;
  const double ddx = -(dy * dy + y * ddy + dx * dx) / x;
  return {{x, y}, {dx, dy}, {ddx, ddy}};
}

// Spring (stiffness 1, rest length L0) from the moving anchor to the right wheel's centre.
class MovingAnchorSpring final : public ForceElement {
 public:
  explicit MovingAnchorSpring(int x_index) : x_(x_index) {}
  void add_force(double time, const Eigen::VectorXd& q, const Eigen::VectorXd&,
                 Eigen::VectorXd& force) const override {
    const Eigen::Vector2d d = q.segment<2>(x_) - anchor(time).position;
    force.segment<2>(x_) += (kRestLength - d.norm()) * d / d.norm();
  }

 private:
  int x_;
};

// phi_1 = xb(t) xl + yb(t) yl: the left wheel stays on the line through the origin normal to
// the anchor's direction.
class AxleOrthogonality final : public ConstraintElement {
 public:
  explicit AxleOrthogonality(int x_index) : x_(x_index) {}
  std::string description() const override { return "car axis phi_1"; }
  ConstraintLevel level() const override { return ConstraintLevel::Position; }
  double residual(double t, const Eigen::VectorXd& q, const Eigen::VectorXd&) const override {
    return anchor(t).position.dot(q.segment<2>(x_));
  }
  void jacobian_row(double t, const Eigen::VectorXd&, RowRef row) const override {
    row.segment<2>(x_) = anchor(t).position.transpose();
  }
  double explicit_time_derivative(double t, const Eigen::VectorXd& q) const override {
    return anchor(t).velocity.dot(q.segment<2>(x_));
  }
  double acceleration_remainder(double t, const Eigen::VectorXd& q,
                                const Eigen::VectorXd& v) const override {
    const Anchor b = anchor(t);
    return 2.0 * b.velocity.dot(v.segment<2>(x_)) + b.acceleration.dot(q.segment<2>(x_));
  }
  void add_force_derivative(double, const Eigen::VectorXd&, double,
                            Eigen::MatrixXd&) const override {}  // linear in q

 private:
  int x_;
};

struct Problem {
  Model model;
  int xl = 0, xr = 0;  // coordinate indices of the wheels' x
};

inline Problem make() {
  Problem p;
  RigidBody2DSpec wheel;
  wheel.mass = kWheelMass;
  wheel.inertia = kWheelMass;
  wheel.name = "left wheel";
  wheel.position = {0.0, 0.5};
  wheel.velocity = {-0.5, 0.0};
  const BodyId left = p.model.add_rigid_body(wheel);
  wheel.name = "right wheel";
  wheel.position = {1.0, 0.5};
  wheel.velocity = {-0.5, 0.0};
  const BodyId right = p.model.add_rigid_body(wheel);
  p.model.set_gravity({0.0, -kGravity});
  p.xl = p.model.coordinate_index(left, Coordinate::X);
  p.xr = p.model.coordinate_index(right, Coordinate::X);
  p.model.add_spring_damper({.a = {kGround, {0.0, 0.0}},
                             .b = {left, {0.0, 0.0}},
                             .stiffness = 1.0,
                             .damping = 0.0,
                             .rest_length = kRestLength});
  p.model.add_force_element(std::make_unique<MovingAnchorSpring>(p.xr));
  p.model.add_constraint_element(std::make_unique<AxleOrthogonality>(p.xl));
  p.model.add_distance_constraint({left, {0.0, 0.0}}, {right, {0.0, 0.0}}, kLength);
  return p;
}

// The state in the test set's order and sign convention.
inline std::array<double, 10> test_set_vector(const Problem& p, const State& state) {
  return {state.q(p.xl),    state.q(p.xl + 1),
          state.q(p.xr),    state.q(p.xr + 1),
          state.v(p.xl),    state.v(p.xl + 1),
          state.v(p.xr),    state.v(p.xr + 1),
          -state.lambda(0), -state.lambda(1) / (2.0 * kLength)};
}

// Significant correct digits of each component as the IVP Test Set counts them:
// scd = -log10(relative error).
inline std::array<double, 10> significant_digits(const Problem& p, const State& state) {
  const auto computed = test_set_vector(p, state);
  std::array<double, 10> digits{};
  for (int k = 0; k < 10; ++k)
    digits[k] = -std::log10(std::abs(computed[k] - kReference[k]) / std::abs(kReference[k]));
  return digits;
}

}  // namespace car_axis
}  // namespace fsi::mbd::reference
