// Acceptance test of issue 4 (stiffness): a chain of three 1 kg masses on springs
// ground -(1e2 N/m)- m1 -(1e9 N/m)- m2 -(1e2 N/m)- m3. The stiff spring's mode has
// omega_max^2 = k (1/m1 + 1/m2) = 2e9 s^-2, so an explicit method is stable only for
// h < 2 / omega_max = 4.47e-5 s (symplectic Euler / leapfrog limit, the most generous of the
// classical explicit methods). Radau IIA (L-stable) runs at 1000 times that step.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "fsi/mbd/integrator.hpp"
#include "fsi/mbd/model.hpp"
#include "fsi/mbd/readouts.hpp"

namespace fsi::mbd {
namespace {

constexpr double kStiff = 1e9;
constexpr double kSoft = 1e2;
const double kExplicitLimit = 2.0 / std::sqrt(2.0 * kStiff);

Model stiff_chain() {
  Model model;
  BodyId previous = kGround;
  const double positions[] = {1.1, 2.1 + 1e-6, 3.0};  // soft springs stretched, stiff by 1 um
  const double stiffness[] = {kSoft, kStiff, kSoft};
  for (int k = 0; k < 3; ++k) {
    RigidBody2DSpec spec;
    spec.name = "mass" + std::to_string(k + 1);
    spec.mass = 1.0;
    spec.inertia = 1.0;
    spec.position = {positions[k], 0.0};
    const BodyId body = model.add_rigid_body(spec);
    model.add_spring_damper({.a = {previous, {0.0, 0.0}},
                             .b = {body, {0.0, 0.0}},
                             .stiffness = stiffness[k],
                             .damping = 0.0,
                             .rest_length = 1.0});
    previous = body;
  }
  return model;
}

// Kinetic energy plus the three springs' energy.
double chain_energy(const Model& model, const State& state) {
  const double x[] = {0.0, state.q(0), state.q(3), state.q(6)};
  const double stiffness[] = {kSoft, kStiff, kSoft};
  double energy = kinetic_energy(model, state);
  for (int k = 0; k < 3; ++k)
    energy += 0.5 * stiffness[k] * std::pow(x[k + 1] - x[k] - 1.0, 2);
  return energy;
}

// Symplectic Euler, v += h M^-1 F(q, v), q += h v: stable for h < 2 / omega_max.
State symplectic_euler(const Model& model, State state, double h, int steps) {
  Eigen::VectorXd force;
  const Eigen::VectorXd inverse_mass = model.mass_matrix().diagonal().cwiseInverse();
  for (int i = 0; i < steps; ++i) {
    model.applied_force(state.time, state.q, state.v, force);
    state.v += h * inverse_mass.cwiseProduct(force);
    state.q += h * state.v;
    state.time += h;
  }
  return state;
}

TEST(MbdStiffnessAcceptance, RadauIIARunsAt1000TimesTheExplicitLimitWhereExplicitBlowsUp) {
  const Model model = stiff_chain();
  const State start = model.initial_state();
  const double start_energy = chain_energy(model, start);
  const double h = 1000.0 * kExplicitLimit;  // 4.47e-2 s
  const int steps = 200;                     // 8.9 s, several periods of the soft modes

  // Symplectic Euler is right below its limit ...
  const State explicit_fine = symplectic_euler(model, start, 0.9 * kExplicitLimit, 20000);
  const double fine_growth = chain_energy(model, explicit_fine) / start_energy;
  // ... and explodes at the step Radau IIA takes.
  const State explicit_coarse = symplectic_euler(model, start, h, 20);
  const double coarse_growth = chain_energy(model, explicit_coarse) / start_energy;

  RadauIIA integrator(3);
  State state = start;
  double largest_energy = start_energy;
  for (int i = 0; i < steps; ++i) {
    integrator.step(model, state, h);
    ASSERT_TRUE(state.q.allFinite() && state.v.allFinite()) << "step " << i;
    largest_energy = std::max(largest_energy, chain_energy(model, state));
  }
  // The soft motion against the same integrator at h / 16 (which resolves it to ~1e-7 m).
  RadauIIA fine_integrator(3);
  State fine = start;
  for (int i = 0; i < 16 * steps; ++i)
    fine_integrator.step(model, fine, h / 16);
  const double soft_difference = (state.q - fine.q).lpNorm<Eigen::Infinity>();

  std::printf(
      "stiff chain: explicit limit 2/omega_max = %.3e s, Radau IIA 3 at h = %.3e s (x%.0f): "
      "energy max/start %.6f, soft motion vs h/16 %.2e m, %llu Newton iterations in %d steps; "
      "symplectic Euler energy growth x%.3g at 0.9 limit (20000 steps), x%.3g after 20 steps "
      "at h\n",
      kExplicitLimit, h, h / kExplicitLimit, largest_energy / start_energy, soft_difference,
      static_cast<unsigned long long>(integrator.statistics().newton_iterations), steps,
      fine_growth, coarse_growth);
  EXPECT_LE(largest_energy, start_energy * (1.0 + 1e-9)) << "stable: no energy gained";
  EXPECT_LT(soft_difference, 1e-3);
  EXPECT_LT(fine_growth, 1.5) << "the explicit reference method itself is right";
  EXPECT_GT(coarse_growth, 1e10) << "an explicit method fails at this step";
}

}  // namespace
}  // namespace fsi::mbd
