// The sparse path of the Newton matrix (Eigen SparseLU) against the dense one: the same steps
// to round-off on a rigid chain with revolute joints and on the car axis problem, and the
// automatic choice by size; the sparse assembly (triplets from the elements' MatrixSink
// entries) against the dense one entry for entry on a model with every element type, and
// Radau runs of that model on both paths.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <random>

#include "element_checks.hpp"
#include "fsi/mbd/integrator.hpp"
#include "radau_stage_equations.hpp"
#include "reference_problems.hpp"
#include "test_elements.hpp"

namespace fsi::mbd {
namespace {

State run(const Model& model, LinearSolver solver, int steps, double h, int threshold = 300) {
  RadauIIA radau({.stages = 3,
                  .newton = {.relative_tolerance = 1e-12,
                             .max_iterations = 20,
                             .max_modified_newton_steps = 0,
                             .linear_solver = solver,
                             .sparse_threshold = threshold}});
  State state = model.initial_state();
  for (int i = 0; i < steps; ++i)
    radau.step(model, state, h);
  return state;
}

struct Difference {
  double q, v, lambda;  // max relative differences
  double lambda_absolute, lambda_floor;
};
// The multipliers are printed, not asserted: on the index-3 system they carry the rounding of
// the position rows amplified by M / h^2 (docs/theory.md), and two factorisations round
// differently (measured: car axis 1.7e-10 N, below the floor; chain of 20 bars 1.1e-8 N, 2.5x the
// single-body floor, the root joint carrying all 20 bars).
// lambda_floor: the round-off floor of the multipliers on the index-3 system,
// 100 eps max(M) |q| / h^2, which Newton's convergence test grants them (docs/theory.md).
Difference relative_difference(const Model& model, const State& a, const State& b, double h) {
  const double lambda = (a.lambda - b.lambda).lpNorm<Eigen::Infinity>();
  return {(a.q - b.q).lpNorm<Eigen::Infinity>() / a.q.lpNorm<Eigen::Infinity>(),
          (a.v - b.v).lpNorm<Eigen::Infinity>() / a.v.lpNorm<Eigen::Infinity>(),
          lambda / a.lambda.lpNorm<Eigen::Infinity>(), lambda,
          100.0 * std::numeric_limits<double>::epsilon() * model.mass_matrix().maxCoeff() *
              a.q.lpNorm<Eigen::Infinity>() / (h * h)};
}

// Runs `model` on the dense and on the sparse path and prints how far apart they end, with how
// far the model moved (a run that stood still would agree trivially); `run_name` names the run.
Difference dense_sparse_difference(const Model& model, int steps, double h, const char* run_name) {
  const State dense = run(model, LinearSolver::Dense, steps, h);
  const State sparse = run(model, LinearSolver::Sparse, steps, h);
  const Difference d = relative_difference(model, dense, sparse, h);
  std::printf(
      "%s: max relative difference sparse - dense: q %.1e, v %.1e, lambda %.1e (%.1e N, floor "
      "%.1e N; moved up to %.3f)\n",
      run_name, d.q, d.v, d.lambda, d.lambda_absolute, d.lambda_floor,
      (dense.q - model.initial_state().q).lpNorm<Eigen::Infinity>());
  return d;
}

TEST(MbdSparseNewton, ChainOf20BarsSameAsDenseToRoundOff) {
  const Model chain = reference::rigid_chain(20);  // Newton matrix 3 x (2 x 60 + 40) = 480
  const Difference d =
      dense_sparse_difference(chain, 20, 1e-3, "chain of 20 bars, 20 steps of 1 ms");
  EXPECT_LT(d.q, 1e-13);
  EXPECT_LT(d.v, 1e-11);
}

TEST(MbdSparseNewton, CarAxisSameAsDenseToRoundOff) {
  const auto problem = reference::car_axis::make();
  const Difference d =
      dense_sparse_difference(problem.model, 2000, 1e-4, "car axis, 2000 steps of 1e-4");
  EXPECT_LT(d.q, 1e-13);
  EXPECT_LT(d.v, 1e-11);
}

TEST(MbdSparseNewton, AutomaticChoiceFollowsTheThreshold) {
  const Model chain = reference::rigid_chain(3);  // Newton matrix 3 x (18 + 6) = 72
  const State dense = run(chain, LinearSolver::Dense, 10, 1e-3);
  // Both automatic runs give the dense (threshold above) or the sparse (below) result.
  const State automatic_dense = run(chain, LinearSolver::Automatic, 10, 1e-3, 73);
  const State automatic_sparse = run(chain, LinearSolver::Automatic, 10, 1e-3, 72);
  const State sparse = run(chain, LinearSolver::Sparse, 10, 1e-3);
  EXPECT_EQ(automatic_dense.q, dense.q);
  EXPECT_EQ(automatic_sparse.q, sparse.q);
}

// A user row that only offers the dense interface (the model's dense fallback): the beam tip's
// height plus the hanging body's angle, held, with a q-dependent G so that its
// add_force_derivative is not zero: C = y_tip + sin(phi) - value.
class UserRow final : public ConstraintElement {
 public:
  UserRow(int y, int angle, double value) : y_(y), angle_(angle), value_(value) {}
  std::string description() const override { return "user row"; }
  ConstraintLevel level() const override { return ConstraintLevel::Position; }
  double residual(double, const Eigen::VectorXd& q, const Eigen::VectorXd&) const override {
    return q(y_) + std::sin(q(angle_)) - value_;
  }
  void jacobian_row(double, const Eigen::VectorXd& q, RowRef row) const override {
    row(y_) = 1.0;
    row(angle_) = std::cos(q(angle_));
  }
  double explicit_time_derivative(double, const Eigen::VectorXd&) const override { return 0.0; }
  double acceleration_remainder(double, const Eigen::VectorXd& q,
                                const Eigen::VectorXd& v) const override {
    return -std::sin(q(angle_)) * v(angle_) * v(angle_);
  }
  void add_force_derivative(double, const Eigen::VectorXd& q, double multiplier,
                            Eigen::MatrixXd& derivative) const override {
    derivative(angle_, angle_) -= multiplier * std::sin(q(angle_));
  }

 private:
  int y_, angle_;
  double value_;
};

// Every element type at a consistent initial state: a cantilever beam (clamp) with loaded face
// markers, a body hanging from its tip (revolute joint on the beam) with a clamped partner, a
// piston on a prismatic guide driven at constant velocity, a rod (distance constraint), a
// pendulum pinned to the ground, held coordinates, springs (linear, rotational, nonlinear user
// law, spring actor), a point force, a torque, and user elements with dense interfaces only
// (force elements with and without derivatives, a constraint row).
Model every_element_model(int beam_elements) {
  Model model;
  model.set_gravity({0.0, -9.81});
  AncfBeamSpec beam;
  beam.name = "beam";
  beam.start = {0.0, 0.0};
  beam.end = {1.0, 0.0};
  beam.element_count = beam_elements;
  beam.axial_stiffness = 1e6;
  beam.bending_stiffness = 50.0;
  beam.mass_per_length = 2.0;
  beam.axial_damping = 10.0;
  beam.bending_damping = 0.05;
  const BodyId b = model.add_ancf_beam(beam);
  model.add_beam_clamp(b, 0);
  auto body = [&](const std::string& name, Eigen::Vector2d position, double angle) {
    RigidBody2DSpec spec;
    spec.name = name;
    spec.mass = 0.4;
    spec.inertia = 0.003;
    spec.position = position;
    spec.angle = angle;
    return model.add_rigid_body(spec);
  };
  const BodyId hanging = body("hanging", {1.0, -0.2}, 0.0);
  model.add_revolute_joint({b, {1.0, 0.0}}, {hanging, {0.0, 0.2}}, "tip");
  const BodyId partner = body("partner", {1.2, -0.2}, 0.0);
  model.add_clamp({.name = "weld", .body = partner, .to = hanging});
  RigidBody2DSpec piston_spec;
  piston_spec.name = "piston";
  piston_spec.mass = 0.3;
  piston_spec.inertia = 0.002;
  piston_spec.position = {2.0, -0.2};
  piston_spec.velocity = {0.0, 0.1};
  const BodyId piston = model.add_rigid_body(piston_spec);
  model.add_prismatic_joint(
      {.name = "guide", .a = {kGround, {2.0, 0.0}}, .b = {piston, {0.0, 0.0}}, .axis = {0.0, 1.0}});
  model.add_velocity_constraint(piston, Coordinate::Y, 0.1);
  model.add_distance_constraint({partner, {0.3, 0.0}}, {piston, {0.0, 0.0}}, std::nullopt, "rod");
  // Pinned at (-0.5, 0) by its body point (0, 0.3), at an angle.
  const double swing = 0.7;
  const Eigen::Vector2d pin = Eigen::Rotation2Dd(swing) * Eigen::Vector2d(0.0, 0.3);
  const BodyId pendulum = body("pendulum", Eigen::Vector2d(-0.5, 0.0) - pin, swing);
  model.add_revolute_joint({pendulum, {0.0, 0.3}}, {kGround, {-0.5, 0.0}});
  const BodyId held = body("held", {-1.0, 0.5}, 0.2);
  model.add_coordinate_constraint(held, Coordinate::X);
  model.add_coordinate_constraint(held, Coordinate::Angle);
  model.add_constraint_element(
      std::make_unique<UserRow>(model.coordinate_index(held, Coordinate::Y),
                                model.coordinate_index(hanging, Coordinate::Angle), 0.5));

  model.add_spring_damper({.a = {pendulum, {0.1, -0.2}},
                           .b = {b, {0.5, 0.01}},
                           .stiffness = 200.0,
                           .damping = 1.5,
                           .rest_length = std::nullopt});
  model.add_rotational_spring_damper(
      {.name = "hinge spring", .a = pendulum, .b = held, .stiffness = 3.0, .damping = 0.1});
  model.add_nonlinear_spring_damper({.name = "rubber",
                                     .a = {held, {0.1, 0.0}},
                                     .b = {b, {0.8, -0.01}},
                                     .tension = [](double s, double rate, double) {
                                       return 50.0 * s + 400.0 * s * s * s + 2.0 * rate;
                                     }});
  model.add_spring_actor({.name = "actor",
                          .a = {hanging, {0.05, 0.0}},
                          .b = {kGround, {1.0, -1.0}},
                          .characteristic = {{-0.1, -30.0}, {0.0, 0.0}, {0.1, 5.0}},
                          .damping = 0.5});
  model.add_point_force({.name = "push", .point = {partner, {0.1, 0.05}}, .force = [](double t) {
                           return Eigen::Vector2d(0.5 + t, -0.2);
                         }});
  model.add_torque({.name = "motor", .body = pendulum, .torque = [](double t) { return 0.1 * t; }});
  model.add_force_element(
      std::make_unique<testing::LinearSpring>(model.coordinate_index(held, Coordinate::Y), 30.0));
  model.add_force_element(std::make_unique<testing::NonlinearCoupling>(
      model.coordinate_index(pendulum, Coordinate::Angle),
      model.coordinate_index(hanging, Coordinate::X)));
  model.add_marker(b, {0.3, 0.01});
  model.add_marker(b, {0.7, -0.01});
  model.add_marker(hanging, {0.05, -0.1});
  model.add_marker(kGround, {0.0, 1.0});
  model.set_point_loads(std::vector<double>{1.0, -2.0, -0.5, 3.0, 0.7, 0.2, 9.0, 9.0});
  return model;
}

TEST(MbdSparseAssembly, NewtonMatrixEqualsTheDenseOneEntryForEntry) {
  const Model model = every_element_model(6);
  State start = model.initial_state();
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> noise(-1.0, 1.0);
  for (Eigen::Index k = 0; k < start.q.size(); ++k) {
    start.q(k) += 0.02 * noise(rng);
    start.v(k) += 0.5 * noise(rng);
  }
  for (Eigen::Index k = 0; k < start.lambda.size(); ++k)
    start.lambda(k) += noise(rng);
  for (const auto& [family, stages] :
       {std::pair{TableauFamily::RadauIIA, 3}, std::pair{TableauFamily::RadauIIA, 1},
        std::pair{TableauFamily::LobattoIIIA, 3}}) {
    const double h = 1e-3;
    detail::RadauStageEquations dense(butcher_tableau(family, stages));
    detail::RadauStageEquations sparse(butcher_tableau(family, stages));
    sparse.set_sparse(true);
    dense.begin_step(model, start, h);
    sparse.begin_step(model, start, h);
    Eigen::VectorXd unknowns;
    dense.predict(unknowns);
    for (Eigen::Index k = 0; k < unknowns.size(); ++k)
      unknowns(k) += 0.1 * noise(rng);
    Eigen::MatrixXd dense_matrix;
    Eigen::SparseMatrix<double> sparse_matrix;
    dense.jacobian(unknowns, dense_matrix);
    sparse.jacobian(unknowns, sparse_matrix);
    const Eigen::MatrixXd from_sparse(sparse_matrix);
    ASSERT_EQ(from_sparse.rows(), dense_matrix.rows());
    ASSERT_EQ(from_sparse.cols(), dense_matrix.cols());
    int entries = 0, worst_row = -1, worst_column = -1;
    double worst = 0.0;
    for (Eigen::Index j = 0; j < dense_matrix.cols(); ++j) {
      for (Eigen::Index i = 0; i < dense_matrix.rows(); ++i) {
        const double expected = dense_matrix(i, j);
        if (expected != 0.0) ++entries;
        const double error = std::abs(from_sparse(i, j) - expected) /
                             std::max(std::abs(expected), std::numeric_limits<double>::min());
        if (error > worst) {
          worst = error;
          worst_row = static_cast<int>(i);
          worst_column = static_cast<int>(j);
        }
      }
    }
    std::printf(
        "%d stages: %d non-zeros of %lld, sparse holds %lld; worst relative difference "
        "%.1e at (%d, %d)\n",
        stages, entries, static_cast<long long>(dense_matrix.size()),
        static_cast<long long>(sparse_matrix.nonZeros()), worst, worst_row, worst_column);
    EXPECT_LE(worst, 1e-12) << "entry (" << worst_row << ", " << worst_column << "): dense "
                            << dense_matrix(worst_row, worst_column) << ", sparse "
                            << from_sparse(worst_row, worst_column);
    EXPECT_EQ(sparse_matrix.nonZeros(), entries);  // exact zeros are not stored

    // The residuals with sparse and dense M and G, and the convergence measure (its rounding
    // terms come from the sparse or the dense dF/dq, dF/dv).
    Eigen::VectorXd dense_residual, sparse_residual;
    dense.residual(unknowns, dense_residual);
    sparse.residual(unknowns, sparse_residual);
    EXPECT_LE((dense_residual - sparse_residual).lpNorm<Eigen::Infinity>(),
              1e-13 * dense_residual.lpNorm<Eigen::Infinity>());
    Eigen::VectorXd increment(unknowns.size());
    for (Eigen::Index k = 0; k < increment.size(); ++k)
      increment(k) = 1e-9 * noise(rng);
    const NewtonOptions options;
    const double dense_norm = dense.increment_norm(unknowns, increment, options);
    EXPECT_NEAR(sparse.increment_norm(unknowns, increment, options), dense_norm,
                1e-12 * dense_norm);
  }
}

TEST(MbdSparseAssembly, ModelMatricesEqualTheDenseOnes) {
  const Model model = every_element_model(4);
  testing::expect_sparse_model_matrices_equal(model, model.initial_state());
}

TEST(MbdSparseAssembly, RadauRunsOfEveryElementAgreeOnBothPaths) {
  const Model model = every_element_model(8);
  const Difference d = dense_sparse_difference(model, 40, 1e-3, "every element, 40 steps of 1 ms");
  EXPECT_LT(d.q, 1e-12);
  EXPECT_LT(d.v, 1e-10);
}

}  // namespace
}  // namespace fsi::mbd
