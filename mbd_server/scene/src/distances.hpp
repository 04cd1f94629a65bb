#pragma once
// Distances of a point to a segment and to a triangle (internal to fsi::scene): a wall pressure
// probe's patch against its mesh, and the crossing check's "touching at the start".

#include <algorithm>
#include <cmath>

namespace fsi::scene::detail {

// Distance of p to the segment a-b (dimension coordinates each).
inline double distance_to_segment(const double* p, const double* a, const double* b,
                                  int dimension) {
  double along = 0.0, length2 = 0.0;
  for (int k = 0; k < dimension; ++k) {
    along += (p[k] - a[k]) * (b[k] - a[k]);
    length2 += (b[k] - a[k]) * (b[k] - a[k]);
  }
  const double t = length2 > 0.0 ? std::clamp(along / length2, 0.0, 1.0) : 0.0;
  double distance2 = 0.0;
  for (int k = 0; k < dimension; ++k) {
    const double gap = p[k] - a[k] - t * (b[k] - a[k]);
    distance2 += gap * gap;
  }
  return std::sqrt(distance2);
}

// Distance of p to the triangle a, b, c in 3D: to its plane where p's foot lies inside it,
// otherwise to its nearest edge.
inline double distance_to_triangle(const double* p, const double* a, const double* b,
                                   const double* c) {
  const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  const double v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  const double w[3] = {p[0] - a[0], p[1] - a[1], p[2] - a[2]};
  const double uu = u[0] * u[0] + u[1] * u[1] + u[2] * u[2];
  const double uv = u[0] * v[0] + u[1] * v[1] + u[2] * v[2];
  const double vv = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
  const double wu = w[0] * u[0] + w[1] * u[1] + w[2] * u[2];
  const double wv = w[0] * v[0] + w[1] * v[1] + w[2] * v[2];
  const double determinant = uu * vv - uv * uv;
  double edges = std::min({distance_to_segment(p, a, b, 3), distance_to_segment(p, b, c, 3),
                           distance_to_segment(p, c, a, 3)});
  if (!(determinant > 0.0)) return edges;
  const double s = (vv * wu - uv * wv) / determinant, t = (uu * wv - uv * wu) / determinant;
  if (s < 0.0 || t < 0.0 || s + t > 1.0) return edges;
  double gap2 = 0.0;
  for (int k = 0; k < 3; ++k) {
    const double gap = w[k] - s * u[k] - t * v[k];
    gap2 += gap * gap;
  }
  return std::sqrt(gap2);
}

}  // namespace fsi::scene::detail
