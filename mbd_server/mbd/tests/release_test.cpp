// Constraints released at a chosen time (Model::set_release_time): a row holds until its release
// time and is removed from then on, its multiplier zero. Every integrator lands on the release:
// Radau IIA and Lobatto IIIA split a step that contains it, IDA stops there and restarts.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <string>

#include "error_message.hpp"
#include "fsi/mbd/adaptive_radau.hpp"
#include "fsi/mbd/ida.hpp"
#include "fsi/mbd/integrator.hpp"
#include "fsi/mbd/model.hpp"
#include "fsi/mbd/readouts.hpp"

namespace fsi::mbd {
namespace {

constexpr double kGravity = 9.81;
constexpr NewtonOptions kTight{.relative_tolerance = 1e-12, .max_iterations = 20};

// --- a pendulum held out of the vertical by a coordinate constraint on x, then let go ---

constexpr double kRodLength = 1.0;
constexpr double kPendulumMass = 1.0;
constexpr double kStartAngle = 0.5;  // [rad] from the downward vertical

struct Pendulum {
  Model model;
  BodyId bob = 0;
  int held_x_row = -1;  // -1: the pendulum swings from the start
};

Pendulum pendulum(bool held) {
  Pendulum p;
  RigidBody2DSpec bob;
  bob.name = "bob";
  bob.mass = kPendulumMass;
  bob.inertia = 1.0;  // no torque acts: the rotation stays at rest
  bob.position = {kRodLength * std::sin(kStartAngle), -kRodLength * std::cos(kStartAngle)};
  p.bob = p.model.add_rigid_body(bob);
  p.model.set_gravity({0.0, -kGravity});
  p.model.add_distance_constraint({kGround, {0.0, 0.0}}, {p.bob, {0.0, 0.0}});
  if (held) p.held_x_row = p.model.add_coordinate_constraint(p.bob, Coordinate::X);
  return p;
}

TEST(MbdRelease, APendulumHeldByACoordinateConstraintSwingsFromItsReleaseLikeOneStartedThere) {
  // The release falls inside a step (t = 0.30 + 0.005 with h = 0.01): Radau IIA ends a part of
  // that step at 0.305 s. The free pendulum starts at 0.305 s from the held state and takes the
  // same steps from there.
  const double release = 0.305, h = 0.01, end = 1.2;
  Pendulum held = pendulum(true);
  held.model.set_release_time(held.held_x_row, release);
  const Pendulum free = pendulum(false);
  RadauIIA held_integrator({.stages = 3, .newton = kTight});
  RadauIIA free_integrator({.stages = 3, .newton = kTight});

  State held_state = held.model.initial_state();
  const Eigen::VectorXd start_q = held_state.q;
  const double holding_force = kPendulumMass * kGravity * std::tan(kStartAngle);
  double rest_error = 0.0, holding_error = 0.0;
  while (held_state.time < release) {
    held_integrator.step(held.model, held_state, h);
    if (held_state.time <= release) {
      rest_error = std::max(rest_error, (held_state.q - start_q).lpNorm<Eigen::Infinity>());
      // The multiplier of the x row is the force that holds the bob out (-G^T lambda, G = e_x).
      holding_error =
          std::max(holding_error, std::abs(-held_state.lambda(held.held_x_row) - holding_force));
    }
  }
  // The step that contained the release ended at t = 0.31 s, after a part ending at 0.305 s.
  ASSERT_NEAR(held_state.time, 0.31, 1e-12);

  State free_state = free.model.initial_state();
  free_state.time = release;
  free_integrator.step(free.model, free_state, held_state.time - release);
  double path_error = 0.0, released_multiplier = 0.0;
  const double swing_at_first_step = std::abs(held_state.q(0) - start_q(0));
  while (held_state.time < end - 0.5 * h) {
    path_error = std::max(path_error, (held_state.q - free_state.q).lpNorm<Eigen::Infinity>());
    path_error = std::max(path_error, (held_state.v - free_state.v).lpNorm<Eigen::Infinity>());
    released_multiplier =
        std::max(released_multiplier, std::abs(held_state.lambda(held.held_x_row)));
    held_integrator.step(held.model, held_state, h);
    free_integrator.step(free.model, free_state, h);
  }
  const double swing = std::abs(held_state.q(0) - start_q(0));
  std::printf(
      "pendulum held at x until %.3f s: at rest to %.1e m, holding force %.6f N (m g tan phi0 "
      "%.6f, off by %.1e); after release: |x - x0| = %.3e m after 5 ms, %.3f m at %.1f s, "
      "path against a pendulum started free at %.3f s off by %.1e, multiplier %.1e\n",
      release, rest_error, holding_force, holding_force, holding_error, swing_at_first_step, swing,
      end, release, path_error, released_multiplier);
  EXPECT_LT(rest_error, 1e-12);
  EXPECT_LT(holding_error, 1e-9 * holding_force);
  EXPECT_GT(swing_at_first_step, 1e-5);  // it moves within the first part step after release
  EXPECT_GT(swing, 0.1);
  EXPECT_LT(path_error, 1e-9);
  EXPECT_EQ(released_multiplier, 0.0);
  EXPECT_LT(position_constraint_drift(held.model, held_state), 1e-12);  // the rod still holds
}

// --- a block held at its height by a coordinate constraint, released under gravity ---

constexpr double kBlockMass = 2.0;
constexpr double kBlockHeight = 1.0;
constexpr double kBlockRelease = 0.25;

struct Block {
  Model model;
  BodyId body = 0;
  int held_y_row = -1;
};

Block released_block() {
  Block b;
  RigidBody2DSpec block;
  block.name = "block";
  block.mass = kBlockMass;
  block.inertia = 0.3;
  block.position = {0.5, kBlockHeight};
  b.body = b.model.add_rigid_body(block);
  b.model.set_gravity({0.0, -kGravity});
  b.model.add_coordinate_constraint(b.body, Coordinate::X);
  b.held_y_row = b.model.add_coordinate_constraint(b.body, Coordinate::Y);
  b.model.add_coordinate_constraint(b.body, Coordinate::Angle);
  b.model.set_release_time(b.held_y_row, kBlockRelease);
  return b;
}

// After the release the block falls freely: y = y0 - g (t - t_r)^2 / 2.
double free_fall_height(double time) {
  const double fallen = std::max(0.0, time - kBlockRelease);
  return kBlockHeight - 0.5 * kGravity * fallen * fallen;
}

struct FallRecord {
  double held_height_error = 0.0;  // max |y - y0| before the release
  double holding_error = 0.0;      // max |F_y - m g| of the constraint force before it
  double fall_error = 0.0;         // max |y - free_fall_height| after it
  double force_after = 0.0;        // max |F_y| after it
  int samples_before = 0, samples_after = 0;
};

// Samples the block every `h` up to 0.6 s; `advance` moves the state to the given time.
FallRecord record_fall(const Block& block, double h,
                       const std::function<void(State&, double)>& advance) {
  State state = block.model.initial_state();
  FallRecord record;
  for (int k = 1; k * h <= 0.6 + 1e-12; ++k) {
    advance(state, k * h);
    // The constraint-force sensor of the coupled run: -G^T lambda on the body's y.
    const double force = constraint_force(block.model, state, block.body, Coordinate::Y);
    if (state.time <= kBlockRelease) {
      record.held_height_error =
          std::max(record.held_height_error, std::abs(state.q(1) - kBlockHeight));
      record.holding_error =
          std::max(record.holding_error, std::abs(force - kBlockMass * kGravity));
      ++record.samples_before;
    } else {
      record.fall_error =
          std::max(record.fall_error, std::abs(state.q(1) - free_fall_height(state.time)));
      record.force_after = std::max(record.force_after, std::abs(force));
      ++record.samples_after;
    }
  }
  return record;
}

void expect_fall(const char* integrator, const FallRecord& record, double tolerance) {
  std::printf(
      "%s: held at y0 to %.1e m with the multiplier's force m g to %.1e N (%d samples), then "
      "falls with g to %.1e m, constraint force %.1e N (%d samples)\n",
      integrator, record.held_height_error, record.holding_error, record.samples_before,
      record.fall_error, record.force_after, record.samples_after);
  EXPECT_GT(record.samples_before, 3) << integrator;
  EXPECT_GT(record.samples_after, 3) << integrator;
  EXPECT_LT(record.held_height_error, 1e-12) << integrator;
  EXPECT_LT(record.holding_error, 1e-8 * kBlockMass * kGravity) << integrator;
  EXPECT_LT(record.fall_error, tolerance) << integrator;
  EXPECT_EQ(record.force_after, 0.0) << integrator;
}

TEST(MbdRelease, ABlockReleasedInsideAStepFallsWithGravityFromTheReleaseTime) {
  // h = 0.02: the release at 0.25 s falls in the middle of the step 0.24 ... 0.26 s.
  const double h = 0.02;
  struct Variant {
    const char* name;
    RadauOptions options;
  };
  const Variant variants[] = {
      {"Radau IIA 3", {.stages = 3, .newton = kTight}},
      {"Radau IIA 1", {.stages = 1, .newton = kTight}},
      {"Lobatto IIIA 3", {.stages = 3, .newton = kTight, .family = TableauFamily::LobattoIIIA}},
      {"Radau IIA 3, index-2 form",
       {.stages = 3, .newton = kTight, .constraint_form = ConstraintForm::Index2}},
      {"Radau IIA 3, sparse Newton matrix",
       {.stages = 3,
        .newton = {.relative_tolerance = 1e-12,
                   .max_iterations = 20,
                   .linear_solver = LinearSolver::Sparse}}},
  };
  for (const Variant& variant : variants) {
    const Block block = released_block();
    RadauIIA integrator(variant.options);
    const FallRecord record = record_fall(
        block, h, [&](State& state, double) { integrator.step(block.model, state, h); });
    // Every tableau integrates a constant acceleration exactly (orders >= 1 on q'' = const with a
    // stage at the step end; implicit Euler's q is off by h g (t - t_r) / 2 per the closed form).
    const double tolerance = variant.options.stages == 1 ? 0.5 * kGravity * h * 0.6 : 1e-12;
    expect_fall(variant.name, record, tolerance);
  }
}

TEST(MbdRelease, IdaAndTheAdaptiveRadauStopAtTheReleaseAndRestartWithoutTheRow) {
  const double h = 0.02;
  {
    const Block block = released_block();
    IdaIntegrator ida({.relative_tolerance = 1e-10, .absolute_tolerance = 1e-12});
    const FallRecord record = record_fall(
        block, h, [&](State& state, double until) { ida.advance(block.model, state, until); });
    expect_fall("SUNDIALS IDA", record, 1e-7);
  }
  {
    const Block block = released_block();
    AdaptiveRadau adaptive({.stages = 3, .newton = kTight},
                           {.relative_tolerance = 1e-10, .absolute_tolerance = 1e-12});
    const FallRecord record = record_fall(
        block, h, [&](State& state, double until) { adaptive.advance(block.model, state, until); });
    expect_fall("adaptive Radau IIA 3", record, 1e-10);
  }
}

TEST(MbdRelease, AReleaseAtTimeZeroHoldsTheStartOnlyAndABadReleaseIsRefusedByRow) {
  Block block = released_block();
  block.model.set_release_time(block.held_y_row, 0.0);
  State state = block.model.initial_state();
  // The t = 0 state is the held one: its multiplier carries the weight (as a body held during
  // the fluid's equilibration and released at t = 0).
  EXPECT_NEAR(constraint_force(block.model, state, block.body, Coordinate::Y),
              kBlockMass * kGravity, 1e-9);
  RadauIIA integrator({.stages = 3, .newton = kTight});
  integrator.step(block.model, state, 0.1);
  EXPECT_NEAR(state.q(1), kBlockHeight - 0.5 * kGravity * 0.01, 1e-12);
  EXPECT_EQ(state.lambda(block.held_y_row), 0.0);

  const std::string negative =
      testing::error_message([&] { block.model.set_release_time(block.held_y_row, -0.5); });
  EXPECT_NE(negative.find("release time -0.5 s is negative"), std::string::npos) << negative;
  EXPECT_NE(negative.find("coordinate constraint on block.y"), std::string::npos) << negative;
  const std::string missing = testing::error_message([&] { block.model.set_release_time(7, 1.0); });
  EXPECT_NE(missing.find("row 7, but the model has 3 rows"), std::string::npos) << missing;
}

}  // namespace
}  // namespace fsi::mbd
