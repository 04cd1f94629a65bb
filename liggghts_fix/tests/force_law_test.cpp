#include "fsi/contact/force_law.hpp"

#include <gtest/gtest.h>

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
