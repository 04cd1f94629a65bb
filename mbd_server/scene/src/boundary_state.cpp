// Where the boundary vertices are: the model's markers, then the static 3D ground.

#include <algorithm>

#include "fsi/common/error.hpp"
#include "fsi/mbd/readouts.hpp"
#include "fsi/scene/scene.hpp"

namespace fsi::scene {

void boundary_state(const BoundaryMesh& boundary, const mbd::Model& model, const mbd::State& state,
                    std::vector<double>& positions, std::vector<double>& velocities) {
  const auto dimension = static_cast<std::size_t>(boundary.dimension);
  const std::size_t dynamic = dimension * boundary.dynamic_vertex_count;
  FSI_ASSERT(boundary.dynamic_vertex_count == static_cast<std::size_t>(model.marker_count()) ||
                 dimension == 2,
             "3D dynamic vertices are the model's markers");
  positions.assign(dimension * boundary.vertex_count, 0.0);
  velocities.assign(positions.size(), 0.0);
  if (dimension == 2) {
    marker_positions(model, state, positions);  // 2D: every vertex is a marker (ground ones too)
    marker_velocities(model, state, velocities);
    return;
  }
  if (dynamic > 0) {
    marker_positions(model, state, std::span<double>(positions.data(), dynamic));
    marker_velocities(model, state, std::span<double>(velocities.data(), dynamic));
  }
  FSI_ASSERT(dynamic + boundary.static_positions.size() == positions.size(),
             "3D boundary vertices do not add up");
  std::copy(boundary.static_positions.begin(), boundary.static_positions.end(),
            positions.begin() + static_cast<std::ptrdiff_t>(dynamic));
}

}  // namespace fsi::scene
