#include "fsi/common/text.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace fsi {
namespace {

TEST(Text, SignificantDigitsInPrintfStyle) {
  EXPECT_EQ(significant(0.012345, 3), "0.0123");
  EXPECT_EQ(significant(17500.0, 3), "1.75e+04");
  EXPECT_EQ(significant(-2.0, 9), "-2");
  EXPECT_EQ(significant(0.1, 17), "0.10000000000000001");
}

TEST(Text, ExactIsTheShortestTextThatReadsBack) {
  EXPECT_EQ(exact(0.1), "0.1");
  EXPECT_EQ(exact(1e-7), "1e-07");
  EXPECT_EQ(exact(0.1 + 0.2), "0.30000000000000004");
  EXPECT_EQ(std::stod(exact(2.0 / 3.0)), 2.0 / 3.0);
}

TEST(Text, PointsIn2DAnd3D) {
  EXPECT_EQ(point_text(std::vector<double>{0.0123456, -1.0}, 4), "(0.01235, -1)");
  EXPECT_EQ(point_text(std::vector<double>{0.1, 0.2, 0.3}, 0), "(0.1, 0.2, 0.3)");
  EXPECT_EQ(point_text(std::vector<double>{}, 3), "()");
}

}  // namespace
}  // namespace fsi
