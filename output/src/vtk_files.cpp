#include "fsi/output/vtk_files.hpp"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <numeric>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "fsi/common/error.hpp"
#include "vtk_document.hpp"

namespace fsi::output {
namespace {

using detail::to_three_components;
using detail::VtkDocument;

std::string count_text(std::size_t count) {
  return std::to_string(count);
}

void check_vectors(std::span<const double> values, std::size_t count, int dimension,
                   const char* what) {
  FSI_ASSERT(values.size() == count * static_cast<std::size_t>(dimension),
             std::string(what) + ": " + std::to_string(values.size()) + " values for " +
                 std::to_string(count) + " items of dimension " + std::to_string(dimension));
}

// ParaView shows a single file's time from this field (the .pvd carries it for a series); the
// names, where given, label the bodies or lines of the file.
void write_field_data(VtkDocument& document, double time, std::string_view names_field = {},
                      const std::vector<std::string>& names = {}) {
  document.open("FieldData");
  const double value[1] = {time};
  document.field_array<double>("TimeValue", value);
  if (!names_field.empty()) document.field_strings(names_field, names);
  document.close();
}

void write_points(VtkDocument& document, std::span<const double> positions, int dimension) {
  document.open("Points");
  document.data_array<double>("Points", 3, to_three_components(positions, dimension));
  document.close();
}

// The cell section ("Cells" of an unstructured grid, "Verts" or "Lines" of poly data): point
// indices of every cell, one past each cell's last index, and for grids the cell types.
void write_cells(VtkDocument& document, std::string_view section,
                 std::span<const std::int64_t> connectivity, std::span<const std::int64_t> offsets,
                 std::optional<std::span<const std::uint8_t>> types = std::nullopt) {
  document.open(section);
  document.data_array<std::int64_t>("connectivity", 1, connectivity);
  document.data_array<std::int64_t>("offsets", 1, offsets);
  // An unstructured grid has the types array even when it has no cells.
  if (types) document.data_array<std::uint8_t>("types", 1, *types);
}

// One vertex cell per point: connectivity i and offset i + 1; the connectivity doubles as the
// point's index.
struct VertexCells {
  std::vector<std::int64_t> connectivity, offsets;
};
VertexCells one_vertex_per_point(std::size_t count) {
  VertexCells cells{std::vector<std::int64_t>(count), std::vector<std::int64_t>(count)};
  std::iota(cells.connectivity.begin(), cells.connectivity.end(), std::int64_t{0});
  std::iota(cells.offsets.begin(), cells.offsets.end(), std::int64_t{1});
  return cells;
}

}  // namespace

std::string encode_particles(const ParticleFrame& frame) {
  const std::size_t count = frame.ids.size();
  check_vectors(frame.positions, count, frame.dimension, "particle positions");
  check_vectors(frame.velocities, count, frame.dimension, "particle velocities");
  FSI_ASSERT(frame.density.size() == count && frame.pressure.size() == count,
             "one density and one pressure per particle");

  VtkDocument document("UnstructuredGrid");
  write_field_data(document, frame.time);
  document.open("Piece", "NumberOfPoints=\"" + count_text(count) + "\" NumberOfCells=\"" +
                             count_text(count) + "\"");
  std::vector<std::int64_t> ids(frame.ids.begin(), frame.ids.end());
  document.open("PointData", "Scalars=\"density\" Vectors=\"velocity\"");
  document.data_array<std::int64_t>("id", 1, ids);
  document.data_array<double>("velocity", 3,
                              to_three_components(frame.velocities, frame.dimension));
  document.data_array<double>("density", 1, frame.density);
  document.data_array<double>("pressure", 1, frame.pressure);
  document.close();
  write_points(document, frame.positions, frame.dimension);
  const VertexCells cells = one_vertex_per_point(count);
  const std::vector<std::uint8_t> types(count, kVtkVertex);
  write_cells(document, "Cells", cells.connectivity, cells.offsets, types);
  return document.finish();
}

std::string encode_boundary(const BoundaryFrame& frame) {
  FSI_ASSERT(frame.dimension == 2 || frame.dimension == 3, "dimension must be 2 or 3");
  const auto dimension = static_cast<std::size_t>(frame.dimension);
  const std::size_t vertex_count = frame.positions.size() / dimension;
  check_vectors(frame.positions, vertex_count, frame.dimension, "boundary positions");
  check_vectors(frame.velocities, vertex_count, frame.dimension, "boundary velocities");
  check_vectors(frame.fluid_forces, vertex_count, frame.dimension, "boundary fluid forces");
  FSI_ASSERT(frame.dynamic_vertex_count <= vertex_count, "more dynamic vertices than vertices");
  // 2D elements are segments (2 vertices), 3D ones triangles (3 vertices).
  const std::size_t per_element = dimension;
  FSI_ASSERT(frame.elements.size() % per_element == 0,
             "element vertex list is not a whole number of elements");
  for (std::uint32_t vertex : frame.elements)
    FSI_ASSERT(vertex < vertex_count, "element vertex index " + std::to_string(vertex) +
                                          " out of range (" + std::to_string(vertex_count) +
                                          " vertices)");
  const std::size_t element_count = frame.elements.size() / per_element;

  VtkDocument document("UnstructuredGrid");
  write_field_data(document, frame.time);
  document.open("Piece", "NumberOfPoints=\"" + count_text(vertex_count) + "\" NumberOfCells=\"" +
                             count_text(element_count) + "\"");
  std::vector<std::uint8_t> dynamic(vertex_count, 0);
  for (std::size_t i = 0; i < frame.dynamic_vertex_count; ++i)
    dynamic[i] = 1;
  document.open("PointData", "Vectors=\"fluid_force\"");
  document.data_array<double>("velocity", 3,
                              to_three_components(frame.velocities, frame.dimension));
  document.data_array<double>("fluid_force", 3,
                              to_three_components(frame.fluid_forces, frame.dimension));
  document.data_array<std::uint8_t>("dynamic", 1, dynamic);
  document.close();
  write_points(document, frame.positions, frame.dimension);
  std::vector<std::int64_t> connectivity(frame.elements.begin(), frame.elements.end());
  std::vector<std::int64_t> offsets(element_count);
  for (std::size_t e = 0; e < element_count; ++e)
    offsets[e] = static_cast<std::int64_t>((e + 1) * per_element);
  const std::vector<std::uint8_t> types(element_count,
                                        frame.dimension == 2 ? kVtkLine : kVtkTriangle);
  write_cells(document, "Cells", connectivity, offsets, types);
  return document.finish();
}

std::string encode_bodies(const BodyFrame& frame) {
  const std::size_t count = frame.names.size();
  check_vectors(frame.positions, count, frame.dimension, "body positions");
  check_vectors(frame.velocities, count, frame.dimension, "body velocities");
  FSI_ASSERT(frame.angles.size() == count, "one angle per body");

  VtkDocument document("PolyData");
  write_field_data(document, frame.time, "body_name", frame.names);
  document.open("Piece", "NumberOfPoints=\"" + count_text(count) + "\" NumberOfVerts=\"" +
                             count_text(count) +
                             "\" NumberOfLines=\"0\" NumberOfStrips=\"0\" NumberOfPolys=\"0\"");
  const VertexCells cells = one_vertex_per_point(count);
  FSI_ASSERT(frame.dimension == 2, "body frames: 2D only so far (axes from the angle)");
  std::vector<double> axis_x(3 * count), axis_y(3 * count), axis_z(3 * count, 0.0);
  for (std::size_t i = 0; i < count; ++i) {
    const double c = std::cos(frame.angles[i]), s = std::sin(frame.angles[i]);
    axis_x[3 * i] = c;
    axis_x[3 * i + 1] = s;
    axis_y[3 * i] = -s;
    axis_y[3 * i + 1] = c;
    axis_z[3 * i + 2] = 1.0;
  }
  document.open("PointData", "Vectors=\"velocity\"");
  document.data_array<std::int64_t>("body_index", 1, cells.connectivity);
  document.data_array<double>("angle", 1, frame.angles);
  document.data_array<double>("axis_x", 3, axis_x);
  document.data_array<double>("axis_y", 3, axis_y);
  document.data_array<double>("axis_z", 3, axis_z);
  document.data_array<double>("velocity", 3,
                              to_three_components(frame.velocities, frame.dimension));
  document.close();
  write_points(document, frame.positions, frame.dimension);
  write_cells(document, "Verts", cells.connectivity, cells.offsets);
  return document.finish();
}

std::string encode_centre_lines(const CentreLineFrame& frame) {
  const std::size_t line_count = frame.names.size();
  FSI_ASSERT(frame.point_counts.size() == line_count, "one point count per centre line");
  for (std::size_t points : frame.point_counts)
    FSI_ASSERT(points >= 2, "a centre line needs at least 2 points");
  const std::size_t count =
      std::accumulate(frame.point_counts.begin(), frame.point_counts.end(), std::size_t{0});
  check_vectors(frame.positions, count, frame.dimension, "centre-line positions");
  check_vectors(frame.velocities, count, frame.dimension, "centre-line velocities");

  VtkDocument document("PolyData");
  write_field_data(document, frame.time, "line_name", frame.names);
  document.open("Piece", "NumberOfPoints=\"" + count_text(count) +
                             "\" NumberOfVerts=\"0\" NumberOfLines=\"" + count_text(line_count) +
                             "\" NumberOfStrips=\"0\" NumberOfPolys=\"0\"");
  std::vector<std::int64_t> line_index, connectivity(count), offsets;
  std::iota(connectivity.begin(), connectivity.end(), std::int64_t{0});
  std::int64_t end = 0;
  for (std::size_t line = 0; line < line_count; ++line) {
    line_index.insert(line_index.end(), frame.point_counts[line], static_cast<std::int64_t>(line));
    end += static_cast<std::int64_t>(frame.point_counts[line]);
    offsets.push_back(end);
  }
  document.open("PointData", "Vectors=\"velocity\"");
  document.data_array<std::int64_t>("line_index", 1, line_index);
  document.data_array<double>("velocity", 3,
                              to_three_components(frame.velocities, frame.dimension));
  document.close();
  write_points(document, frame.positions, frame.dimension);
  write_cells(document, "Lines", connectivity, offsets);
  return document.finish();
}

}  // namespace fsi::output
