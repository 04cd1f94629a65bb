// Acceptance tests of issue 4 for the planar ANCF beam: Gerstmayr & Irschik's large-deflection
// cantilever (static tip displacement against element count) and its first two bending
// frequencies (linearised eigenproblem, and a free vibration integrated with Radau IIA).
//
// Setup (Gerstmayr & Irschik 2008, J. Sound Vib.; /work/shared/reference-data/
// ancf_cantilever_gerstmayr_irschik_2008.dat): L = 2 m, E = 2.07e11 Pa, rho = 7800 kg/m^3,
// b = h = 0.1 m, clamped at x = 0 (position and slope direction), dead tip load
// F = 3 E I / L^2 in -y. Measured numbers: docs/theory.md ("Planar ANCF beam").
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "fsi/mbd/integrator.hpp"
#include "fsi/mbd/model.hpp"
#include "fsi/mbd/readouts.hpp"
#include "fsi/mbd/static_analysis.hpp"

namespace fsi::mbd {
namespace {

constexpr double kLength = 2.0;
constexpr double kYoung = 2.07e11;
constexpr double kDensity = 7800.0;
constexpr double kArea = 0.1 * 0.1;
constexpr double kInertia = 0.1 * 0.1 * 0.1 * 0.1 / 12.0;
constexpr double kTipLoad = 3.0 * kYoung * kInertia / (kLength * kLength);

// Tip displacement (ux, uy) [m] from the reference-data file (Gerstmayr & Irschik 2008 as
// reproduced in Exudyn's ANCFcantileverTest.py).
struct TipDisplacement {
  int elements;
  double ux;
  double uy;
};
constexpr TipDisplacement kTable[] = {
    {4, -0.50742871545579, -1.20553370256025},
    {8, -0.50850923657299, -1.20719775609310},
    {32, -0.50853727776170, -1.20723982646509},
};
constexpr TipDisplacement kConverged = {0, -0.508537304326, -1.207239854550};

// Euler-Bernoulli clamped-free frequencies of the same beam, same file [Hz].
constexpr double kFirstFrequency = 20.8045;
constexpr double kSecondFrequency = 130.3798;

struct Cantilever {
  Model model;
  BodyId beam = 0;
  int tip_marker = 0;
};

Cantilever cantilever(int elements) {
  Cantilever c;
  AncfBeamSpec spec;
  spec.name = "cantilever";
  spec.start = {0.0, 0.0};
  spec.end = {kLength, 0.0};
  spec.element_count = elements;
  spec.axial_stiffness = kYoung * kArea;
  spec.bending_stiffness = kYoung * kInertia;
  spec.mass_per_length = kDensity * kArea;
  c.beam = c.model.add_ancf_beam(spec);
  c.model.add_beam_clamp(c.beam, 0);
  c.tip_marker = c.model.add_marker(c.beam, {kLength, 0.0});
  return c;
}

Eigen::Vector2d static_tip_displacement(int elements, double load) {
  Cantilever c = cantilever(elements);
  c.model.set_point_loads(std::vector<double>{0.0, -load});
  const StaticResult result = solve_static(c.model, c.model.initial_state());
  return marker_position(c.model, result.state, c.tip_marker).head<2>() -
         Eigen::Vector2d(kLength, 0.0);
}

double relative_error(const Eigen::Vector2d& value, double ux, double uy) {
  const Eigen::Vector2d reference(ux, uy);
  return (value - reference).norm() / reference.norm();
}

TEST(MbdAncfCantilever, StaticTipDisplacementWith32ElementsMatchesTheConvergedReference) {
  const Eigen::Vector2d tip = static_tip_displacement(32, kTipLoad);
  const double error = relative_error(tip, kConverged.ux, kConverged.uy);
  std::printf("32 elements: tip (%.12f, %.12f) m, relative error to converged %.3e\n", tip.x(),
              tip.y(), error);
  EXPECT_LT(error, 1e-6);
}

TEST(MbdAncfCantilever, StaticTipDisplacementWith4And8ElementsMatchesTheTable) {
  for (const TipDisplacement& row : kTable) {
    if (row.elements > 8) continue;
    const Eigen::Vector2d tip = static_tip_displacement(row.elements, kTipLoad);
    const double error = relative_error(tip, row.ux, row.uy);
    std::printf("%d elements: tip (%.12f, %.12f) m, relative error to the table %.3e\n",
                row.elements, tip.x(), tip.y(), error);
    EXPECT_LT(error, 1e-3) << row.elements << " elements";
  }
}

// The same element, strain measure, clamp and Gauss rules as the paper's table reproduce its
// rows to round-off of the reported digits, not just to the discretisation error: a 4-point
// axial rule or the Green strain (|r'|^2 - 1) / 2 are off by 2e-6 relative at 4 elements.
TEST(MbdAncfCantilever, TheSameElementAndRulesReproduceThePapersTableClosely) {
  for (const TipDisplacement& row : kTable) {
    const double error =
        relative_error(static_tip_displacement(row.elements, kTipLoad), row.ux, row.uy);
    EXPECT_LT(error, 1e-8) << row.elements << " elements";
  }
}

TEST(MbdAncfCantilever, StaticSolveRestoresTheLoadsAndSatisfiesTheClamp) {
  Cantilever c = cantilever(4);
  c.model.set_point_loads(std::vector<double>{0.0, -kTipLoad});
  const StaticResult result = solve_static(c.model, c.model.initial_state());
  EXPECT_EQ(c.model.point_loads()[1], -kTipLoad);
  EXPECT_LT(position_constraint_drift(c.model, result.state), 1e-14);
  // The clamp carries the load: -G^T lambda balances the tip load in y.
  const Eigen::VectorXd reaction = generalised_constraint_force(c.model, result.state);
  const int y0 = c.model.beam_coordinate_index(c.beam, 0, BeamNodeCoordinate::Y);
  EXPECT_NEAR(reaction(y0), kTipLoad, 1e-8 * kTipLoad);
}

// A spring actor at a point of the beam acts on the beam (the pump's outlet valve, examples/pump:
// thesis §6.5's actor 1 holds the elastic valve's free end). The actor runs from the free end to a
// point 1 m below it and pushes only when compressed, at k = 3 E I / L^3, the tip's own stiffness:
// a small load down (linear range, tip 1e-4 L) is carried half by the beam, half by the actor; the
// same load up stretches it, and the beam alone carries it.
TEST(MbdAncfCantilever, ASpringActorAtTheFreeEndIsCarriedByTheBeam) {
  const double stiffness = 3.0 * kYoung * kInertia / (kLength * kLength * kLength);
  const double load = 1e-4 * kTipLoad;
  for (const double sign : {-1.0, 1.0}) {
    Cantilever c = cantilever(8);
    SpringActorSpec actor;
    actor.name = "stop";
    actor.a = {c.beam, {kLength, 0.0}};
    actor.b = {kGround, {kLength, -1.0}};
    actor.characteristic = {{-0.01, -0.01 * stiffness}, {0.0, 0.0}, {0.01, 0.0}};
    c.model.add_spring_actor(actor);
    c.model.set_point_loads(std::vector<double>{0.0, sign * load});
    const StaticResult result = solve_static(c.model, c.model.initial_state());
    const double uy = marker_position(c.model, result.state, c.tip_marker).y();
    const double free_end = sign * load / stiffness;  // the beam alone: F L^3 / (3 E I)
    const double expected = sign < 0.0 ? 0.5 * free_end : free_end;
    EXPECT_NEAR(uy, expected, 1e-4 * std::abs(expected))
        << (sign < 0.0 ? "pushed down" : "pulled up");
  }
}

TEST(MbdAncfCantilever, FirstTwoBendingFrequenciesFromTheLinearisedSystem) {
  Cantilever c = cantilever(16);
  const std::vector<double> f = natural_frequencies(c.model, c.model.initial_state(), 3);
  ASSERT_EQ(f.size(), 3U);
  std::printf("16 elements: f1 = %.6f Hz (%.2e), f2 = %.6f Hz (%.2e), f3 = %.6f Hz\n", f[0],
              f[0] / kFirstFrequency - 1.0, f[1], f[1] / kSecondFrequency - 1.0, f[2]);
  EXPECT_NEAR(f[0] / kFirstFrequency, 1.0, 5e-3);
  EXPECT_NEAR(f[1] / kSecondFrequency, 1.0, 5e-3);
}

// Released from the static deflection under a small tip load (linear range), the tip swings in
// mostly the first mode: its period from the zero crossings of uy.
TEST(MbdAncfCantilever, FreeVibrationWithRadauIIAHasTheFirstBendingFrequency) {
  Cantilever c = cantilever(8);
  c.model.set_point_loads(std::vector<double>{0.0, -1e-4 * kTipLoad});
  State state = solve_static(c.model, c.model.initial_state()).state;
  c.model.set_point_loads(std::vector<double>{0.0, 0.0});
  const int tip_y = c.model.beam_coordinate_index(c.beam, 8, BeamNodeCoordinate::Y);
  RadauIIA integrator(3);
  const double h = 2e-4;
  std::vector<double> crossings;
  double previous = state.q(tip_y);
  while (state.time < 0.2) {
    const double t0 = state.time;
    integrator.step(c.model, state, h);
    const double current = state.q(tip_y);
    if ((previous < 0.0) != (current < 0.0))
      crossings.push_back(t0 + h * previous / (previous - current));
    previous = current;
  }
  ASSERT_GE(crossings.size(), 6U);
  const double period =
      2.0 * (crossings.back() - crossings.front()) / static_cast<double>(crossings.size() - 1);
  std::printf("free vibration (8 elements, h = %g s): f1 = %.5f Hz (%.2e) from %zu crossings\n", h,
              1.0 / period, 1.0 / (period * kFirstFrequency) - 1.0, crossings.size());
  EXPECT_NEAR(1.0 / (period * kFirstFrequency), 1.0, 5e-3);
  const IntegratorStatistics& statistics = integrator.statistics();
  std::printf("  %llu steps, %llu Newton iterations, %llu factorisations\n",
              static_cast<unsigned long long>(statistics.steps),
              static_cast<unsigned long long>(statistics.newton_iterations),
              static_cast<unsigned long long>(statistics.factorisations));
}

// At the coupled runs' step (5e-6 s) and the default Newton tolerance the stiff steel beam
// converges: the convergence test includes the rounding of the elastic forces. The run keeps
// the energy of the free vibration (Radau IIA's dissipation at h f = 1e-4 is negligible).
TEST(MbdAncfCantilever, CoupledStepSizeConvergesAtTheDefaultNewtonTolerance) {
  Cantilever c = cantilever(8);
  c.model.set_point_loads(std::vector<double>{0.0, -1e-4 * kTipLoad});
  State state = solve_static(c.model, c.model.initial_state()).state;
  c.model.set_point_loads(std::vector<double>{0.0, 0.0});
  const double energy = strain_energy(c.model, state);
  RadauIIA integrator(3);
  for (int step = 0; step < 400; ++step)
    integrator.step(c.model, state, 5e-6);
  const double total = kinetic_energy(c.model, state) + strain_energy(c.model, state);
  EXPECT_NEAR(total / energy, 1.0, 1e-6);
  EXPECT_LT(static_cast<double>(integrator.statistics().newton_iterations), 4.0 * 400);
}

}  // namespace
}  // namespace fsi::mbd
