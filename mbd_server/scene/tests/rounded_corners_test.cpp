#include "fsi/scene/rounded_corners.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "fsi/common/error.hpp"
#include "fsi/test_support/thrown.hpp"

namespace fsi::scene {
namespace {

using test_support::message_thrown;
constexpr double kPi = std::numbers::pi;

double degrees(double value) {
  return value * kPi / 180.0;
}

double area(const std::vector<Point2>& ring) {
  double twice = 0.0;
  for (std::size_t i = 0; i < ring.size(); ++i) {
    const Point2& a = ring[i];
    const Point2& b = ring[(i + 1) % ring.size()];
    twice += a[0] * b[1] - b[0] * a[1];
  }
  return 0.5 * twice;
}

// The open tank outline of examples/wave_flume/corner_tank_rounded.scene, whose points the
// scene writes out one by one with cos and sin: the same points from two radii.
TEST(RoundedCorners, TheTankOfTheExampleFromTwoRadii) {
  const double r = 0.1, width = 0.5;
  const auto rounded =
      round_corners(outline_points({{0, 0.8}, {0, 0, r}, {width, 0, r}, {width, 0.8}}), false);
  std::vector<Point2> written{{0, 0.8}, {0, r}};
  for (int k = 1; k <= 5; ++k) {
    const double a = degrees(15.0 * k);
    written.push_back({r * (1 - std::cos(a)), r * (1 - std::sin(a))});
  }
  written.push_back({r, 0});
  written.push_back({width - r, 0});
  for (int k = 5; k >= 1; --k) {
    const double a = degrees(15.0 * k);
    written.push_back({width - r * (1 - std::cos(a)), r * (1 - std::sin(a))});
  }
  written.push_back({width, r});
  written.push_back({width, 0.8});
  ASSERT_EQ(rounded.size(), written.size());
  for (std::size_t i = 0; i < written.size(); ++i) {
    EXPECT_NEAR(rounded[i][0], written[i][0], 1e-15) << "point " << i;
    EXPECT_NEAR(rounded[i][1], written[i][1], 1e-15) << "point " << i;
  }
}

// Every corner of a triangle, either way round: the arc points lie on the circle of the radius
// about a centre r from both edges, each piece turns by at most 15 degrees, and the area is the
// triangle's less what the arcs cut off.
TEST(RoundedCorners, ArcsTouchBothEdgesInPiecesOfAtMost15Degrees) {
  const std::vector<Point2> triangle{{0, 0}, {1, 0}, {0.3, 0.8}};
  const std::vector<double> radii{0.1, 0.05, 0.12};
  for (bool reversed : {false, true}) {
    std::vector<OutlinePoint> points;
    for (std::size_t i = 0; i < 3; ++i)
      points.push_back({triangle[i], radii[i]});
    if (reversed) std::reverse(points.begin(), points.end());
    const auto ring = round_corners(points, true);
    // Piece by piece, the turn of the outline.
    double total_turn = 0.0;
    for (std::size_t i = 0; i < ring.size(); ++i) {
      const Point2& a = ring[(i + ring.size() - 1) % ring.size()];
      const Point2& b = ring[i];
      const Point2& c = ring[(i + 1) % ring.size()];
      const double in = std::atan2(b[1] - a[1], b[0] - a[0]);
      const double out = std::atan2(c[1] - b[1], c[0] - b[0]);
      double turn = std::remainder(out - in, 2 * kPi);
      EXPECT_LE(std::abs(turn), degrees(15.0) + 1e-12) << "at point " << i;
      total_turn += turn;
    }
    EXPECT_NEAR(std::abs(total_turn), 2 * kPi, 1e-12);
    // The area the arcs cut off: per corner, the kite of the tangent lengths less the pieces'
    // triangles from the centre.
    double cut = 0.0;
    for (std::size_t i = 0; i < 3; ++i) {
      const Point2& p = triangle[i];
      const Point2& q = triangle[(i + 1) % 3];
      const Point2& s = triangle[(i + 2) % 3];
      const double angle =
          std::acos(((q[0] - p[0]) * (s[0] - p[0]) + (q[1] - p[1]) * (s[1] - p[1])) /
                    (std::hypot(q[0] - p[0], q[1] - p[1]) * std::hypot(s[0] - p[0], s[1] - p[1])));
      const double turn = kPi - angle;
      const double r = radii[i];
      const int pieces = static_cast<int>(std::ceil(turn / degrees(15.0) - 1e-9));
      cut += r * r / std::tan(0.5 * angle) - 0.5 * pieces * r * r * std::sin(turn / pieces);
    }
    EXPECT_NEAR(std::abs(area(ring)), std::abs(area(triangle)) - cut, 1e-14);
  }
}

// Each arc point is r from its centre, and the centre r from both edges.
TEST(RoundedCorners, ArcPointsAreTheRadiusFromACentreTheRadiusFromBothEdges) {
  const double r = 0.2;
  // A concave corner of 60 degrees at the origin, between edges along x and at 60 degrees.
  const Point2 along{1, 0}, slanted{std::cos(degrees(60)), std::sin(degrees(60))};
  const auto ring = round_corners(
      outline_points({{along[0], along[1]}, {0, 0, r}, {slanted[0], slanted[1]}}), false);
  // A turn of 120 degrees: 8 pieces, 9 arc points between the two ends.
  ASSERT_EQ(ring.size(), 11u);
  const double to_centre = r / std::sin(degrees(30));
  const Point2 centre{to_centre * std::cos(degrees(30)), to_centre * std::sin(degrees(30))};
  for (std::size_t i = 1; i + 1 < ring.size(); ++i)
    EXPECT_NEAR(std::hypot(ring[i][0] - centre[0], ring[i][1] - centre[1]), r, 1e-15);
  EXPECT_NEAR(ring[1][1], 0.0, 1e-15);  // the first tangent point on the x axis
  EXPECT_NEAR(ring[1][0], r / std::tan(degrees(30)), 1e-15);
}

TEST(RoundedCorners, SharpCornersAndStraightRunsStayAsGiven) {
  const std::vector<std::vector<double>> rows{{0, 0}, {1, 0, 0.3}, {2, 0}, {2, 1}};
  const auto ring = round_corners(outline_points(rows), false);
  ASSERT_EQ(ring.size(), 4u);
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_EQ(ring[i][0], rows[i][0]);
    EXPECT_EQ(ring[i][1], rows[i][1]);
  }
}

TEST(RoundedCorners, BadRadiiSayWhichPointAndWhatFits) {
  const auto open = [](std::vector<std::vector<double>> rows) {
    return message_thrown([&] { round_corners(outline_points(rows), false); }, "(nothing thrown)");
  };
  EXPECT_EQ(
      open({{0, 0}, {1, 0, -0.1}, {1, 1}}),
      "point 1 (1, 0): the corner radius -0.1 m is not a length\n  how to fix: give the point "
      "two values [x, y] for a sharp corner, or a radius >= 0 as its third value");
  EXPECT_NE(open({{0, 0, 0.1}, {1, 0}, {1, 1}})
                .find("point 0 (0, 0) has a corner radius (0.1 m), "
                      "but it ends the open outline"),
            std::string::npos);
  EXPECT_NE(open({{0, 0}, {1, 0, 0.1}, {1, 0}}).find("point 1 (1, 0) repeats a neighbour"),
            std::string::npos);
  EXPECT_NE(open({{0, 0}, {1, 0, 0.1}, {0.5, 0}}).find("fold back onto each other"),
            std::string::npos);
  // Two quarter circles of 0.6 m on an edge of 1 m: 1.2 m needed, both radii times 0.8333.
  const std::string too_large = open({{0, 1}, {0, 0, 0.6}, {1, 0, 0.6}, {1, 1}});
  EXPECT_NE(too_large.find("the edge from point 1 (0, 0) to point 2 (1, 0) is 1 m long, but the "
                           "arcs rounding its corners take 1.2 m of it"),
            std::string::npos)
      << too_large;
  EXPECT_NE(too_large.find("make the radii at most 0.8333 times as large (0.5 and 0.5 m)"),
            std::string::npos)
      << too_large;
  // Exactly filling the edge is allowed.
  EXPECT_EQ(open({{0, 1}, {0, 0, 0.5}, {1, 0, 0.5}, {1, 1}}), "(nothing thrown)");
}

TEST(RoundedCorners, APolygonAndItsHolesAreClosedRings) {
  // A unit square with every corner rounded (r = 0.25) and a square hole with one.
  const Polygon polygon = rounded_polygon({{0, 0, 0.25}, {1, 0, 0.25}, {1, 1, 0.25}, {0, 1, 0.25}},
                                          {{{0.4, 0.4}, {0.6, 0.4, 0.05}, {0.6, 0.6}, {0.4, 0.6}}});
  EXPECT_EQ(polygon.outer.size(), 4u * 7u);
  const double cut = 0.25 * 0.25 * (1.0 - 3.0 * std::sin(degrees(15)));
  EXPECT_NEAR(area(polygon.outer), 1.0 - 4.0 * cut, 1e-14);
  ASSERT_EQ(polygon.holes.size(), 1u);
  EXPECT_EQ(polygon.holes[0].size(), 3u + 7u);
  EXPECT_EQ(polygon_problem(polygon), "");
  EXPECT_NE(message_thrown([] {
              rounded_polygon({{0, 0}, {1, 0}, {1, 1}}, {{{0.5, 0.2, -1}, {0.6, 0.2}, {0.6, 0.3}}});
            }).find("hole 0, point 0 (0.5, 0.2): the corner radius -1 m"),
            std::string::npos);
}

}  // namespace
}  // namespace fsi::scene
