#include "boundary_share.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace fsi::client {
namespace {

void check_dimension(int dimension) {
  if (dimension != 2 && dimension != 3) {
    throw std::invalid_argument("boundary share: dimension must be 2 or 3, got " +
                                std::to_string(dimension));
  }
}

// The vertices used by `elements` (whole-mesh indices), ascending, and how many are dynamic.
void collect_vertices(const WholeMesh& mesh, BoundaryShare& share) {
  const auto per_element = static_cast<std::size_t>(mesh.dimension);
  for (const std::uint32_t element : share.elements) {
    for (std::size_t c = 0; c < per_element; ++c)
      share.vertices.push_back(mesh.elements[element * per_element + c]);
  }
  std::sort(share.vertices.begin(), share.vertices.end());
  share.vertices.erase(std::unique(share.vertices.begin(), share.vertices.end()),
                       share.vertices.end());
  share.dynamic_vertices = static_cast<std::size_t>(
      std::lower_bound(share.vertices.begin(), share.vertices.end(), mesh.dynamic_vertex_count) -
      share.vertices.begin());
}

void check_mesh(const WholeMesh& mesh) {
  check_dimension(mesh.dimension);
  const auto per_element = static_cast<std::size_t>(mesh.dimension);
  const std::size_t vertex_count = mesh.positions.size() / per_element;
  if (mesh.elements.size() % per_element != 0) {
    throw std::invalid_argument("boundary share: " + std::to_string(mesh.elements.size()) +
                                " element vertex indices are not " + std::to_string(per_element) +
                                " per element");
  }
  for (std::size_t i = 0; i < mesh.elements.size(); ++i) {
    if (mesh.elements[i] >= vertex_count) {
      throw std::invalid_argument("boundary share: element " + std::to_string(i / per_element) +
                                  " names vertex " + std::to_string(mesh.elements[i]) +
                                  " of a mesh with " + std::to_string(vertex_count));
    }
  }
}

}  // namespace

bool ShareBox::empty(int dimension) const {
  for (int k = 0; k < dimension; ++k) {
    if (!(low[k] <= high[k])) return true;
  }
  return false;
}

void ShareBox::include(std::span<const double> point, int dimension) {
  for (int k = 0; k < dimension; ++k) {
    low[k] = std::min(low[k], point[k]);
    high[k] = std::max(high[k], point[k]);
  }
}

void ShareBox::include(const ShareBox& other, int dimension) {
  if (other.empty(dimension)) return;
  for (int k = 0; k < dimension; ++k) {
    low[k] = std::min(low[k], other.low[k]);
    high[k] = std::max(high[k], other.high[k]);
  }
}

ShareBox ShareBox::widened(double margin, int dimension) const {
  if (empty(dimension)) return *this;
  ShareBox grown = *this;
  for (int k = 0; k < dimension; ++k) {
    grown.low[k] -= margin;
    grown.high[k] += margin;
  }
  return grown;
}

bool ShareBox::contains(std::span<const double> point, int dimension) const {
  for (int k = 0; k < dimension; ++k) {
    if (!(point[k] >= low[k] && point[k] <= high[k])) return false;
  }
  return true;
}

bool ShareBox::meets(const ShareBox& other, int dimension) const {
  if (empty(dimension) || other.empty(dimension)) return false;
  for (int k = 0; k < dimension; ++k) {
    if (other.high[k] < low[k] || other.low[k] > high[k]) return false;
  }
  return true;
}

ShareBox bounding_box(std::span<const double> positions, int dimension) {
  check_dimension(dimension);
  const auto d = static_cast<std::size_t>(dimension);
  ShareBox box;
  for (std::size_t i = 0; i + d <= positions.size(); i += d)
    box.include(positions.subspan(i, d), dimension);
  return box;
}

BoundaryShare select_share(const WholeMesh& mesh, const ShareBox& covered, double reach,
                           const SharePeriodicity& periodicity) {
  check_mesh(mesh);
  if (!(reach >= 0.0)) {
    throw std::invalid_argument("boundary share: the reach must be >= 0, got " +
                                std::to_string(reach));
  }
  const int dimension = mesh.dimension;
  BoundaryShare share;
  if (covered.empty(dimension)) return share;
  // The covered box and its periodic images (shifts of -1, 0, +1 period per periodic axis).
  std::vector<ShareBox> images{covered};
  for (int k = 0; k < dimension; ++k) {
    if (!periodicity.periodic[k]) continue;
    const std::size_t before = images.size();
    for (std::size_t i = 0; i < before; ++i) {
      for (const double sign : {-1.0, 1.0}) {
        ShareBox shifted = images[i];
        shifted.low[k] += sign * periodicity.period[k];
        shifted.high[k] += sign * periodicity.period[k];
        images.push_back(shifted);
      }
    }
  }
  const auto per_element = static_cast<std::size_t>(dimension);
  const std::size_t element_count = mesh.elements.size() / per_element;
  for (std::size_t e = 0; e < element_count; ++e) {
    ShareBox element;
    for (std::size_t c = 0; c < per_element; ++c) {
      const std::size_t vertex = mesh.elements[e * per_element + c];
      element.include(mesh.positions.subspan(vertex * per_element, per_element), dimension);
    }
    const ShareBox reached = element.widened(reach, dimension);
    if (std::any_of(images.begin(), images.end(),
                    [&](const ShareBox& image) { return reached.meets(image, dimension); }))
      share.elements.push_back(static_cast<std::uint32_t>(e));
  }
  collect_vertices(mesh, share);
  return share;
}

BoundaryShare whole_share(const WholeMesh& mesh) {
  check_mesh(mesh);
  BoundaryShare share;
  const std::size_t element_count = mesh.elements.size() / static_cast<std::size_t>(mesh.dimension);
  share.elements.resize(element_count);
  for (std::size_t e = 0; e < element_count; ++e)
    share.elements[e] = static_cast<std::uint32_t>(e);
  collect_vertices(mesh, share);
  return share;
}

LocalMesh local_mesh(const WholeMesh& mesh, std::span<const double> velocities,
                     const BoundaryShare& share) {
  const int dimension = mesh.dimension;
  const auto per_element = static_cast<std::size_t>(dimension);
  LocalMesh local;
  local.positions = share_values(mesh.positions, share.vertices, share.vertices.size(), dimension);
  local.velocities = share_values(velocities, share.vertices, share.vertices.size(), dimension);
  local.elements.reserve(share.elements.size() * per_element);
  for (const std::uint32_t element : share.elements) {
    for (std::size_t c = 0; c < per_element; ++c) {
      const std::uint32_t vertex = mesh.elements[element * per_element + c];
      const auto at = std::lower_bound(share.vertices.begin(), share.vertices.end(), vertex);
      local.elements.push_back(static_cast<std::uint32_t>(at - share.vertices.begin()));
    }
  }
  return local;
}

std::vector<double> share_values(std::span<const double> whole,
                                 std::span<const std::uint32_t> vertices, std::size_t count,
                                 int dimension) {
  const auto d = static_cast<std::size_t>(dimension);
  std::vector<double> values(count * d);
  for (std::size_t i = 0; i < count; ++i) {
    for (std::size_t k = 0; k < d; ++k)
      values[i * d + k] = whole[vertices[i] * d + k];
  }
  return values;
}

void add_share_values(std::span<const double> share, std::span<const std::uint32_t> vertices,
                      std::size_t count, int dimension, std::span<double> whole) {
  const auto d = static_cast<std::size_t>(dimension);
  for (std::size_t i = 0; i < count; ++i) {
    for (std::size_t k = 0; k < d; ++k)
      whole[vertices[i] * d + k] += share[i * d + k];
  }
}

double largest_displacement(std::span<const double> a, std::span<const double> b, int dimension) {
  const auto d = static_cast<std::size_t>(dimension);
  double largest_squared = 0.0;
  for (std::size_t i = 0; i + d <= std::min(a.size(), b.size()); i += d) {
    double squared = 0.0;
    for (std::size_t k = 0; k < d; ++k)
      squared += (a[i + k] - b[i + k]) * (a[i + k] - b[i + k]);
    largest_squared = std::max(largest_squared, squared);
  }
  return std::sqrt(largest_squared);
}

}  // namespace fsi::client
