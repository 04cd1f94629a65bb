// Acceptance test of issue 4: the car axis problem of the IVP Test Set (Mazzia & Magherini),
// an index-3 DAE with 4 coordinates and 2 multipliers, eps = 1e-2, against its reference y(3)
// (/work/shared/reference-data/ivp_testset_caraxis_crank_reference.dat, copied below).
//
// Test set form: K p'' = f(p, t) + G(p, t)^T lambda, 0 = phi(p, t), K = M eps^2 / 2 I, with
//   f = spring origin-left wheel (stiffness 1, rest length L0) + spring (xb, yb)-right wheel
//       + gravity -K g on y,
//   phi_1 = xb(t) xl + yb(t) yl,  phi_2 = (xl - xr)^2 + (yl - yr)^2 - L^2,
//   yb = r sin(w t), xb = sqrt(L^2 - yb^2).
// In the engine: each wheel is a rigid body of mass K (its rotation is decoupled and stays at
// rest), the left spring is a spring-damper, the right one a force element whose anchor moves,
// phi_1 a user ConstraintElement, phi_2 the engine's distance constraint, which is written
// phi_2 / (2 L). With the engine's sign (-G^T lambda): lambda_1 = -lambda_1,ref and
// lambda_2 = -2 L lambda_2,ref.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "fsi/mbd/integrator.hpp"

namespace fsi::mbd {
namespace {

constexpr double kEpsilon = 1e-2, kAxleMass = 10.0, kLength = 1.0, kRestLength = 0.5;
constexpr double kRadius = 0.1, kOmega = 10.0, kGravity = 1.0;
constexpr double kWheelMass = kAxleMass * kEpsilon * kEpsilon / 2.0;

// The moving end of the right spring, (xb, yb), with its first two time derivatives.
struct Anchor {
  Eigen::Vector2d position, velocity, acceleration;
};
Anchor anchor(double t) {
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

TEST(MbdCarAxisAcceptance, RadauIIA3MatchesTheReferenceAtTEquals3ToSixDigits) {
  Model model;
  RigidBody2DSpec wheel;
  wheel.mass = kWheelMass;
  wheel.inertia = kWheelMass;
  wheel.name = "left wheel";
  wheel.position = {0.0, 0.5};
  wheel.velocity = {-0.5, 0.0};
  const BodyId left = model.add_rigid_body(wheel);
  wheel.name = "right wheel";
  wheel.position = {1.0, 0.5};
  wheel.velocity = {-0.5, 0.0};
  const BodyId right = model.add_rigid_body(wheel);
  model.set_gravity({0.0, -kGravity});
  const int xl = model.coordinate_index(left, Coordinate::X);
  const int xr = model.coordinate_index(right, Coordinate::X);
  model.add_spring_damper({.a = {kGround, {0.0, 0.0}},
                           .b = {left, {0.0, 0.0}},
                           .stiffness = 1.0,
                           .damping = 0.0,
                           .rest_length = kRestLength});
  model.add_force_element(std::make_unique<MovingAnchorSpring>(xr));
  model.add_constraint_element(std::make_unique<AxleOrthogonality>(xl));
  model.add_distance_constraint({left, {0.0, 0.0}}, {right, {0.0, 0.0}}, kLength);

  const double h = 1e-4;
  RadauIIA integrator(3, {.relative_tolerance = 1e-12, .max_iterations = 20});
  State state = model.initial_state();
  for (int i = 0; i < 30000; ++i)
    integrator.step(model, state, h);
  ASSERT_NEAR(state.time, 3.0, 1e-10);  // 30000 additions of h

  // IVP Test Set reference y(3): xl, yl, xr, yr, their velocities, lambda_1, lambda_2.
  const double reference[10] = {0.493455784275402809122e-1,  0.496989460230171153861,
                                0.104174252488542151681e1,   0.373911027265361256927,
                                -0.770583684040972357970e-1, 0.744686658723778553466e-2,
                                0.175568157537232222276e-1,  0.770341043779251976443,
                                -0.473688659084893324729e-2, -0.110468033125734368808e-2};
  const double computed[10] = {state.q(xl),      state.q(xl + 1),
                               state.q(xr),      state.q(xr + 1),
                               state.v(xl),      state.v(xl + 1),
                               state.v(xr),      state.v(xr + 1),
                               -state.lambda(0), -state.lambda(1) / (2.0 * kLength)};
  double fewest_digits = 99.0;
  for (int k = 0; k < 10; ++k) {
    const double relative = std::abs(computed[k] - reference[k]) / std::abs(reference[k]);
    const double digits = -std::log10(relative);
    fewest_digits = std::min(fewest_digits, digits);
    std::printf("car axis y%-2d = %+.12e  reference %+.12e  relative error %.1e\n", k + 1,
                computed[k], reference[k], relative);
    // Significant correct digits as the IVP Test Set counts them: scd = -log10(relative error).
    EXPECT_GE(digits, 6.0) << "component " << k + 1;
  }
  std::printf(
      "car axis, Radau IIA 3, h = %g: at least %.1f significant digits in every component\n", h,
      fewest_digits);
}

}  // namespace
}  // namespace fsi::mbd
