#include "fsi/contact/force_law.hpp"

#include <gtest/gtest.h>

#include "contact_test_support.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace fsi::contact {
namespace {

ForceLaw thesis_law(double r0) {
  ForceLaw law;
  law.repulsion_scale = 1000.0;
  law.viscous_scale = 2.0;
  law.cutoff = 2.0;  // h = 1
  law.equilibrium_distance = r0;
  return law;
}

TEST(ForceLaw, RepulsionEqualsScaleAtContactAndVanishesAtEquilibriumAndCutoff) {
  for (double r0 : {0.5, 1.0, 1.5, 2.0}) {
    const ForceLaw law = thesis_law(r0);
    EXPECT_NEAR(law.repulsion(0.0), 1000.0, 1e-12) << "r0 = " << r0;
    EXPECT_NEAR(law.repulsion(r0), 0.0, 1e-12) << "r0 = " << r0;
    EXPECT_NEAR(law.repulsion(2.0), 0.0, 1e-12);
    EXPECT_EQ(law.repulsion(2.5), 0.0);
  }
}

TEST(ForceLaw, MatchesThesisEquationWithSmoothingLength) {
  // Eq. (4.2) written with h: k [(2h-r)^4 - (2h-r0)^2 (2h-r)^2] / (4 h^2 r0 (4h - r0)).
  const double h = 0.7;
  const double r0 = 0.9;
  ForceLaw law{500.0, 0.0, r0, 2.0 * h};
  for (double r = 0.0; r < 2.0 * h; r += 0.05) {
    const double a = 2.0 * h - r;
    const double b = 2.0 * h - r0;
    const double expected =
        500.0 * (a * a * a * a - b * b * a * a) / (4 * h * h * r0 * (4 * h - r0));
    EXPECT_NEAR(law.repulsion(r), expected, 1e-10 * 500.0) << "r = " << r;
  }
}

TEST(ForceLaw, AdhesionBetweenEquilibriumDistanceAndCutoff) {
  const ForceLaw law = thesis_law(1.0);
  EXPECT_GT(law.repulsion(0.5), 0.0);
  EXPECT_LT(law.repulsion(1.5), 0.0);
  const ForceLaw no_adhesion = thesis_law(2.0);
  for (double r = 0.0; r < 2.0; r += 0.1)
    EXPECT_GE(no_adhesion.repulsion(r), 0.0);
}

TEST(ForceLaw, ViscousWeightIsRenormalisedSpikyLaplacian) {
  // Eq. (5.5): (1/alpha) Laplacian W = 2 - r/h, and f_visc = -(t/2)(2 - r/h) v_rel.
  const ForceLaw law = thesis_law(2.0);
  const double h = 1.0;
  for (double r = 0.0; r < 2.0; r += 0.1) {
    EXPECT_NEAR(law.viscous_weight(r), 0.5 * (2.0 - r / h), 1e-15);
  }
  EXPECT_EQ(law.viscous_weight(2.0), 0.0);
}

TEST(ForceLaw, ValidationNamesTheParameter) {
  ForceLaw law = thesis_law(2.0);
  law.equilibrium_distance = 3.0;
  try {
    law.validate();
    FAIL() << "r0 > cutoff accepted";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("r0"), std::string::npos) << error.what();
  }
  law = thesis_law(2.0);
  law.cutoff = -1.0;
  EXPECT_THROW(law.validate(), std::invalid_argument);
  law = thesis_law(2.0);
  law.repulsion_scale = -1.0;
  EXPECT_THROW(law.validate(), std::invalid_argument);
}

}  // namespace
}  // namespace fsi::contact

namespace fsi::contact {
namespace {

// The physics checks take the wall's stiffness from here: it must be the steepest slope of the
// law the fix evaluates, found here by central differences over the whole range.
TEST(ForceLaw, SteepestRepulsionSlopeIsTheLargestSlopeOfTheLaw) {
  auto steepest_by_differences = [](const ForceLaw& law, double from) {
    const double step = 1e-6 * law.cutoff;
    double steepest = 0.0;
    for (double d = from; d + step < law.cutoff; d += 1e-3 * law.cutoff) {
      const double slope = (law.repulsion(d + step) - law.repulsion(d - step)) / (2.0 * step);
      steepest = std::max(steepest, std::abs(slope));
    }
    return steepest;
  };
  for (double r0 : {0.5, 1.0, 1.5, 2.0}) {
    const ForceLaw law = thesis_law(r0);
    // One-sided at contact, where the slope is largest.
    const double step = 1e-7;
    const double at_contact = std::abs(law.repulsion(step) - law.repulsion(0.0)) / step;
    EXPECT_NEAR(law.steepest_repulsion_slope(), at_contact, 1e-5 * at_contact) << "r0 = " << r0;
    EXPECT_GE(law.steepest_repulsion_slope() * (1.0 + 1e-6), steepest_by_differences(law, step))
        << "r0 = " << r0;
  }
  EXPECT_DOUBLE_EQ(thesis_law(2.0).steepest_repulsion_slope(), 4.0 * 1000.0 / 2.0);
  ForceLaw lj = thesis_law(0.5);
  lj.repulsion_law = RepulsionLaw::LennardJones;
  const double core = 0.05;  // r0 / 10: inside it the law is constant
  const double just_outside = steepest_by_differences(lj, core + 3e-6);
  EXPECT_NEAR(lj.steepest_repulsion_slope(), just_outside, 2e-3 * just_outside);
}

TEST(ForceLaw, LennardJonesIsThesisEquation43WithAFiniteCore) {
  ForceLaw law = thesis_law(0.5);
  law.repulsion_law = RepulsionLaw::LennardJones;
  law.lj_p1 = 12;
  law.lj_p2 = 6;
  ASSERT_NO_THROW(law.validate());
  for (double d = 0.05; d < 2.0; d += 0.05) {
    const double q = 0.5 / d;
    EXPECT_NEAR(law.repulsion(d), 1000.0 * (std::pow(q, 12) - std::pow(q, 6)),
                1e-12 * std::abs(1000.0 * std::pow(q, 12)))
        << "d = " << d;
  }
  EXPECT_NEAR(law.repulsion(0.5), 0.0, 1e-12);
  EXPECT_LT(law.repulsion(1.0), 0.0);  // attractive beyond r0
  EXPECT_EQ(law.repulsion(2.0), 0.0);  // truncated at the cut-off
  // Below r0/10 the law is held at its value there: finite at zero distance.
  EXPECT_EQ(law.repulsion(0.0), law.repulsion(0.05));
  EXPECT_EQ(law.repulsion(1e-300), law.repulsion(0.05));
  EXPECT_TRUE(std::isfinite(law.repulsion(0.0)));
  law.lj_p2 = 12;
  EXPECT_THROW(law.validate(), std::invalid_argument);
}

TEST(ForceLaw, CubicSplineViscousWeightIsSmoothAndMatchesSpikyAtContact) {
  ForceLaw law = thesis_law(2.0);
  law.viscous_kernel = ViscousKernel::CubicSpline;
  EXPECT_EQ(law.viscous_weight(0.0), 1.0);
  ForceLaw spiky = thesis_law(2.0);
  EXPECT_EQ(spiky.viscous_weight(0.0), law.viscous_weight(0.0));
  // (3.22) with R = d/h, h = 1: 1 - 1.5 R^2 + 0.75 R^3 for R < 1, 0.25 (2 - R)^3 for R < 2.
  EXPECT_NEAR(law.viscous_weight(0.5), 1.0 - 1.5 * 0.25 + 0.75 * 0.125, 1e-15);
  EXPECT_NEAR(law.viscous_weight(1.5), 0.25 * 0.125, 1e-15);
  // Continuous with continuous slope at R = 1 and at the support.
  const double e = 1e-7;
  EXPECT_NEAR(law.viscous_weight(1.0 - e), law.viscous_weight(1.0 + e), 1e-6);
  EXPECT_NEAR((law.viscous_weight(1.0) - law.viscous_weight(1.0 - e)) / e,
              (law.viscous_weight(1.0 + e) - law.viscous_weight(1.0)) / e, 1e-5);
  EXPECT_NEAR(law.viscous_weight(2.0 - e), 0.0, 1e-12);
  EXPECT_EQ(law.viscous_weight(2.0), 0.0);
  for (double d = 0.0; d < 2.0; d += 0.01)
    EXPECT_GE(law.viscous_weight(d), 0.0);
}

TEST(ForceLaw, SeparateViscousCutoff) {
  ForceLaw law = thesis_law(2.0);
  law.viscous_cutoff = 3.0;
  ASSERT_NO_THROW(law.validate());
  EXPECT_EQ(law.range(), 3.0);
  EXPECT_EQ(law.repulsion(2.5), 0.0);
  EXPECT_NEAR(law.viscous_weight(1.5), 0.5, 1e-15);  // 1 - 1.5/3
  EXPECT_EQ(law.viscous_weight(3.0), 0.0);
  law.viscous_cutoff = 1.0;  // shorter than the repulsion: the search radius stays r_c
  EXPECT_EQ(law.range(), 2.0);
  EXPECT_EQ(law.viscous_weight(1.5), 0.0);
  EXPECT_GT(law.repulsion(1.5), 0.0);
  law.viscous_cutoff = -1.0;
  EXPECT_THROW(law.validate(), std::invalid_argument);
}

TEST(ForceLaw, NonFiniteDistancesGiveNoForce) {
  const ForceLaw law = thesis_law(1.0);
  EXPECT_EQ(law.repulsion(std::nan("")), 0.0);
  EXPECT_EQ(law.viscous_weight(std::nan("")), 0.0);
}

}  // namespace
}  // namespace fsi::contact

namespace fsi::contact {
namespace {

ForceLaw repulsive_law(double k, double cutoff) {
  ForceLaw law;
  law.repulsion_scale = k;
  law.cutoff = cutoff;
  law.equilibrium_distance = cutoff;
  return law;
}

TEST(FlatWall, ThreeDimensionalForceMatchesClosedForm) {
  // r0 = r_c: f = k (1 - r/r_c)^4, so F(z) = 2 pi z k r_c (1 - z/r_c)^5 / 5.
  const ForceLaw law = repulsive_law(1000.0, 0.003);
  for (double z : {0.0003, 0.001, 0.002, 0.0029}) {
    const double expected =
        2.0 * std::numbers::pi * z * 1000.0 * 0.003 * std::pow(1.0 - z / 0.003, 5) / 5.0;
    EXPECT_NEAR(flat_wall_force(law, z, 3), expected, 1e-11 * std::abs(expected)) << "z = " << z;
  }
  EXPECT_EQ(flat_wall_force(law, 0.003, 3), 0.0);
}

TEST(FlatWall, TwoDimensionalForceMatchesTheWallIntegral) {
  // The same line integral the 2D contact accuracy is measured against (Gauss-Kronrod).
  for (const ForceLaw& law :
       {repulsive_law(17500.0, 0.0038), test_support::adhesive_law(0.0038, 0.0)}) {
    for (double z : {0.0002, 0.001, 0.0019, 0.003}) {
      const double exact = test_support::exact_wall_repulsion(law, z, 15, 1e-14);
      EXPECT_NEAR(flat_wall_force(law, z, 2), exact, 1e-10 * std::abs(exact) + 1e-14)
          << "z = " << z << ", r0 = " << law.equilibrium_distance;
    }
  }
}

TEST(FlatWall, RestDistanceBalancesThePressureOnALatticeCell) {
  const double d = 0.002;
  const ForceLaw law = repulsive_law(17500.0, 3.8 * d);
  for (int dimension : {2, 3}) {
    for (double pressure : {100.0, 490.0, 2000.0}) {
      const double z = rest_distance(law, pressure, d, dimension);
      const double load = pressure * (dimension == 3 ? d * d : d);
      EXPECT_GT(z, 0.0);
      EXPECT_NEAR(flat_wall_force(law, z, dimension), load, 1e-9 * load)
          << dimension << "D, p = " << pressure;
    }
  }
  // The same law rests the first layer at 2.5 d under 490 Pa in 2D (measured in a coupled run:
  // 2.47-2.62 d, docs/validation.md, "True shape").
  EXPECT_NEAR(rest_distance(law, 490.0, d, 2) / d, 2.50, 0.01);
  // More pressure, closer; a pressure the wall cannot hold at any distance: 0.
  EXPECT_LT(rest_distance(law, 2000.0, d, 2), rest_distance(law, 100.0, d, 2));
  EXPECT_EQ(rest_distance(law, 1e12, d, 2), 0.0);
}

TEST(TrueShape, FirstLayerRestsAtItsFractionOfTheSpacingAtTheReferencePressure) {
  for (int dimension : {2, 3}) {
    for (double d : {0.001, 0.002, 0.05}) {
      ForceLaw law;
      law.viscous_scale = 3.0;
      apply_true_shape(law, TrueShape{d, 490.0}, dimension);
      EXPECT_EQ(law.viscous_scale, 3.0);
      EXPECT_EQ(law.repulsion_law, RepulsionLaw::Thesis);
      EXPECT_DOUBLE_EQ(law.cutoff, kTrueShapeCutoffFraction * d);
      EXPECT_DOUBLE_EQ(law.equilibrium_distance, law.cutoff);
      EXPECT_NEAR(rest_distance(law, 490.0, d, dimension) / d, kTrueShapeRestFraction, 1e-9)
          << dimension << "D, d = " << d;
      EXPECT_NO_THROW(law.validate());
    }
  }
}

TEST(TrueShape, RefusesMissingSpacingOrPressure) {
  ForceLaw law;
  EXPECT_THROW(apply_true_shape(law, TrueShape{0.0, 490.0}, 2), std::invalid_argument);
  EXPECT_THROW(apply_true_shape(law, TrueShape{0.002, -1.0}, 2), std::invalid_argument);
  EXPECT_THROW(apply_true_shape(law, TrueShape{0.002, 490.0}, 4), std::invalid_argument);
}

}  // namespace
}  // namespace fsi::contact
