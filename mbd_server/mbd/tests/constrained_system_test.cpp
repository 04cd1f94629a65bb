// The integrators' seam: a system written directly against ConstrainedSystem, without Model, is
// integrated by Radau IIA. The pendulum in two Cartesian coordinates q = (x, y) of a 1 kg mass on
// a rod of L = 1 m, C = (x^2 + y^2 - L^2) / (2 L), is the same motion as the reference pendulum of
// the acceptance tests (a rigid body on the engine's distance constraint, whose rotation is
// decoupled): the two runs must agree step for step, and the hand-written one must keep its rod.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "fsi/mbd/constrained_system.hpp"
#include "fsi/mbd/integrator.hpp"
#include "reference_problems.hpp"

namespace fsi::mbd {
namespace {

class CartesianPendulum final : public ConstrainedSystem {
 public:
  CartesianPendulum()
      : mass_(Eigen::MatrixXd::Identity(2, 2)),
        sparse_mass_(mass_.sparseView()),
        mass_diagonal_(Eigen::VectorXd::Ones(2)) {}

  int coordinate_count() const override { return 2; }
  int constraint_count() const override { return 1; }
  const Eigen::MatrixXd& mass_matrix() const override { return mass_; }
  const Eigen::SparseMatrix<double>& sparse_mass_matrix() const override { return sparse_mass_; }
  const Eigen::VectorXd& mass_diagonal() const override { return mass_diagonal_; }

  void applied_force(double, const Eigen::VectorXd&, const Eigen::VectorXd&,
                     Eigen::VectorXd& force) const override {
    force = Eigen::Vector2d(0.0, -reference::kPendulumGravity);
  }
  void add_applied_force_derivatives(double, const Eigen::VectorXd&, const Eigen::VectorXd&,
                                     MatrixSink&, MatrixSink&) const override {}

  ConstraintLevel constraint_level(int) const override { return ConstraintLevel::Position; }
  void constraint_residual(double, const Eigen::VectorXd& q, const Eigen::VectorXd&,
                           Eigen::VectorXd& residual) const override {
    residual.resize(1);
    residual(0) = (q.squaredNorm() - kLength * kLength) / (2.0 * kLength);
  }
  void constraint_rate(double, const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                       Eigen::VectorXd& rate) const override {
    rate.resize(1);
    rate(0) = q.dot(v) / kLength;
  }
  void constraint_acceleration_remainder(double, const Eigen::VectorXd&, const Eigen::VectorXd& v,
                                         Eigen::VectorXd& remainder) const override {
    remainder.resize(1);
    remainder(0) = v.squaredNorm() / kLength;
  }
  void add_constraint_jacobian(double, const Eigen::VectorXd& q,
                               MatrixSink& jacobian) const override {
    jacobian.add(0, 0, q(0) / kLength);
    jacobian.add(0, 1, q(1) / kLength);
  }
  void add_constraint_force_derivative(double, const Eigen::VectorXd&,
                                       const Eigen::VectorXd& lambda,
                                       MatrixSink& derivative) const override {
    derivative.add(0, 0, lambda(0) / kLength);
    derivative.add(1, 1, lambda(0) / kLength);
  }
  void add_constraint_velocity_derivative(double, const Eigen::VectorXd&, const Eigen::VectorXd& v,
                                          MatrixSink& derivative) const override {
    derivative.add(0, 0, v(0) / kLength);
    derivative.add(0, 1, v(1) / kLength);
  }
  std::span<const double> point_loads() const override { return {}; }

 private:
  static constexpr double kLength = reference::kPendulumLength;
  Eigen::MatrixXd mass_;
  Eigen::SparseMatrix<double> sparse_mass_;
  Eigen::VectorXd mass_diagonal_;
};

TEST(MbdConstrainedSystem, HandWrittenPendulumIntegratesAsTheModelPendulum) {
  const CartesianPendulum cartesian;
  const Model model = reference::point_mass_pendulum();
  State cartesian_state;
  cartesian_state.q = Eigen::Vector2d(reference::kPendulumLength, 0.0);
  cartesian_state.v = Eigen::Vector2d::Zero();
  cartesian_state.lambda = Eigen::VectorXd::Zero(1);  // released from rest: the rod is slack
  State model_state = model.initial_state();
  ASSERT_NEAR(model_state.lambda(0), 0.0, 1e-15);

  // Full Newton to a tight tolerance: the two systems differ in size (the model has the bob's
  // decoupled angle), so their iterations stop at different points within the tolerance.
  const NewtonOptions tight{
      .relative_tolerance = 1e-13, .max_iterations = 30, .max_modified_newton_steps = 0};
  RadauIIA cartesian_integrator(3, tight), model_integrator(3, tight);
  const double h = 1e-3;
  double position_difference = 0.0, velocity_difference = 0.0, multiplier_difference = 0.0;
  double largest_rod_error = 0.0;
  for (int step = 0; step < 1000; ++step) {
    cartesian_integrator.step(cartesian, cartesian_state, h);
    model_integrator.step(model, model_state, h);
    position_difference =
        std::max(position_difference, (cartesian_state.q - model_state.q.head<2>()).norm());
    velocity_difference =
        std::max(velocity_difference, (cartesian_state.v - model_state.v.head<2>()).norm());
    multiplier_difference = std::max(multiplier_difference,
                                     std::abs(cartesian_state.lambda(0) - model_state.lambda(0)));
    largest_rod_error = std::max(largest_rod_error,
                                 std::abs(cartesian_state.q.norm() - reference::kPendulumLength));
  }
  std::printf(
      "Cartesian pendulum against the model's over 1 s: |q| %.1e m, |v| %.1e m/s, "
      "|lambda| %.1e N; rod length error %.1e m\n",
      position_difference, velocity_difference, multiplier_difference, largest_rod_error);
  EXPECT_NEAR(cartesian_state.time, 1.0, 1e-12);
  EXPECT_LE(position_difference, 1e-12);
  EXPECT_LE(velocity_difference, 1e-11);
  // lambda = L / h inherits the rounding of M V / h, and Newton accepts 100 eps of that
  // (README, "Newton"): 100 eps M |q| / h^2 = 2.2e-8 N here, of a rod force up to ~30 N.
  EXPECT_LE(multiplier_difference, 1e-7);
  EXPECT_LE(largest_rod_error, 1e-13);
  // After 1 s (past the first swing through the bottom) the rod carries tension.
  EXPECT_GT(cartesian_state.lambda(0), 0.0);
  EXPECT_GT(cartesian_integrator.statistics().steps, 0u);
}

}  // namespace
}  // namespace fsi::mbd
