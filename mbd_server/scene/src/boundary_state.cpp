// Where the boundary vertices are (the model's markers, then the static 3D ground) and which
// body carries each.

#include <algorithm>
#include <map>

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

mbd::BodyId vertex_body(const BoundaryMesh& boundary, const mbd::Model& model, std::uint32_t v) {
  return v < boundary.dynamic_vertex_count ? model.marker_body(static_cast<int>(v)) : mbd::kGround;
}

std::vector<BodyElements> elements_by_body(const BoundaryMesh& boundary, const mbd::Model& model) {
  const auto corners = static_cast<std::size_t>(boundary.dimension);
  const std::vector<std::uint32_t>& elements = boundary.elements();
  std::vector<BodyElements> parts;
  std::map<mbd::BodyId, std::size_t> part_of_body;
  for (std::size_t e = 0; e + corners <= elements.size(); e += corners) {
    const mbd::BodyId body = vertex_body(boundary, model, elements[e]);
    auto [found, added] = part_of_body.emplace(body, parts.size());
    if (added) parts.push_back({body, {}});
    auto& part = parts[found->second].elements;
    part.insert(part.end(), elements.begin() + static_cast<std::ptrdiff_t>(e),
                elements.begin() + static_cast<std::ptrdiff_t>(e + corners));
  }
  return parts;
}

}  // namespace fsi::scene
