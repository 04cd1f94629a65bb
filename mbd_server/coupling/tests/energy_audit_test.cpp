// The energy audit of the coupling: the work each side did on the other over an exchange.
#include "fsi/coupling/energy_audit.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "fsi/common/error.hpp"

namespace fsi::coupling {
namespace {

TEST(EnergyAudit, AStructureAtRestExchangesNoEnergy) {
  EnergyAudit audit;
  const std::vector<double> x{0.0, 0.1, 0.2, 0.1};
  const std::vector<double> v(4, 0.0);
  const std::vector<double> f{1.0, -2.0, 0.5, -9.81};
  audit.start(x, v, f);
  for (std::uint64_t n = 1; n <= 100; ++n)
    audit.exchange(x, v, 1e-4, f, n);
  EXPECT_EQ(audit.totals().work_fluid_on_structure, 0.0);
  EXPECT_EQ(audit.totals().work_structure_on_fluid, 0.0);
  EXPECT_EQ(audit.totals().coupling_energy, 0.0);
  EXPECT_EQ(audit.totals().exchanges, 100u);
  EXPECT_TRUE(audit.take_warning().empty());
}

TEST(EnergyAudit, AConstantForceOnAUniformMotionIsExchangedExactly) {
  // A vertex moving at 0.3 m/s under a constant 2 N: each side gets what the other gives.
  EnergyAudit audit;
  const double dt = 1e-3;
  const std::vector<double> f{2.0, -1.0};
  const std::vector<double> v{0.3, 0.0};
  audit.start(std::vector<double>{0.0, 1.0}, v, f);
  for (std::uint64_t n = 1; n <= 1000; ++n)
    audit.exchange(std::vector<double>{0.3 * dt * static_cast<double>(n), 1.0}, v, dt, f, n);
  EXPECT_NEAR(audit.totals().work_fluid_on_structure, 2.0 * 0.3 * 1.0, 1e-12);
  EXPECT_NEAR(audit.totals().work_structure_on_fluid, -2.0 * 0.3 * 1.0, 1e-12);
  EXPECT_NEAR(audit.totals().traffic, 2.0 * 0.3 * 1.0, 1e-12);
  EXPECT_NEAR(audit.totals().coupling_energy, 0.0, 1e-12);
  EXPECT_TRUE(audit.take_warning().empty());
}

TEST(EnergyAudit, AWallDrivenFromRestIsNotMistakenForTheInstability) {
  // A prescribed motion x = a t^2 / 2 under a constant force: the staggered scheme's lag makes a
  // coupling energy of 1/n of the traffic after n exchanges, which is no instability.
  EnergyAudit audit;
  const double a = 0.5, dt = 1e-4;
  const std::vector<double> f{3.0};  // along the acceleration: the created energy is positive
  audit.start(std::vector<double>{0.0}, std::vector<double>{0.0}, f);
  for (std::uint64_t n = 1; n <= 200; ++n) {
    const double t = dt * static_cast<double>(n);
    audit.exchange(std::vector<double>{0.5 * a * t * t}, std::vector<double>{a * t}, dt, f, n);
    if (n == 4) {
      EXPECT_NEAR(audit.totals().coupling_energy, 0.25 * audit.totals().traffic, 1e-18);
    }
  }
  EXPECT_NEAR(audit.totals().coupling_energy, audit.totals().traffic / 200.0, 1e-15);
  EXPECT_FALSE(audit.warned_at());
}

// A mass m on a spring k in a "fluid" that damps it, f = -c v, coupled the staggered way: the
// structure moves under the force of the previous exchange, the fluid answers to the new motion.
// Explicit coupling of a damper is stable for c dt / m < 2 and unstable above.
// With stop_growth > 0 it ends where the audit says stop, as the session does.
EnergyAudit staggered_damper(double c_dt_over_m, int steps, double stop_growth = 0.0,
                             double* largest_speed = nullptr, const std::string& remedy = {},
                             double noise_floor = kAuditRoundOff) {
  const double m = 1.0, k = 100.0, dt = 1e-3, c = c_dt_over_m * m / dt;
  double x = 0.01, v = 0.0, f = 0.0;
  EnergyAudit audit(stop_growth, remedy, noise_floor);
  audit.start(std::vector<double>{x}, std::vector<double>{v}, std::vector<double>{f});
  for (int n = 1; n <= steps && audit.stop().empty(); ++n) {
    v += dt * (-k * x + f) / m;  // symplectic Euler under the held force
    x += dt * v;
    f = -c * v;
    audit.exchange(std::vector<double>{x}, std::vector<double>{v}, dt, std::vector<double>{f},
                   static_cast<std::uint64_t>(n));
    if (largest_speed) *largest_speed = std::max(*largest_speed, std::abs(v));
  }
  return audit;
}

TEST(EnergyAudit, ALightlyCoupledDamperTakesEnergyFromTheStructure) {
  EnergyAudit audit = staggered_damper(0.05, 2000);
  EXPECT_LT(audit.totals().work_fluid_on_structure, 0.0);  // the fluid damps the structure
  EXPECT_GT(audit.totals().work_structure_on_fluid, 0.0);  // and receives what it takes
  EXPECT_LT(std::abs(audit.totals().coupling_energy),
            0.01 * std::abs(audit.totals().work_fluid_on_structure));
  EXPECT_TRUE(audit.take_warning().empty());
  EXPECT_FALSE(audit.warned_at());
}

TEST(EnergyAudit, TheAddedMassInstabilityIsSeenAsCreatedEnergy) {
  EnergyAudit audit = staggered_damper(2.5, 40);
  ASSERT_TRUE(audit.warned_at());
  EXPECT_LT(*audit.warned_at(), 40u);
  EXPECT_GT(audit.totals().coupling_energy, 0.0);
  const std::string warning = audit.take_warning();
  EXPECT_NE(warning.find("the coupling has created energy: by step " +
                         std::to_string(*audit.warned_at())),
            std::string::npos)
      << warning;
  EXPECT_NE(warning.find("added-mass instability"), std::string::npos);
  EXPECT_NE(warning.find("halve SolverOptions.Timeint.step_size"), std::string::npos);
  EXPECT_TRUE(audit.take_warning().empty());  // once
}

TEST(EnergyAudit, TheInstabilityIsStoppedSoonAfterTheWarningAndNamesTheLimit) {
  // Unstable (c dt/m = 2.5): the speed grows by 1.5 per step; unchecked it overflows in about
  // 1 800 steps. The audit with a stop growth of 3 ends it a few steps after its warning.
  double largest_speed = 0.0;
  EnergyAudit audit = staggered_damper(2.5, 5000, 3.0, &largest_speed);
  ASSERT_TRUE(audit.warned_at());
  ASSERT_TRUE(audit.stopped_at());
  EXPECT_GT(*audit.stopped_at(), *audit.warned_at());
  EXPECT_LE(*audit.stopped_at(), *audit.warned_at() + 5);
  EXPECT_LT(largest_speed, 1e3);  // the initial speed scale is 0.1 m/s
  EXPECT_GT(audit.totals().max_coupling_fraction, 0.1);
  const std::string& stop = audit.stop();
  EXPECT_NE(stop.find("by step " + std::to_string(*audit.stopped_at())), std::string::npos) << stop;
  EXPECT_NE(stop.find("since the warning at step " + std::to_string(*audit.warned_at())),
            std::string::npos)
      << stop;
  EXPECT_NE(stop.find("FluidHealth.max_coupling_energy_growth = 3"), std::string::npos) << stop;
  EXPECT_EQ(stop.find("halve"), std::string::npos) << stop;  // the remedy comes apart
  EXPECT_NE(audit.remedy().find("lower the substeps"), std::string::npos);
}

TEST(EnergyAudit, AGivenRemedyEndsTheWarningAndComesWithTheStop) {
  // The session gives the remedy that names the scene's own step and substeps.
  const std::string remedy = "halve SolverOptions.Timeint.step_size (to 5e-05 s)";
  EnergyAudit audit = staggered_damper(2.5, 5000, 3.0, nullptr, remedy);
  ASSERT_TRUE(audit.stopped_at());
  const std::string warning = audit.take_warning();
  EXPECT_EQ(warning.substr(warning.size() - remedy.size()), remedy) << warning;
  EXPECT_EQ(audit.remedy(), remedy);
  EXPECT_EQ(audit.stop().find(remedy), std::string::npos) << audit.stop();
}

TEST(EnergyAudit, AStableDamperIsNeverStoppedAndAZeroGrowthNeverStops) {
  EnergyAudit stable = staggered_damper(0.05, 2000, 3.0);
  EXPECT_FALSE(stable.stopped_at());
  EXPECT_TRUE(stable.stop().empty());
  EXPECT_LT(stable.totals().max_coupling_fraction, 0.01);
  EnergyAudit unchecked = staggered_damper(2.5, 100, 0.0);
  EXPECT_FALSE(unchecked.stopped_at());
  EXPECT_EQ(unchecked.totals().exchanges, 100u);
  EXPECT_TRUE(unchecked.warned_at());  // the warning still fires
}

TEST(EnergyAudit, AOneOffInjectionWarnsButDoesNotStop) {
  // A release: the structure jumps once under a held force (a very light plate that sags in
  // one step), then rests. The energy made at the jump is all of the traffic, so the audit warns
  // at its first judged exchange; it does not grow, so the run goes on.
  EnergyAudit audit(3.0);
  const std::vector<double> v{0.0};
  const std::vector<double> f{1.0};
  audit.start(std::vector<double>{0.0}, v, f);
  for (std::uint64_t n = 1; n <= 500; ++n)
    audit.exchange(std::vector<double>{1e-3}, v, 1e-4, f, n);
  EXPECT_NEAR(audit.totals().coupling_energy, 1e-3, 1e-18);
  ASSERT_TRUE(audit.warned_at());
  EXPECT_EQ(*audit.warned_at(), kAuditFirstJudgedExchange);
  EXPECT_FALSE(audit.stopped_at());
}

TEST(EnergyAudit, TheNoiseFloorIsAMillionthOfTheFluidsEnergyAtATenthOfItsSoundSpeed) {
  // 42 kg/m of water with c = 67.7 m/s: 1/2 M (c/10)^2 = 962.5 J/m.
  EXPECT_NEAR(audit_energy_scale(42.0, 67.7), 0.5 * 42.0 * 6.77 * 6.77, 1e-9);
  EXPECT_NEAR(audit_noise_floor(audit_energy_scale(42.0, 67.7)), 9.625e-4, 1e-7);
  EXPECT_EQ(audit_energy_scale(42.0, 0.0), 0.0);  // c unknown: round-off only
  EXPECT_EQ(audit_noise_floor(0.0), kAuditRoundOff);
  EXPECT_EQ(EnergyAudit(3.0, {}, 0.0).noise_floor(), kAuditRoundOff);
}

// A water front's first touch on a structure at rest (a dam break reaching an obstacle): for a
// few exchanges the structure creeps under the first particles' force while the fluid sees it
// at rest, so all of the tiny traffic is created energy, doubling each step, and then it rests.
EnergyAudit first_touch(double noise_floor) {
  EnergyAudit audit(3.0, {}, noise_floor);
  const std::vector<double> v{0.0};
  const std::vector<double> f{1e-2};  // N/m: the front's first particles
  double x = 0.0;
  audit.start(std::vector<double>{x}, v, std::vector<double>{0.0});
  for (std::uint64_t n = 1; n <= 2000; ++n) {
    if (n > 1000 && n <= 1010) x += 1e-9 * std::pow(2.0, static_cast<double>(n - 1000));
    audit.exchange(std::vector<double>{x}, v, 1e-5, n > 1000 ? f : std::vector<double>{0.0}, n);
  }
  return audit;
}

TEST(EnergyAudit, AFirstTouchBelowTheNoiseFloorIsNotJudged) {
  // The healthy run a user's dam break through an elastic obstacle was stopped by: 2e-8 J/m
  // created at the first touch, against 42 kg/m of water at c = 67.7 m/s (floor 9.6e-4 J/m).
  const EnergyAudit judged_from_round_off = first_touch(kAuditRoundOff);
  EXPECT_NEAR(judged_from_round_off.totals().coupling_energy, 1e-2 * 1e-9 * 2044.0, 1e-15);
  EXPECT_TRUE(judged_from_round_off.warned_at());
  EXPECT_TRUE(judged_from_round_off.stopped_at());  // what happened before the floor
  const EnergyAudit audit = first_touch(audit_noise_floor(audit_energy_scale(42.0, 67.7)));
  EXPECT_EQ(audit.totals().coupling_energy, judged_from_round_off.totals().coupling_energy);
  EXPECT_FALSE(audit.warned_at());
  EXPECT_FALSE(audit.stopped_at());
  EXPECT_EQ(audit.totals().max_coupling_fraction, 0.0);
}

TEST(EnergyAudit, AnInstabilityGrowsThroughTheNoiseFloorAndIsStopped) {
  // The unstable damper starts with 5e-3 J and its energy grows by 2.25 per step; a floor of
  // 1e5 J, 2e7 times that, delays the verdict by a few steps, before the speed reaches 1e3.
  double largest_speed = 0.0;
  const EnergyAudit audit = staggered_damper(2.5, 5000, 3.0, &largest_speed, {}, 1e5);
  ASSERT_TRUE(audit.warned_at());
  ASSERT_TRUE(audit.stopped_at());
  EXPECT_GT(audit.totals().coupling_energy, 1e5);
  EXPECT_LT(largest_speed, 1e3);
  const EnergyAudit from_round_off = staggered_damper(2.5, 5000, 3.0);
  EXPECT_GT(*audit.stopped_at(), *from_round_off.stopped_at());
  EXPECT_LE(*audit.stopped_at(), *from_round_off.stopped_at() + 20);
}

TEST(EnergyAudit, APredictedForceIsTheStructuresWorkAndTheDifferenceIsCreated) {
  // A wall moving uniformly at v under a fluid force f while the structure moves under a
  // predicted f_a: the fluid gets -f v dt, the structure f_a v dt, the coupling makes the rest.
  EnergyAudit audit;
  const double dt = 1e-3, v = 0.2, f = 2.0, f_a = 2.5;
  audit.start(std::vector<double>{0.0}, std::vector<double>{v}, std::vector<double>{f});
  for (std::uint64_t n = 1; n <= 10; ++n) {
    audit.exchange(std::vector<double>{v * dt * static_cast<double>(n)}, std::vector<double>{v}, dt,
                   std::vector<double>{f}, n, std::vector<double>{f_a});
  }
  // The first exchange pairs the start's force (no prediction yet), the other nine f_a.
  EXPECT_NEAR(audit.totals().work_fluid_on_structure, (f + 9 * f_a) * v * dt, 1e-15);
  EXPECT_NEAR(audit.totals().work_structure_on_fluid, -10 * f * v * dt, 1e-15);
  EXPECT_NEAR(audit.totals().coupling_energy, 9 * (f_a - f) * v * dt, 1e-15);
  EXPECT_THROW(audit.exchange(std::vector<double>{0.0}, std::vector<double>{v}, dt,
                              std::vector<double>{f}, 11, std::vector<double>{f, f}),
               Error);
}

// A driven wall moving much water (large traffic, its own books balanced) and a light flap
// beside it whose coupling energy grows geometrically: on the whole's books the flap's energy is
// a few per cent of the traffic (a user's baffle in a rolling tank ran to its end unwarned); on
// its own books it is all of its traffic, warned and stopped, by name.
TEST(EnergyAudit, EachBodyIsJudgedOnItsOwnBooks) {
  const double dt = 1e-3, omega = 5.0, wall_force = 1e3;
  auto run = [&](bool by_body) {
    EnergyAudit audit(3.0);
    if (by_body) audit.set_parts({0, 1}, {"body 'tank'", "body 'flap'"});
    double flap = 0.0, flap_force = 0.0;
    // The wall moves uniformly as it says (its books balance exactly: the whole's coupling
    // energy is the flap's).
    audit.start(std::vector<double>{0.0, 0.0}, std::vector<double>{omega * 0.1, 0.0},
                std::vector<double>{wall_force, 0.0});
    std::uint64_t n = 1;
    for (; n <= 3000; ++n) {
      const double t = dt * static_cast<double>(n);
      // The flap creates energy: it moves by a growing step under a force that follows it,
      // while it tells the fluid it stands still.
      const double step = 1e-7 * std::exp(2.5 * t);
      flap += step;
      flap_force = step * 1e3;
      audit.exchange(std::vector<double>{omega * 0.1 * t, flap},
                     std::vector<double>{omega * 0.1, 0.0}, dt,
                     std::vector<double>{wall_force, flap_force}, n);
      if (!audit.stop().empty()) break;
    }
    return std::make_pair(std::move(audit), n);
  };
  const auto [whole, whole_steps] = run(false);
  EXPECT_TRUE(whole.stop().empty()) << whole.stop();
  EXPECT_FALSE(whole.warned_at().has_value());
  EXPECT_LT(whole.totals().max_coupling_fraction, 0.1);
  auto [bodies, stopped_step] = run(true);
  ASSERT_FALSE(bodies.stop().empty());
  EXPECT_NE(bodies.stop().find("the coupling keeps creating energy at body 'flap'"),
            std::string::npos)
      << bodies.stop();
  EXPECT_EQ(bodies.stop().find("inf times"), std::string::npos) << bodies.stop();
  ASSERT_TRUE(bodies.warned_at().has_value());
  EXPECT_EQ(bodies.warned_at(), bodies.parts()[1].warned_at);
  EXPECT_LT(stopped_step, 3000u);
  EXPECT_NE(bodies.take_warning().find("the coupling has created energy at body 'flap'"),
            std::string::npos);
  ASSERT_EQ(bodies.parts().size(), 2u);
  EXPECT_EQ(bodies.parts()[1].name, "body 'flap'");
  EXPECT_GT(bodies.parts()[1].totals.max_coupling_fraction, 0.1);
  EXPECT_LT(bodies.parts()[0].totals.max_coupling_fraction, 0.1);
  EXPECT_FALSE(bodies.parts()[0].warned_at.has_value());
  // The books add up to the whole's.
  EXPECT_NEAR(bodies.parts()[0].totals.coupling_energy + bodies.parts()[1].totals.coupling_energy,
              bodies.totals().coupling_energy, 1e-12 * bodies.totals().traffic);
}

TEST(EnergyAudit, MismatchedSizesAreABug) {
  EnergyAudit audit;
  const std::vector<double> two(2, 0.0);
  audit.start(two, two, two);
  EXPECT_THROW(audit.exchange(std::vector<double>{0.0}, std::vector<double>{0.0}, 1e-3,
                              std::vector<double>{0.0}, 1),
               Error);
}

}  // namespace
}  // namespace fsi::coupling
