// A planar ANCF beam clamped to a rigid body: the slope rows against finite differences, and a
// cantilever clamped to a turned, held body bends exactly as the same cantilever clamped to the
// ground (Gerstmayr & Irschik's steel beam, tip load 3 EI / L^2).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "direction_rows.hpp"
#include "element_checks.hpp"
#include "fsi/mbd/model.hpp"
#include "fsi/mbd/readouts.hpp"
#include "fsi/mbd/static_analysis.hpp"

namespace fsi::mbd {
namespace {

TEST(MbdBeamClampToBody, SlopeRowsHaveExactDerivatives) {
  // q: a body (x, y, phi) and a node (x, y, slope x, slope y), general values.
  const Eigen::VectorXd q{{0.3, -0.2, 0.7, 1.1, 0.4, 0.9, -0.35}};
  const Eigen::VectorXd v{{0.5, -1.5, 2.0, -0.7, 0.9, 3.0, -1.2}};
  const Eigen::Vector2d vector(0.6, -0.8);
  testing::expect_exact_row_derivatives(
      detail::SlopeOnBodyConstraint("direction", 5, 6, 2, vector, -1), q, v, "slope direction");
  for (int k = 0; k < 2; ++k) {
    testing::expect_exact_row_derivatives(
        detail::SlopeOnBodyConstraint("component", 5, 6, 2, vector, k), q, v, "slope component");
  }
}

constexpr double kLength = 2.0;
constexpr double kBending = 2.07e11 * 1e-4 / 12.0;

Eigen::Vector2d tip_displacement(bool on_body, BeamClamp clamp) {
  const double angle = std::numbers::pi / 6.0;
  const Eigen::Vector2d along(std::cos(angle), std::sin(angle));
  Model model;
  AncfBeamSpec spec;
  spec.name = "beam";
  spec.start = {0.0, 0.0};
  spec.end = kLength * along;
  spec.element_count = 8;
  spec.axial_stiffness = 2.07e11 * 0.01;
  spec.bending_stiffness = kBending;
  spec.mass_per_length = 78.0;
  const BodyId beam = model.add_ancf_beam(spec);
  if (on_body) {
    RigidBody2DSpec hub;
    hub.name = "hub";
    hub.mass = 5.0;
    hub.inertia = 0.2;
    hub.position = {-0.1, 0.05};
    hub.angle = angle;
    const BodyId body = model.add_rigid_body(hub);
    model.add_clamp({"base", body, kGround});
    model.add_beam_clamp(beam, 0, clamp, body);
  } else {
    model.add_beam_clamp(beam, 0, clamp);
  }
  const int tip = model.add_marker(beam, {kLength, 0.0});
  const Eigen::Vector2d load = -3.0 * kBending / (kLength * kLength) *
                               Eigen::Vector2d(-along.y(), along.x());  // normal to the beam
  model.set_point_loads(std::vector<double>{load.x(), load.y()});
  const StaticResult result = solve_static(model, model.initial_state());
  return marker_position(model, result.state, tip).head<2>() - kLength * along;
}

TEST(MbdBeamClampToBody, CantileverOnATurnedHeldBodyBendsAsOnTheGround) {
  for (const BeamClamp clamp : {BeamClamp::Direction, BeamClamp::Full}) {
    const Eigen::Vector2d ground = tip_displacement(false, clamp);
    const Eigen::Vector2d body = tip_displacement(true, clamp);
    std::printf(
        "beam clamped to a body (%s): tip displacement (%.9f, %.9f) m, off the ground "
        "clamp by %.2e\n",
        clamp == BeamClamp::Full ? "full" : "direction", body.x(), body.y(),
        (body - ground).norm() / ground.norm());
    EXPECT_GT(ground.norm(), 0.5);  // large deflection
    EXPECT_LT((body - ground).norm(), 1e-9 * ground.norm());
  }
}

TEST(MbdBeamClampReaction, TheClampHoldsTheLoadAndItsMomentAboutTheNode) {
  // A cantilever in large deflection under a tip load F: in equilibrium the clamp exerts -F on
  // the beam and the moment -(r_tip - r_clamp) x F about its node, in the deformed shape. The
  // clamp is not at node 0: the beam runs from the tip (node 0) to the clamped end (node 8).
  for (const BeamClamp clamp : {BeamClamp::Direction, BeamClamp::Full}) {
    Model model;
    AncfBeamSpec spec;
    spec.name = "beam";
    spec.start = {kLength, 0.0};
    spec.end = {0.0, 0.0};
    spec.element_count = 8;
    spec.axial_stiffness = 2.07e11 * 0.01;
    spec.bending_stiffness = kBending;
    spec.mass_per_length = 78.0;
    const BodyId beam = model.add_ancf_beam(spec);
    const int first_row = model.constraint_count();
    model.add_beam_clamp(beam, 8, clamp);
    const int rows = model.constraint_count() - first_row;
    const int tip = model.add_marker(beam, {0.0, 0.0});
    const Eigen::Vector2d load(0.3 * kBending / (kLength * kLength),
                               -2.0 * kBending / (kLength * kLength));
    model.set_point_loads(std::vector<double>{load.x(), load.y()});
    const StaticResult result = solve_static(model, model.initial_state());
    const Wrench reaction =
        beam_joint_reaction(model, result.state, first_row, rows, beam, {kLength, 0.0});
    const Eigen::Vector2d arm = marker_position(model, result.state, tip).head<2>();  // clamp at 0
    const double moment = -(arm.x() * load.y() - arm.y() * load.x());
    std::printf("clamp reaction (%s): force (%.6f, %.6f) N, moment %.6f N m (expected %.6f)\n",
                clamp == BeamClamp::Full ? "full" : "direction", reaction.force.x(),
                reaction.force.y(), reaction.torque.z(), moment);
    EXPECT_GT(arm.norm(), 0.1);
    EXPECT_LT((kLength * Eigen::Vector2d(1.0, 0.0) - arm).norm(), 0.9 * kLength);  // it bent
    EXPECT_NEAR(reaction.force.x(), -load.x(), 1e-8 * load.norm());
    EXPECT_NEAR(reaction.force.y(), -load.y(), 1e-8 * load.norm());
    EXPECT_NEAR(reaction.torque.z(), moment, 1e-7 * std::abs(moment));
  }
  Model model;
  EXPECT_THROW(beam_joint_reaction(model, model.initial_state(), 0, 0, 0, {0.0, 0.0}), Error);
}

}  // namespace
}  // namespace fsi::mbd
