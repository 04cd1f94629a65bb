#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

#include "element_checks.hpp"
#include "fsi/common/error.hpp"
#include "fsi/mbd/integrator.hpp"
#include "fsi/mbd/model.hpp"
#include "fsi/mbd/readouts.hpp"
#include "reference_problems.hpp"
#include "test_elements.hpp"

namespace fsi::mbd {
namespace {

using reference::fitted_order;

constexpr NewtonOptions kTight{.relative_tolerance = 1e-13, .max_iterations = 20};

// x'' = -x, x(0) = 1: error of (x, v) at t = 1 against (cos 1, -sin 1).
double oscillator_error(int stages, int steps) {
  Model model;
  RigidBody2DSpec spec = testing::rigid("mass", 1.0, 1.0);
  spec.position = {1.0, 0.0};
  const BodyId b = model.add_rigid_body(spec);
  model.add_force_element(
      std::make_unique<testing::LinearSpring>(model.coordinate_index(b, Coordinate::X), 1.0));
  RadauIIA integrator(stages, kTight);
  State state = model.initial_state();
  for (int i = 0; i < steps; ++i)
    integrator.step(model, state, 1.0 / steps);
  return std::max(std::abs(state.q(0) - std::cos(1.0)), std::abs(state.v(0) + std::sin(1.0)));
}

TEST(MbdRadauIIA, ObservedOrdersOnTheHarmonicOscillatorAre1And3And5) {
  const int first_steps[] = {0, 32, 4, 2};
  for (int s = 1; s <= 3; ++s) {
    std::vector<double> steps, errors;
    for (int halving = 0; halving < 4; ++halving) {
      const int count = first_steps[s] << halving;
      steps.push_back(1.0 / count);
      errors.push_back(oscillator_error(s, count));
    }
    const double order = fitted_order(steps, errors);
    std::printf("oscillator, %d stages: errors %.2e .. %.2e, fitted order %.2f\n", s, errors[0],
                errors[3], order);
    EXPECT_NEAR(order, 2 * s - 1, 0.3) << s << " stages";
  }
}

TEST(MbdRadauIIA, FreeFallFollowsTheParabola) {
  const double g = -9.81;
  for (int s = 1; s <= 3; ++s) {
    Model model;
    RigidBody2DSpec spec = testing::rigid("stone", 1.0, 1.0);
    spec.position = {0.5, 10.0};
    spec.velocity = {1.0, 2.0};
    spec.angular_velocity = 3.0;
    model.add_rigid_body(spec);
    model.set_gravity({0.0, g});
    RadauIIA integrator(s);
    State state = model.initial_state();
    const double h = 0.01;
    for (int i = 0; i < 100; ++i)
      integrator.step(model, state, h);
    const double t = 1.0;
    // Collocation with s >= 2 is exact for the quadratic; implicit Euler (s = 1) integrates
    // v exactly and then sums q_n+1 = q_n + h v_n+1, which adds g t h / 2.
    const double euler_offset = s == 1 ? 0.5 * g * t * h : 0.0;
    EXPECT_NEAR(state.time, t, 1e-14);
    EXPECT_NEAR(state.q(0), 0.5 + t, 1e-13) << s;
    EXPECT_NEAR(state.q(1), 10.0 + 2.0 * t + 0.5 * g * t * t + euler_offset, 1e-12) << s;
    EXPECT_NEAR(state.q(2), 3.0 * t, 1e-13) << s;
    EXPECT_NEAR(state.v(0), 1.0, 1e-14) << s;
    EXPECT_NEAR(state.v(1), 2.0 + g * t, 1e-12) << s;
    EXPECT_NEAR(state.v(2), 3.0, 1e-14) << s;
  }
}

void expect_relative(double actual, double expected, double tolerance, const std::string& what) {
  ASSERT_LE(std::abs(actual - expected), tolerance * std::abs(expected)) << what;
}

// The coupled run weighs the fluid through the multipliers of a held body (thesis §6.3): at
// every step -(constraint force) = gravity + generalised point load, to 1e-10 relative.
TEST(MbdRadauIIA, HeldBodyMultipliersBalanceGravityAndPointLoadsAtEveryStep) {
  for (int s = 1; s <= 3; ++s) {
    Model model;
    RigidBody2DSpec spec = testing::rigid("bottom", 0.25, 5e-5);
    spec.position = {0.025, 0.0};
    spec.angle = 0.3;
    const BodyId b = model.add_rigid_body(spec);
    model.set_gravity({0.0, -9.81});
    model.add_marker(b, {-0.02, 0.0025});
    model.add_marker(b, {0.025, 0.0025});
    for (Coordinate c : {Coordinate::X, Coordinate::Y, Coordinate::Angle})
      model.add_coordinate_constraint(b, c);
    RadauIIA integrator(s);
    State state = model.initial_state();
    const State start = state;
    std::mt19937 rng(2);
    std::uniform_real_distribution<double> load(-12.0, 2.0);
    std::vector<double> loads{1.5, -10.0, 0.0, 0.0};  // constant load at an offset point first
    for (int i = 0; i < 400; ++i) {
      if (i >= 200) loads = {0.1 * load(rng), load(rng), 0.1 * load(rng), load(rng)};
      model.set_point_loads(loads);
      integrator.step(model, state, 5e-6);
      const std::string where = std::to_string(s) + " stages, step " + std::to_string(i);
      for (int j = 0; j < 3; ++j) {
        // Bit-identical for the non-zero coordinates; the held y = 0 may pick up 1e-40-ish
        // rounding from the LU back substitution.
        ASSERT_NEAR(state.q(j), start.q(j), 1e-30) << where << ", coordinate " << j;
        ASSERT_LE(std::abs(state.v(j)), 1e-20) << where << ", coordinate " << j;
      }
      const Eigen::Vector3d loads_on_body = point_load_resultant(model, state, b).planar();
      const Eigen::Vector3d gravity(0.0, -9.81 * spec.mass, 0.0);
      const Eigen::VectorXd held = -generalised_constraint_force(model, state);
      for (int j = 0; j < 3; ++j)
        expect_relative(held(j), gravity(j) + loads_on_body(j), 1e-10,
                        where + ", component " + std::to_string(j));
    }
    EXPECT_LE(position_constraint_drift(model, state), 1e-30);
    EXPECT_LE(velocity_constraint_drift(model, state), 1e-20);
  }
}

// Q_i += amplitude sin(omega t): a load that changes within a step.
class OscillatingLoad final : public ForceElement {
 public:
  OscillatingLoad(int coordinate, double amplitude, double omega)
      : coordinate_(coordinate), amplitude_(amplitude), omega_(omega) {}
  void add_force(double time, const Eigen::VectorXd&, const Eigen::VectorXd&,
                 Eigen::VectorXd& force) const override {
    force(coordinate_) += amplitude_ * std::sin(omega_ * time);
  }

 private:
  int coordinate_;
  double amplitude_;
  double omega_;
};

// Stiffly accurate: lambda_n+1 is the multiplier of the last stage, t_n+1, not of an earlier
// stage; for a held body it balances the applied force at exactly that time.
TEST(MbdRadauIIA, MultipliersBelongToTheEndOfTheStep) {
  for (int s = 1; s <= 3; ++s) {
    Model model;
    const BodyId b = model.add_rigid_body(testing::rigid("held", 1.0, 1.0));
    model.add_coordinate_constraint(b, Coordinate::Y);
    const int y = model.coordinate_index(b, Coordinate::Y);
    model.add_force_element(std::make_unique<OscillatingLoad>(y, 3.0, 40.0));
    RadauIIA integrator(s);
    State state = model.initial_state();
    for (int i = 0; i < 50; ++i) {
      integrator.step(model, state, 1e-3);
      const double expected = 3.0 * std::sin(40.0 * state.time);
      ASSERT_NEAR(-constraint_force(model, state, b, Coordinate::Y), expected, 1e-12)
          << s << " stages, t = " << state.time;
    }
  }
}

// The piston of thesis §6.3: x and angle held, dy/dt = v0 prescribed. It moves at exactly v0,
// and the constraint force is what keeps it from accelerating under gravity and the load.
TEST(MbdRadauIIA, VelocityConstraintDrivesTheBodyAtThePrescribedVelocity) {
  for (int s = 1; s <= 3; ++s) {
    Model model;
    RigidBody2DSpec spec = testing::rigid("piston", 0.1, 2e-5);
    spec.position = {0.025, 0.0725};
    spec.velocity = {0.0, -0.05};
    const BodyId b = model.add_rigid_body(spec);
    model.set_gravity({0.0, -9.81});
    model.add_marker(b, {0.01, -0.0025});
    model.set_point_loads(std::vector<double>{0.5, 3.0});
    model.add_coordinate_constraint(b, Coordinate::X);
    model.add_coordinate_constraint(b, Coordinate::Angle);
    model.add_velocity_constraint(b, Coordinate::Y, -0.05);
    RadauIIA integrator(s);
    State state = model.initial_state();
    const double h = 5e-6;
    for (int i = 1; i <= 1000; ++i) {
      integrator.step(model, state, h);
      const std::string where = std::to_string(s) + " stages, step " + std::to_string(i);
      // Round-off of q_n + h v summed over the steps: ~eps |q| per step at most.
      ASSERT_NEAR(state.q(1), 0.0725 - 0.05 * i * h, 1e-14) << where;
      ASSERT_NEAR(state.v(1), -0.05, 1e-17) << where;
      ASSERT_EQ(state.q(0), 0.025) << where;
      ASSERT_EQ(state.q(2), 0.0) << where;
      const Eigen::Vector3d load = point_load_resultant(model, state, b).planar();
      expect_relative(constraint_force(model, state, b, Coordinate::Y), 0.1 * 9.81 - load(1), 1e-10,
                      where + ", y");
      expect_relative(constraint_force(model, state, b, Coordinate::X), -load(0), 1e-10,
                      where + ", x");
      expect_relative(constraint_force(model, state, b, Coordinate::Angle), -load(2), 1e-10,
                      where + ", torque");
    }
    EXPECT_LE(velocity_constraint_drift(model, state), 1e-17);
  }
}

// A free body under a constant world-frame load at a body-fixed point: the torque depends on
// the angle nonlinearly, the body spins and swings. Final state after 2 s.
State rotating_body(int stages, int steps, const NewtonOptions& options = kTight,
                    IntegratorStatistics* statistics = nullptr) {
  Model model;
  RigidBody2DSpec spec = testing::rigid("rotor", 1.0, 0.2);
  spec.angle = 0.3;
  spec.angular_velocity = 3.0;
  spec.velocity = {0.2, 0.0};
  const BodyId b = model.add_rigid_body(spec);
  model.add_marker(b, {1.0, 0.5});
  model.set_point_loads(std::vector<double>{0.3, -1.0});
  RadauIIA integrator(stages, options);
  State state = model.initial_state();
  for (int i = 0; i < steps; ++i)
    integrator.step(model, state, 2.0 / steps);
  if (statistics != nullptr) *statistics = integrator.statistics();
  return state;
}

double state_distance(const State& a, const State& b) {
  return std::max((a.q - b.q).lpNorm<Eigen::Infinity>(), (a.v - b.v).lpNorm<Eigen::Infinity>());
}

TEST(MbdRadauIIA, ObservedOrdersOnANonlinearRotationAre1And3And5) {
  const State reference = rotating_body(3, 2048);
  const int first_steps[] = {0, 128, 32, 16};
  for (int s = 1; s <= 3; ++s) {
    std::vector<double> steps, errors;
    for (int halving = 0; halving < 4; ++halving) {
      const int count = first_steps[s] << halving;
      steps.push_back(2.0 / count);
      errors.push_back(state_distance(rotating_body(s, count), reference));
    }
    const double order = fitted_order(steps, errors);
    std::printf("rotating body, %d stages: errors %.2e .. %.2e, fitted order %.2f\n", s, errors[0],
                errors[3], order);
    EXPECT_NEAR(order, 2 * s - 1, 0.3) << s << " stages";
  }
}

TEST(MbdRadauIIA, ModifiedNewtonKeepsTheFactorisationAndAgreesWithFullNewton) {
  IntegratorStatistics modified, full, refreshed;
  const State with_modified = rotating_body(
      3, 64, {.relative_tolerance = 1e-12, .max_iterations = 20, .max_modified_newton_steps = 20},
      &modified);
  const State with_full = rotating_body(
      3, 64, {.relative_tolerance = 1e-12, .max_iterations = 20, .max_modified_newton_steps = 0},
      &full);
  // Reuse allowed for the whole run, but a demanding contraction threshold: only the
  // contraction test can ask for new matrices.
  const State with_refreshed = rotating_body(3, 64,
                                             {.relative_tolerance = 1e-12,
                                              .max_iterations = 20,
                                              .max_modified_newton_steps = 1000000,
                                              .max_contraction = 1e-3},
                                             &refreshed);
  EXPECT_LE(state_distance(with_modified, with_full), 1e-10);
  EXPECT_LE(state_distance(with_refreshed, with_full), 1e-10);
  EXPECT_EQ(full.factorisations, full.newton_iterations);
  EXPECT_EQ(full.jacobian_evaluations, full.factorisations);
  EXPECT_LT(modified.factorisations, modified.steps);
  EXPECT_GT(refreshed.factorisations, 1u) << "slow contraction must trigger new matrices";
  std::printf("64 steps: full Newton %llu iterations / %llu factorisations, modified %llu / %llu\n",
              static_cast<unsigned long long>(full.newton_iterations),
              static_cast<unsigned long long>(full.factorisations),
              static_cast<unsigned long long>(modified.newton_iterations),
              static_cast<unsigned long long>(modified.factorisations));
}

// A spring that stiffens 10^4-fold at t = 0.5: the Newton matrix kept from the steps before is
// useless after the switch.
class SwitchingSpring final : public ForceElement {
 public:
  explicit SwitchingSpring(int coordinate) : coordinate_(coordinate) {}
  double stiffness(double time) const { return time < 0.5 ? 1.0 : 1e4; }
  void add_force(double time, const Eigen::VectorXd& q, const Eigen::VectorXd&,
                 Eigen::VectorXd& force) const override {
    force(coordinate_) -= stiffness(time) * q(coordinate_);
  }
  bool add_jacobians(double time, const Eigen::VectorXd&, const Eigen::VectorXd&,
                     Eigen::MatrixXd& by_position, Eigen::MatrixXd&) const override {
    by_position(coordinate_, coordinate_) -= stiffness(time);
    return true;
  }

 private:
  int coordinate_;
};

TEST(MbdRadauIIA, AMatrixThatStopsContractingIsReplacedWithinTheStep) {
  Model model;
  RigidBody2DSpec spec = testing::rigid("mass", 1.0, 1.0);
  spec.position = {1.0, 0.0};
  const BodyId b = model.add_rigid_body(spec);
  model.add_force_element(
      std::make_unique<SwitchingSpring>(model.coordinate_index(b, Coordinate::X)));
  RadauIIA integrator(2, {.max_modified_newton_steps = 1000});
  State state = model.initial_state();
  for (int i = 0; i < 50; ++i)
    integrator.step(model, state, 0.01);
  EXPECT_EQ(integrator.statistics().factorisations, 1u) << "kept while the spring is soft";
  const StepStatistics switching = integrator.step(model, state, 0.01);  // stages beyond 0.5
  EXPECT_EQ(switching.retries, 0) << "refreshed at the current iterate, not restarted";
  EXPECT_EQ(switching.factorisations, 1);
  EXPECT_LE(switching.newton_iterations, 4);
}

TEST(MbdRadauIIA, StatisticsAccumulateThePerStepCounts) {
  Model model;
  model.add_rigid_body(testing::rigid("b", 1.0, 1.0));
  model.set_gravity({0.0, -1.0});
  RadauIIA integrator(2);
  State state = model.initial_state();
  StepStatistics sum;
  for (int i = 0; i < 30; ++i) {
    const StepStatistics step = integrator.step(model, state, 0.01);
    EXPECT_GE(step.newton_iterations, 1);
    sum.newton_iterations += step.newton_iterations;
    sum.jacobian_evaluations += step.jacobian_evaluations;
    sum.factorisations += step.factorisations;
  }
  const IntegratorStatistics& total = integrator.statistics();
  EXPECT_EQ(total.steps, 30u);
  EXPECT_EQ(total.newton_iterations, static_cast<std::uint64_t>(sum.newton_iterations));
  EXPECT_EQ(total.jacobian_evaluations, static_cast<std::uint64_t>(sum.jacobian_evaluations));
  EXPECT_EQ(total.factorisations, static_cast<std::uint64_t>(sum.factorisations));
  EXPECT_EQ(total.factorisations, 2u) << "one factorisation per 20 steps of a linear problem";
}

std::string failure_of(RadauIIA& integrator, const Model& model, State& state, double h) {
  try {
    integrator.step(model, state, h);
  } catch (const fsi::Error& error) {
    return error.what();
  }
  return "(no fsi::Error thrown)";
}

TEST(MbdRadauIIA, NonConvergingNewtonNamesTimeStepSizeAndResidual) {
  Model model;
  RigidBody2DSpec spec = testing::rigid("rotor", 1.0, 1.0);
  spec.angular_velocity = 3.0;
  const BodyId b = model.add_rigid_body(spec);
  model.add_marker(b, {1.0, 0.0});
  model.set_point_loads(std::vector<double>{0.0, -1.0});
  State state = model.initial_state();
  RadauIIA good(3);
  good.step(model, state, 0.1);
  good.step(model, state, 0.1);
  RadauIIA hasty(3, {.max_iterations = 1});
  const State before = state;
  const std::string text = failure_of(hasty, model, state, 0.1);
  EXPECT_NE(text.find("failed at t = 0.2 s with step size 0.1 s"), std::string::npos) << text;
  EXPECT_NE(text.find("no convergence within the iteration limit"), std::string::npos) << text;
  EXPECT_NE(text.find("residual of the scaled stage equations"), std::string::npos) << text;
  EXPECT_NE(text.find("reduce the step size"), std::string::npos) << text;
  EXPECT_EQ(state.time, before.time);
  EXPECT_EQ(state.q, before.q);
  EXPECT_EQ(state.v, before.v);
}

class NotANumberLater final : public ForceElement {
 public:
  void add_force(double time, const Eigen::VectorXd&, const Eigen::VectorXd&,
                 Eigen::VectorXd& force) const override {
    if (time > 0.25) force(0) = std::nan("");
  }
  bool add_jacobians(double, const Eigen::VectorXd&, const Eigen::VectorXd&, Eigen::MatrixXd&,
                     Eigen::MatrixXd&) const override {
    return true;
  }
};

TEST(MbdRadauIIA, NonFiniteForcesAreAnErrorAtTheirTime) {
  Model model;
  model.add_rigid_body(testing::rigid("b", 1.0, 1.0));
  model.add_force_element(std::make_unique<NotANumberLater>());
  RadauIIA integrator(3);
  State state = model.initial_state();
  integrator.step(model, state, 0.1);
  integrator.step(model, state, 0.1);
  const State before = state;
  const std::string text = failure_of(integrator, model, state, 0.1);
  EXPECT_NE(text.find("failed at t = 0.2 s with step size 0.1 s"), std::string::npos) << text;
  EXPECT_NE(text.find("not finite"), std::string::npos) << text;
  EXPECT_EQ(state.time, before.time);
  EXPECT_EQ(state.q, before.q);
}

TEST(MbdRadauIIA, InvalidInputIsAUserError) {
  EXPECT_THROW(RadauIIA(3, {.relative_tolerance = 0.0}), fsi::Error);
  EXPECT_THROW(RadauIIA(3, {.max_iterations = 0}), fsi::Error);
  EXPECT_THROW(RadauIIA(RadauOptions{.stages = 4, .newton = {}}), fsi::Error);
  Model model;
  model.add_rigid_body(testing::rigid("b", 1.0, 1.0));
  RadauIIA integrator(2);
  State state = model.initial_state();
  EXPECT_NE(failure_of(integrator, model, state, 0.0).find("step size must be positive"),
            std::string::npos);
  State wrong = state;
  wrong.lambda = Eigen::VectorXd::Zero(2);
  EXPECT_NE(failure_of(integrator, model, wrong, 0.1).find("does not match the model"),
            std::string::npos);
}

}  // namespace
}  // namespace fsi::mbd
