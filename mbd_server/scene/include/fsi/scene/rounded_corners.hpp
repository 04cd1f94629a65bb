#pragma once
// Rounded corners for 2D outlines: a Mesh's polyline, a fluid polygon and its holes. A point may
// carry a radius; the corner there becomes an arc of that radius tangent to both of its edges,
// drawn as straight pieces that each turn by at most kMaxBendDegrees. Pure geometry.
//
// Why a scene wants it: in a concave 90° corner of a tank the first particle layers of two walls
// meet in one place and tight particle pairs form there; bends of 15° do not hold them, and a
// radius of 2-4 d removes them (docs/theory.md, "Particle pairs along the walls").

#include <vector>

#include "fsi/scene/fluid_region.hpp"

namespace fsi::scene {

// The largest turn of one straight piece of an arc (docs/theory.md: measured with 15°).
inline constexpr double kMaxBendDegrees = 15.0;

struct OutlinePoint {
  Point2 at{};
  double radius = 0.0;  // 0: a sharp corner
};

// The rows of a scene's `points`: [x, y] (a sharp corner) or [x, y, radius].
std::vector<OutlinePoint> outline_points(const std::vector<std::vector<double>>& rows);

// The outline with each corner of nonzero radius replaced by its arc: the tangent point on the
// edge before, the arc's inner points, the tangent point on the edge after. `closed`: the last
// point joins the first and every point is a corner; open: the two ends are no corners. A point
// with a radius whose edges run straight on keeps its place. Throws fsi::Error (what and how to
// fix, points named by their 0-based index as in the scene) for a negative radius, a radius at an
// open outline's end, a repeated point or edges that fold back onto each other at a rounded
// corner, and two arcs that need more of an edge than it has.
std::vector<Point2> round_corners(const std::vector<OutlinePoint>& points, bool closed);

// A polygon fluid region from the rows of its points and of its holes' points, each ring closed
// and its corners rounded. Throws as round_corners, the ring named ("the polygon", "hole 0").
Polygon rounded_polygon(const std::vector<std::vector<double>>& outer,
                        const std::vector<std::vector<std::vector<double>>>& holes);

}  // namespace fsi::scene
