// White-box tests of the Radau IIA stage equations (src/radau_stage_equations.hpp): the
// analytic Newton matrix against differences of the residual, and its conditioning for the tiny
// steps of the coupled runs.
#include <gtest/gtest.h>

#include <random>

#include "element_checks.hpp"
#include "fsi/mbd/integrator.hpp"
#include "fsi/mbd/model.hpp"
#include "radau_stage_equations.hpp"
#include "test_elements.hpp"

namespace fsi::mbd {
namespace {

// Two bodies with everything the equations contain: gravity, point loads at offsets,
// a spring with analytic derivatives, a nonlinear element without, position and velocity
// constraints.
Model rich_model() {
  Model model;
  model.set_gravity({0.5, -9.81});
  RigidBody2DSpec spec = testing::rigid("a", 0.25, 5e-5);
  spec.position = {0.1, 0.2};
  spec.angle = 0.4;
  spec.velocity = {0.3, 0.0};
  spec.angular_velocity = 2.0;
  const BodyId a = model.add_rigid_body(spec);
  spec.name = "b";
  spec.position = {-0.3, 0.05};
  spec.angle = -1.2;
  spec.velocity = {0.0, -0.05};
  spec.angular_velocity = 0.0;
  const BodyId b = model.add_rigid_body(spec);
  model.add_marker(a, {0.02, -0.003});
  model.add_marker(b, {-0.025, 0.0025});
  model.set_point_loads(std::vector<double>{3.0, -8.0, -1.0, 12.0});
  model.add_force_element(
      std::make_unique<testing::LinearSpring>(model.coordinate_index(a, Coordinate::Y), 500.0));
  model.add_force_element(std::make_unique<testing::NonlinearCoupling>(
      model.coordinate_index(a, Coordinate::Angle), model.coordinate_index(b, Coordinate::X)));
  model.add_coordinate_constraint(b, Coordinate::X);
  model.add_coordinate_constraint(b, Coordinate::Angle);
  model.add_velocity_constraint(b, Coordinate::Y, -0.05);
  return model;
}

// Two bodies linked by a revolute joint, the first hanging from the ground on a rod, with a
// spring-damper to the ground: the nonlinear joints' d(G^T lambda)/dq in the Newton matrix.
Model jointed_model() {
  Model model;
  model.set_gravity({0.0, -9.81});
  RigidBody2DSpec spec = testing::rigid("upper", 0.5, 0.02);
  spec.position = {0.4, -0.3};
  spec.angle = 0.3;
  const BodyId upper = model.add_rigid_body(spec);
  spec.name = "lower";
  spec.position = {0.9, -0.6};
  spec.angle = -0.5;
  const BodyId lower = model.add_rigid_body(spec);
  model.add_distance_constraint({kGround, {0.0, 0.0}}, {upper, {-0.1, 0.05}}, 0.45);
  model.add_revolute_joint({upper, {0.2, 0.0}}, {lower, {-0.25, 0.1}});
  model.add_spring_damper({.a = {lower, {0.1, 0.0}},
                           .b = {kGround, {1.5, 0.2}},
                           .stiffness = 300.0,
                           .damping = 4.0,
                           .rest_length = 0.5});
  return model;
}

// For every tableau and both constraint forms, at a coupled and a plain step size: the Newton
// matrix against central differences of the residual, and the sparse assembly against the dense.
void expect_newton_matrix_matches_differences(const Model& model, const State& start,
                                              std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const std::pair<TableauFamily, int> tableaux[] = {{TableauFamily::RadauIIA, 1},
                                                    {TableauFamily::RadauIIA, 2},
                                                    {TableauFamily::RadauIIA, 3},
                                                    {TableauFamily::LobattoIIIA, 2},
                                                    {TableauFamily::LobattoIIIA, 3}};
  for (const auto& [family, s] : tableaux) {
    for (const auto& [form, h] :
         {std::pair{ConstraintForm::Index3, 1e-2}, std::pair{ConstraintForm::Index3, 5e-6},
          std::pair{ConstraintForm::Index2, 1e-2}, std::pair{ConstraintForm::Index2, 5e-6}}) {
      detail::RadauStageEquations equations(butcher_tableau(family, s));
      equations.set_constraint_form(form);
      equations.begin_step(model, start, h);
      Eigen::VectorXd x;
      equations.predict(x);
      for (int k = 0; k < x.size(); ++k)
        x(k) += 0.1 * u(rng) * (1.0 + std::abs(x(k)));  // away from the prediction
      Eigen::MatrixXd jacobian;
      equations.jacobian(x, jacobian);
      Eigen::VectorXd plus, minus;
      double worst = 0.0;
      const int n = model.coordinate_count();
      const int block = 2 * n + model.constraint_count();
      for (int j = 0; j < x.size(); ++j) {
        // Z moves the positions by h Z: perturb it by what moves Q by 1e-7 (1 + |q|), or the
        // rounding of q_n + h Z (~1e-17 / h) swamps the difference quotient.
        const bool is_z = j % block < n;
        const double step =
            is_z ? 1e-7 * (1.0 + start.q.lpNorm<Eigen::Infinity>()) / h + 1e-6 * std::abs(x(j))
                 : 1e-6 * (1.0 + std::abs(x(j)));
        Eigen::VectorXd probe = x;
        probe(j) += step;
        equations.residual(probe, plus);
        probe(j) -= 2.0 * step;
        equations.residual(probe, minus);
        const Eigen::VectorXd difference = (plus - minus) / (2.0 * step);
        worst = std::max(worst, (jacobian.col(j) - difference).lpNorm<Eigen::Infinity>() /
                                    (1.0 + difference.lpNorm<Eigen::Infinity>()));
      }
      EXPECT_LT(worst, 1e-7) << butcher_tableau(family, s).name << " " << s << " stages, h = " << h
                             << ", model with " << model.constraint_count()
                             << " constraints, index " << (form == ConstraintForm::Index2 ? 2 : 3);
      // The sparse assembly of the same form gives the same matrix.
      detail::RadauStageEquations sparse(butcher_tableau(family, s));
      sparse.set_constraint_form(form);
      sparse.set_sparse(true);
      sparse.begin_step(model, start, h);
      Eigen::SparseMatrix<double> sparse_jacobian;
      sparse.jacobian(x, sparse_jacobian);
      EXPECT_LE((Eigen::MatrixXd(sparse_jacobian) - jacobian).lpNorm<Eigen::Infinity>(),
                1e-12 * (1.0 + jacobian.lpNorm<Eigen::Infinity>()));
    }
  }
}

// The jointed model's state away from any solution (the Newton matrix does not care).
State inconsistent_jointed_start(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  State start;
  start.time = 0.5;
  start.q = Eigen::VectorXd::NullaryExpr(6, [&] { return u(rng); });
  start.v = Eigen::VectorXd::NullaryExpr(6, [&] { return u(rng); });
  start.lambda = Eigen::VectorXd::NullaryExpr(3, [&] { return 5.0 * u(rng); });
  return start;
}

TEST(MbdRadauStageEquations, NewtonMatrixMatchesDifferencesOfTheResidual) {
  std::mt19937 rng(11);
  const Model rich = rich_model();
  const Model jointed = jointed_model();
  State rich_start = rich.initial_state();
  rich_start.time = 0.125;
  const State jointed_start = inconsistent_jointed_start(rng);
  expect_newton_matrix_matches_differences(rich, rich_start, rng);
  expect_newton_matrix_matches_differences(jointed, jointed_start, rng);
}

// Released rows (L = 0, no G row) in every form: a held coordinate and a velocity row of the
// rich model, the revolute joint of the jointed one (its d(G^T lambda)/dq must go with it).
TEST(MbdRadauStageEquations, NewtonMatrixWithReleasedRowsMatchesDifferencesOfTheResidual) {
  std::mt19937 rng(12);
  Model rich = rich_model();
  rich.set_release_time(0, 0.1);  // b.x
  rich.set_release_time(2, 0.1);  // b's velocity row
  Model jointed = jointed_model();
  jointed.set_release_time(1, 0.2);  // the revolute joint's two rows
  jointed.set_release_time(2, 0.2);
  State rich_start = rich.initial_state();
  rich_start.time = 0.125;
  const State jointed_start = inconsistent_jointed_start(rng);
  detail::RadauStageEquations probe(butcher_tableau(TableauFamily::RadauIIA, 3));
  probe.begin_step(jointed, jointed_start, 1e-2);
  EXPECT_EQ(probe.released(), (std::vector<bool>{false, true, true}));
  expect_newton_matrix_matches_differences(rich, rich_start, rng);
  expect_newton_matrix_matches_differences(jointed, jointed_start, rng);
}

double condition_number(const Eigen::MatrixXd& matrix) {
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(matrix);
  return svd.singularValues()(0) / svd.singularValues().tail(1)(0);
}

// The unknowns (Z = (Q - q_n)/h, V, L = h Lambda) and the constraint rows divided by h keep the
// Newton matrix O(1): for small steps its condition number tends to a limit set by the mass
// ratio m/J = 5e3, instead of growing like 1/h.
TEST(MbdRadauStageEquations, NewtonMatrixStaysConditionedForTinySteps) {
  const Model model = rich_model();
  const State start = model.initial_state();
  for (int s = 1; s <= 3; ++s) {
    detail::RadauStageEquations equations(radau_iia(s));
    Eigen::VectorXd x;
    Eigen::MatrixXd jacobian;
    std::vector<double> condition;
    for (double h : {5e-5, 5e-6, 5e-7, 5e-8}) {
      equations.begin_step(model, start, h);
      equations.predict(x);
      equations.jacobian(x, jacobian);
      condition.push_back(condition_number(jacobian));
    }
    std::printf("%d stages: condition number %.3g, %.3g, %.3g, %.3g at h = 5e-5 ... 5e-8\n", s,
                condition[0], condition[1], condition[2], condition[3]);
    for (int k = 1; k < 4; ++k)
      EXPECT_LT(condition[k], 2.0 * condition[k - 1]) << s << " stages, decade " << k;
    EXPECT_LT(condition[1], 1e6) << s << " stages";
  }
}

TEST(MbdRadauStageEquations, PredictionHoldsConstrainedCoordinatesExactly) {
  const Model model = rich_model();
  const State start = model.initial_state();
  detail::RadauStageEquations equations(radau_iia(3));
  equations.begin_step(model, start, 5e-6);
  Eigen::VectorXd x, residual;
  equations.predict(x);
  equations.residual(x, residual);
  const int n = model.coordinate_count();
  const int block = 2 * n + model.constraint_count();
  for (int i = 0; i < 3; ++i) {
    EXPECT_EQ(residual.segment(i * block + 2 * n, model.constraint_count()).norm(), 0.0)
        << "stage " << i;
  }
}

}  // namespace
}  // namespace fsi::mbd
