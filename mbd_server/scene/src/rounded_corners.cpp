#include "fsi/scene/rounded_corners.hpp"

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cmath>
#include <cstddef>
#include <numbers>
#include <string>

#include "fsi/common/error.hpp"
#include "fsi/common/text.hpp"

namespace fsi::scene {
namespace {

using Vector = Eigen::Vector2d;

std::string number(double value) {
  return fsi::significant(value, 4);
}

std::string point_name(std::size_t index, const Point2& at) {
  return "point " + std::to_string(index) + " " + fsi::point_text(at, 4);
}

Vector vector(const Point2& point) {
  return {point[0], point[1]};
}

// One rounded corner: where its arc meets the two edges, and the turn it makes.
struct Corner {
  double tangent_length = 0.0;  // from the point to each tangent point, along its edges
  double turn = 0.0;            // [rad], pi minus the angle between the edges
};

constexpr double kStraight = 1e-12;  // turns below this (rad) are no corner

}  // namespace

std::vector<OutlinePoint> outline_points(const std::vector<std::vector<double>>& rows) {
  std::vector<OutlinePoint> points;
  points.reserve(rows.size());
  for (const auto& row : rows)
    points.push_back({{row.at(0), row.at(1)}, row.size() > 2 ? row[2] : 0.0});
  return points;
}

std::vector<Point2> round_corners(const std::vector<OutlinePoint>& points, bool closed) {
  const std::size_t count = points.size();
  const auto neighbour = [&](std::size_t i, bool after) {
    return after ? (i + 1) % count : (i + count - 1) % count;
  };
  const auto is_corner = [&](std::size_t i) { return closed || (i > 0 && i + 1 < count); };
  constexpr const char* kFixRadius =
      "give the point two values [x, y] for a sharp corner, or a radius >= 0 as its third value";

  std::vector<Corner> corners(count);
  for (std::size_t i = 0; i < count; ++i) {
    const double radius = points[i].radius;
    if (!(radius >= 0.0) || !std::isfinite(radius)) {
      throw Error(point_name(i, points[i].at) + ": the corner radius " + number(radius) +
                      " m is not a length",
                  "", kFixRadius);
    }
    if (radius == 0.0) continue;
    if (!is_corner(i) || count < 3) {
      throw Error(point_name(i, points[i].at) + " has a corner radius (" + number(radius) +
                      " m), but it ends the open outline: there is no corner to round",
                  "", "drop its third value, or close the outline (closed = 1)");
    }
    const Vector back = vector(points[neighbour(i, false)].at) - vector(points[i].at);
    const Vector ahead = vector(points[neighbour(i, true)].at) - vector(points[i].at);
    if (!(back.norm() > 0.0) || !(ahead.norm() > 0.0)) {
      throw Error(point_name(i, points[i].at) + " repeats a neighbour, so its corner (radius " +
                      number(radius) + " m) has no edge to round",
                  "", "remove the repeated point");
    }
    // The angle between the two edges, and the turn the outline makes there.
    const double angle =
        std::atan2(std::abs(back.x() * ahead.y() - back.y() * ahead.x()), back.dot(ahead));
    const double turn = std::numbers::pi - angle;
    if (turn < kStraight) continue;  // a straight run: nothing to round
    if (angle < 1e-6) {
      throw Error(point_name(i, points[i].at) + ": its two edges fold back onto each other, " +
                      "which no arc of radius " + number(radius) + " m can round",
                  "", "drop its corner radius, or move the point");
    }
    corners[i] = {radius / std::tan(0.5 * angle), turn};
  }

  // Each edge holds the arcs of both its ends.
  for (std::size_t i = 0; i < count; ++i) {
    if (!closed && i + 1 == count) break;
    const std::size_t j = neighbour(i, true);
    const double needed = corners[i].tangent_length + corners[j].tangent_length;
    const double edge = (vector(points[j].at) - vector(points[i].at)).norm();
    if (needed > edge * (1.0 + 1e-9)) {
      const double scale = edge / needed;
      throw Error("the edge from " + point_name(i, points[i].at) + " to " +
                      point_name(j, points[j].at) + " is " + number(edge) +
                      " m long, but the arcs rounding its corners take " + number(needed) +
                      " m of it (a radius r takes r / tan(angle / 2) of each edge)",
                  "",
                  "make the radii at most " + number(scale) + " times as large (" +
                      number(points[i].radius * scale) + " and " +
                      number(points[j].radius * scale) + " m), or lengthen the edge");
    }
  }

  std::vector<Point2> outline;
  outline.reserve(count);
  for (std::size_t i = 0; i < count; ++i) {
    const Corner& corner = corners[i];
    if (corner.tangent_length == 0.0) {
      outline.push_back(points[i].at);
      continue;
    }
    const Vector p = vector(points[i].at);
    const Vector u = (vector(points[neighbour(i, false)].at) - p).normalized();
    const Vector w = (vector(points[neighbour(i, true)].at) - p).normalized();
    const Vector start = p + corner.tangent_length * u, end = p + corner.tangent_length * w;
    // The centre lies on the bisector, r / sin(angle / 2) = r / cos(turn / 2) from the point.
    const Vector centre = p + points[i].radius / std::cos(0.5 * corner.turn) * (u + w).normalized();
    const Vector from_centre = start - centre, to_end = end - centre;
    const double sense =
        from_centre.x() * to_end.y() - from_centre.y() * to_end.x() >= 0.0 ? 1.0 : -1.0;
    const double max_bend = kMaxBendDegrees * std::numbers::pi / 180.0;
    const auto pieces = static_cast<int>(std::ceil(corner.turn / max_bend - 1e-9));
    outline.push_back({start.x(), start.y()});
    for (int k = 1; k < pieces; ++k) {
      const Vector on =
          centre +
          Eigen::Rotation2Dd(sense * corner.turn * k / pieces).toRotationMatrix() * from_centre;
      outline.push_back({on.x(), on.y()});
    }
    outline.push_back({end.x(), end.y()});
  }
  return outline;
}

Polygon rounded_polygon(const std::vector<std::vector<double>>& outer,
                        const std::vector<std::vector<std::vector<double>>>& holes) {
  const auto ring = [](const std::vector<std::vector<double>>& rows, const std::string& name) {
    try {
      return round_corners(outline_points(rows), true);
    } catch (const Error& error) {
      throw Error(name + ", " + error.fault(), error.location(), error.remedy());
    }
  };
  Polygon polygon{ring(outer, "the polygon"), {}};
  for (std::size_t n = 0; n < holes.size(); ++n)
    polygon.holes.push_back(ring(holes[n], "hole " + std::to_string(n)));
  return polygon;
}

}  // namespace fsi::scene
