#pragma once
// Thesis eq. (4.11)/(4.12): the counterforce of one particle–wall pair acts at a sampling point
// inside an element (a segment in 2D, a triangle in 3D); it is handed to the element's corner
// vertices in proportion to the sampling point's coordinates in the original element (linear
// weights 1 − g and g on a segment, barycentric weights on a triangle). The shares sum to one and
// reproduce the sampling point as their weighted mean, so the vertex forces keep both the total
// force and the total moment of the pair exactly (the reason the thesis chose this rule).

#include <cstddef>
#include <cstdint>

namespace fsi::contact {

// Subtracts corner_share[c] * force from the force of vertex corner_vertex[c] (Dimension values
// per vertex in vertex_forces): the structure feels −force, the reaction to the pair force on the
// particle.
template <int Dimension, int Corners>
void redistribute(const double (&force)[Dimension], const std::uint32_t (&corner_vertex)[Corners],
                  const double (&corner_share)[Corners], double* vertex_forces) {
  for (int corner = 0; corner < Corners; ++corner) {
    double* target = vertex_forces + Dimension * std::size_t{corner_vertex[corner]};
    for (int k = 0; k < Dimension; ++k)
      target[k] -= corner_share[corner] * force[k];
  }
}

}  // namespace fsi::contact
