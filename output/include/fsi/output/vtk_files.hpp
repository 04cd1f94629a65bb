#pragma once
// The VTK XML files a run writes for ParaView (docs/user-guide.md, "Outputs"): SPH particles and
// boundary meshes as UnstructuredGrid (.vtu), rigid-body frames as PolyData (.vtp). Every file
// is VTK XML format 1.0 with all numbers in one raw appended block (little endian, UInt64 size
// headers), so it is compact and exact to the last bit.
//
// The encode_* functions return the whole file as bytes; they do not touch the disk (the series
// in series.hpp writes them). Sizes that do not match the frame's counts are programmer errors.

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace fsi::output {

// VTK cell type numbers (vtkCellType.h) used by these files.
inline constexpr std::uint8_t kVtkVertex = 1;
inline constexpr std::uint8_t kVtkLine = 3;
inline constexpr std::uint8_t kVtkTriangle = 5;

// SPH particles at one instant. dimension values per particle in positions and velocities
// (2: z is written as 0).
struct ParticleFrame {
  int dimension = 2;
  double time = 0.0;
  std::span<const std::uint64_t> ids;
  std::span<const double> positions;
  std::span<const double> velocities;
  std::span<const double> density;
  std::span<const double> pressure;
};

// A boundary mesh at one instant: dimension values per vertex in positions, velocities and
// fluid_forces; the first dynamic_vertex_count vertices move with bodies, the rest are static.
// elements: vertex indices, 2 per segment in 2D, 3 per triangle in 3D.
struct BoundaryFrame {
  int dimension = 2;
  double time = 0.0;
  std::span<const double> positions;
  std::span<const double> velocities;
  std::span<const double> fluid_forces;
  std::size_t dynamic_vertex_count = 0;
  std::span<const std::uint32_t> elements;
};

// Rigid-body frames at one instant: one point per body at its reference point (the origin of its
// frame), with the frame's unit axes as point data `axis_x`, `axis_y` (and `axis_z`), so that
// ParaView's Glyph filter draws the frames as arrows (orientation array axis_x, then axis_y).
// 2D only so far: the axes follow from the rotation angle.
struct BodyFrame {
  int dimension = 2;
  double time = 0.0;
  std::vector<std::string> names;     // one per body (field data "body_name")
  std::span<const double> positions;  // dimension values per body
  std::span<const double> velocities;
  std::span<const double> angles;  // 2D: the rotation angle [rad], one per body
};

std::string encode_particles(const ParticleFrame& frame);
std::string encode_boundary(const BoundaryFrame& frame);
std::string encode_bodies(const BodyFrame& frame);

// Centre lines of beam elements at one instant, as PolyData lines (one polyline per line, its
// points in order along the line): for ANCF beams the server samples each element's centre line
// r(x) at a few points per element (not written yet: there are no ANCF elements yet; this is
// the encoder the beams' series in mbd_server/coupling/vtk_output.cpp will use).
struct CentreLineFrame {
  int dimension = 2;
  double time = 0.0;
  std::vector<std::string> names;             // one per line (field data "line_name")
  std::span<const std::size_t> point_counts;  // points of each line, >= 2
  std::span<const double> positions;          // dimension values per point, line after line
  std::span<const double> velocities;         // as positions
};

std::string encode_centre_lines(const CentreLineFrame& frame);

}  // namespace fsi::output
