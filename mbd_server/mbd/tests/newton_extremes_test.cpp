// Newton at the extremes (issue 15, item 4): a stiff closed-loop mechanism at microsecond steps
// with a tight tolerance, where the residual reaches round-off long before the scaled increment
// can pass the tolerance; and the advice of a failed iteration (docs/theory.md, "Newton
// convergence test").
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "error_message.hpp"
#include "fsi/mbd/force_element.hpp"
#include "fsi/mbd/integrator.hpp"
#include "fsi/mbd/model.hpp"
#include "fsi/mbd/readouts.hpp"
#include "newton_convergence.hpp"

namespace fsi::mbd {
namespace {

// Five links closed into a loop through two ground pivots 1 m apart, almost stretched straight
// (the joints zigzag by 1 mm: near the loop's singular, fully stretched configuration, where the
// Newton matrix amplifies rounding by ~1/sin 0.01), the middle link a million times heavier than
// the others (1e6 kg against 1 kg), and a 1e9 N/m spring stretched by 0.1 mm between the second
// and the fourth link; gravity. Three degrees of freedom.
struct StiffLoop {
  Model model;
  std::vector<BodyId> links;
};

StiffLoop stiff_closed_loop() {
  constexpr double zigzag = 1e-3;
  const std::vector<Eigen::Vector2d> joints = {{0.0, 0.0},    {0.2, zigzag},  {0.4, -zigzag},
                                               {0.6, zigzag}, {0.8, -zigzag}, {1.0, 0.0}};
  const double masses[] = {1.0, 2.0, 1e6, 1.5, 1.0};
  StiffLoop loop;
  loop.model.set_gravity({0.0, -9.81});
  std::vector<double> half_lengths;
  for (int k = 0; k < 5; ++k) {
    const Eigen::Vector2d from = joints[k], to = joints[k + 1];
    const double length = (to - from).norm();
    half_lengths.push_back(0.5 * length);
    RigidBody2DSpec spec;
    spec.name = "link" + std::to_string(k + 1);
    spec.mass = masses[k];
    spec.inertia = masses[k] * length * length / 12.0;
    spec.position = 0.5 * (from + to);
    spec.angle = std::atan2(to.y() - from.y(), to.x() - from.x());
    loop.links.push_back(loop.model.add_rigid_body(spec));
  }
  auto end_of = [&](int k, double side) {
    return BodyPointSpec{loop.links[k], {side * half_lengths[k], 0.0}};
  };
  loop.model.add_revolute_joint(end_of(0, -1.0), {kGround, joints[0]}, "O1");
  for (int k = 0; k < 4; ++k) {
    loop.model.add_revolute_joint(end_of(k, 1.0), end_of(k + 1, -1.0), "J" + std::to_string(k + 1));
  }
  loop.model.add_revolute_joint(end_of(4, 1.0), {kGround, joints[5]}, "O2");
  const double spring_length = 0.4;  // between the centres of links 2 and 4
  loop.model.add_spring_damper({.a = {loop.links[1], {0.0, 0.0}},
                                .b = {loop.links[3], {0.0, 0.0}},
                                .stiffness = 1e9,
                                .damping = 0.0,
                                .rest_length = spring_length - 1e-4});
  return loop;
}

struct LoopRun {
  State state;
  IntegratorStatistics statistics;
  std::string failure;
};

LoopRun integrate(const Model& model, TableauFamily family, double step_size, double end_time) {
  RadauOptions options;
  options.family = family;
  options.stages = 3;
  options.newton.relative_tolerance = 1e-12;
  RadauIIA integrator(options);
  LoopRun run{model.initial_state(), {}, {}};
  const int steps = static_cast<int>(std::lround(end_time / step_size));
  run.failure = testing::error_message(
      [&] {
        for (int n = 0; n < steps; ++n)
          integrator.step(model, run.state, step_size);
      },
      "");
  run.statistics = integrator.statistics();
  return run;
}

TEST(MbdNewtonExtremes, StiffClosedLoopOfFiveBodiesConvergesAtMicrosecondStepsAndTolerance1e12) {
  const StiffLoop loop = stiff_closed_loop();
  const double end_time = 1e-3;
  for (const TableauFamily family : {TableauFamily::RadauIIA, TableauFamily::LobattoIIIA}) {
    const char* name = family == TableauFamily::RadauIIA ? "Radau IIA 3" : "Lobatto IIIA 3";
    std::vector<LoopRun> runs;
    for (const double h : {1e-6, 5e-6}) {
      runs.push_back(integrate(loop.model, family, h, end_time));
      const LoopRun& run = runs.back();
      std::printf(
          "%s, h = %g s, relative tolerance 1e-12: %llu steps, %llu Newton iterations, %llu "
          "factorisations, position drift %.2e m%s%s\n",
          name, h, static_cast<unsigned long long>(run.statistics.steps),
          static_cast<unsigned long long>(run.statistics.newton_iterations),
          static_cast<unsigned long long>(run.statistics.factorisations),
          position_constraint_drift(loop.model, run.state), run.failure.empty() ? "" : "; ",
          run.failure.c_str());
      ASSERT_EQ(run.failure, "") << name << " at h = " << h;
      EXPECT_NEAR(run.state.time, end_time, 1e-15);
      EXPECT_LE(position_constraint_drift(loop.model, run.state), 1e-14) << name;
    }
    // The two step sizes describe the same motion: the heavy link has fallen by ~g t^2 / 2 at
    // the start of its motion, the two results agree far below that.
    const double heavy_y =
        runs[0].state.q(loop.model.coordinate_index(loop.links[2], Coordinate::Y));
    const double difference = (runs[0].state.q - runs[1].state.q).lpNorm<Eigen::Infinity>();
    std::printf("%s: heavy link's centre y(1 ms) = %.12f m, h = 1e-6 against 5e-6: |dq| = %.2e\n",
                name, heavy_y, difference);
    EXPECT_LT(difference, 1e-9) << name;
  }
}

// A force computed to only about nine digits (a tabulated law, an inner iteration): its
// noise, not the arithmetic, sets the floor of the residual, so the convergence test cannot
// accept it at round-off and the tolerance 1e-13 is out of reach.
class NoisySpring final : public ForceElement {
 public:
  explicit NoisySpring(int coordinate) : coordinate_(coordinate) {}
  void add_force(double, const Eigen::VectorXd& q, const Eigen::VectorXd&,
                 Eigen::VectorXd& force) const override {
    // A different pseudo-random noise of at most 1e-9 N at every evaluation.
    state_ = state_ * 6364136223846793005ULL + 1442695040888963407ULL;
    const double unit = static_cast<double>(state_ >> 11) / 9007199254740992.0;  // [0, 1)
    force(coordinate_) -= q(coordinate_) + 1e-9 * (2.0 * unit - 1.0);
  }
  bool add_jacobians(double, const Eigen::VectorXd&, const Eigen::VectorXd&,
                     Eigen::MatrixXd& by_position, Eigen::MatrixXd&) const override {
    by_position(coordinate_, coordinate_) -= 1.0;
    return true;
  }

 private:
  int coordinate_;
  mutable std::uint64_t state_ = 12345;
};

Model noisy_oscillator() {
  Model model;
  RigidBody2DSpec spec;
  spec.name = "mass";
  spec.mass = 1.0;
  spec.inertia = 1.0;
  spec.position = {1.0, 0.0};
  const BodyId body = model.add_rigid_body(spec);
  model.add_force_element(
      std::make_unique<NoisySpring>(model.coordinate_index(body, Coordinate::X)));
  return model;
}

TEST(MbdNewtonExtremes, StalledIncrementsAdviseTheToleranceThatPassesNotASmallerStep) {
  const Model model = noisy_oscillator();
  State state = model.initial_state();
  RadauIIA tight(3, {.relative_tolerance = 1e-13});
  const std::string text = testing::error_message([&] { tight.step(model, state, 0.01); });
  std::printf("%s\n", text.c_str());
  EXPECT_NE(text.find("the increments stalled at round-off above the tolerance"), std::string::npos)
      << text;
  std::string without_warning = text;
  const std::string warning = "do not reduce the step size";
  for (std::size_t at = without_warning.find(warning); at != std::string::npos;
       at = without_warning.find(warning))
    without_warning.erase(at, warning.size());
  EXPECT_EQ(without_warning.find("reduce the step size"), std::string::npos) << text;
  const std::string advice = "loosen Newton.relative_tolerance to ";
  const std::size_t at = text.find(advice);
  ASSERT_NE(at, std::string::npos) << text;
  const double advised = std::stod(text.substr(at + advice.size()));
  EXPECT_GT(advised, 1e-13);
  EXPECT_LE(advised, 1e-9) << "no looser than the noise needs";
  // The advised tolerance is reachable: the same step converges with it.
  RadauIIA advised_integrator(3, {.relative_tolerance = advised});
  State again = model.initial_state();
  EXPECT_NO_THROW(advised_integrator.step(model, again, 0.01)) << "advised " << advised;
}

using detail::NewtonConvergence;
using detail::NewtonFailureKind;
using detail::NewtonVerdict;

TEST(MbdNewtonConvergence, RoundOffIsAcceptedOnlyOnceTheIncrementsStopShrinking) {
  NewtonConvergence convergence(1e-12);
  EXPECT_EQ(convergence.observe(2335.0, 9.8, false, true), NewtonVerdict::Continue);
  // At the floor already, but the increments still shrink fast: iterate on.
  EXPECT_EQ(convergence.observe(14.5, 1.1e-10, true, true), NewtonVerdict::Continue);
  EXPECT_EQ(convergence.observe(14.4, 1.1e-10, true, true), NewtonVerdict::ConvergedAtRoundOff);
  // Below the tolerance is converged whatever the residual.
  convergence.restart();
  EXPECT_EQ(convergence.observe(0.5, 1.0, false, true), NewtonVerdict::Converged);
}

TEST(MbdNewtonConvergence, AStallAboveTheFloorAdvisesALooserToleranceNotASmallerStep) {
  NewtonConvergence convergence(1e-12);
  const double increments[] = {2335.0, 14.5, 14.4, 25.4, 18.8, 14.4};
  const double residuals[] = {9.8, 1.1e-10, 1.1e-10, 1.2e-10, 1.1e-10, 1.1e-10};
  for (int k = 0; k < 6; ++k) {
    EXPECT_EQ(convergence.observe(increments[k], residuals[k], false, true),
              NewtonVerdict::Continue);
  }
  EXPECT_EQ(convergence.failure_kind(), NewtonFailureKind::StalledAtRoundOff);
  EXPECT_DOUBLE_EQ(convergence.reachable_relative_tolerance(), 1e-10);  // 2 * 1e-12 * 25.4
  const std::string advice = convergence.advice(12);
  EXPECT_NE(advice.find("loosen Newton.relative_tolerance to 1e-10 (now 1e-12)"), std::string::npos)
      << advice;
  EXPECT_NE(advice.find("do not reduce the step size"), std::string::npos) << advice;
}

TEST(MbdNewtonConvergence, PersistentGrowthWithAFreshMatrixIsDivergenceAndWantsASmallerStep) {
  NewtonConvergence convergence(1e-10);
  EXPECT_EQ(convergence.observe(1e3, 1.0, false, true), NewtonVerdict::Continue);
  // Growth below the prediction's residual is noise, not divergence.
  EXPECT_EQ(convergence.observe(1e1, 1e-8, false, true), NewtonVerdict::Continue);
  EXPECT_EQ(convergence.observe(2e1, 2e-8, false, true), NewtonVerdict::Continue);
  EXPECT_EQ(convergence.observe(4e1, 4e-8, false, true), NewtonVerdict::Continue);
  EXPECT_EQ(convergence.observe(8e1, 8e-8, false, true), NewtonVerdict::Continue);
  EXPECT_EQ(convergence.observe(2e3, 2.0, false, true), NewtonVerdict::Continue);
  EXPECT_EQ(convergence.observe(4e3, 4.0, false, true), NewtonVerdict::Continue);
  EXPECT_EQ(convergence.observe(8e3, 8.0, false, true), NewtonVerdict::Diverging);
  EXPECT_EQ(convergence.failure_kind(), NewtonFailureKind::Diverging);
  const std::string advice = convergence.advice(12);
  EXPECT_NE(advice.find("diverges"), std::string::npos) << advice;
  EXPECT_NE(advice.find("reduce the step size"), std::string::npos) << advice;
  EXPECT_EQ(advice.find("relative_tolerance"), std::string::npos) << advice;
  // Growth with a kept (stale) matrix is the driver's cue to refresh it, not divergence.
  NewtonConvergence stale(1e-10);
  for (double growth : {1e3, 2e3, 4e3, 8e3, 1.6e4}) {
    EXPECT_EQ(stale.observe(growth, growth * 1e-3, false, false), NewtonVerdict::Continue);
  }
}

TEST(MbdNewtonConvergence, SlowContractionAdvisesMoreIterationsOrASmallerStep) {
  NewtonConvergence convergence(1e-10);
  for (double increment : {1e6, 1e5, 1e4})
    convergence.observe(increment, increment * 1e-6, false, true);
  EXPECT_EQ(convergence.failure_kind(), NewtonFailureKind::TooSlow);
  const std::string advice = convergence.advice(3);
  EXPECT_NE(advice.find("reduce the step size, or raise Newton.max_iterations (now 3)"),
            std::string::npos)
      << advice;
  EXPECT_NE(advice.find("about 4 more iterations"), std::string::npos) << advice;
}

}  // namespace
}  // namespace fsi::mbd
