#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <regex>
#include <string>
#include <vector>

#include "fsi/output/vtk_files.hpp"

namespace fsi::output {
namespace {

// One <DataArray format="appended"> of a file and its block in the appended data.
struct Array {
  std::string type;
  std::string name;
  int components = 1;
  std::uint64_t offset = 0;
  std::uint64_t size_header = 0;  // the UInt64 in front of the block
  std::string bytes;              // the block's values
};

struct Parsed {
  std::string xml;       // everything before the '_' that opens the appended data
  std::string appended;  // everything after it, up to the closing newline
  std::vector<Array> arrays;
};

Parsed parse(const std::string& file) {
  Parsed parsed;
  const std::string opening = "<AppendedData encoding=\"raw\">\n   _";
  const auto start = file.find(opening);
  EXPECT_NE(start, std::string::npos) << "no raw appended data";
  const std::string closing = "\n  </AppendedData>\n</VTKFile>\n";
  EXPECT_TRUE(file.ends_with(closing)) << "file does not end with the appended data and VTKFile";
  parsed.xml = file.substr(0, start);
  const auto data_begin = start + opening.size();
  parsed.appended = file.substr(data_begin, file.size() - closing.size() - data_begin);

  const std::regex pattern(
      "<DataArray type=\"(\\w+)\" Name=\"(\\w+)\"(?: NumberOfComponents=\"(\\d+)\")?"
      "(?: NumberOfTuples=\"\\d+\")? format=\"appended\" offset=\"(\\d+)\"/>");
  for (auto it = std::sregex_iterator(parsed.xml.begin(), parsed.xml.end(), pattern);
       it != std::sregex_iterator(); ++it) {
    Array array;
    array.type = (*it)[1];
    array.name = (*it)[2];
    if ((*it)[3].matched) array.components = std::stoi((*it)[3]);
    array.offset = std::stoull((*it)[4]);
    if (array.offset + 8 <= parsed.appended.size()) {
      std::memcpy(&array.size_header, parsed.appended.data() + array.offset, 8);
      if (array.offset + 8 + array.size_header <= parsed.appended.size())
        array.bytes = parsed.appended.substr(array.offset + 8, array.size_header);
    }
    parsed.arrays.push_back(array);
  }
  return parsed;
}

template <class T>
std::vector<T> values(const Array& array) {
  std::vector<T> out(array.bytes.size() / sizeof(T));
  std::memcpy(out.data(), array.bytes.data(), out.size() * sizeof(T));
  return out;
}

const Array& find(const Parsed& parsed, const std::string& name) {
  for (const auto& array : parsed.arrays)
    if (array.name == name) return array;
  ADD_FAILURE() << "no array " << name;
  static const Array none;
  return none;
}

// Blocks follow each other without gaps, each offset = previous offset + 8 + previous size, and
// the last one ends where the appended data ends.
void expect_contiguous_blocks(const Parsed& parsed) {
  std::uint64_t expected_offset = 0;
  for (const auto& array : parsed.arrays) {
    EXPECT_EQ(array.offset, expected_offset) << array.name;
    expected_offset = array.offset + 8 + array.size_header;
  }
  EXPECT_EQ(expected_offset, parsed.appended.size());
}

TEST(VtkFiles, ParticleFileLayout) {
  const std::vector<std::uint64_t> ids = {7, 9};
  const std::vector<double> positions = {0.1, 0.2, 0.3, 0.4};
  const std::vector<double> velocities = {-1.0, 2.0, 3.0, -4.0};
  const std::vector<double> density = {1000.5, 999.25};
  const std::vector<double> pressure = {12.0, -3.5};
  ParticleFrame frame{2, 0.125, ids, positions, velocities, density, pressure};
  const std::string file = encode_particles(frame);

  ASSERT_TRUE(file.starts_with(
      "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" "
      "byte_order=\"LittleEndian\" header_type=\"UInt64\">\n  <UnstructuredGrid>\n"));
  const Parsed parsed = parse(file);
  EXPECT_NE(parsed.xml.find("<Piece NumberOfPoints=\"2\" NumberOfCells=\"2\">"), std::string::npos);

  const std::vector<std::string> order = {"TimeValue",    "id",       "velocity",
                                          "density",      "pressure", "Points",
                                          "connectivity", "offsets",  "types"};
  ASSERT_EQ(parsed.arrays.size(), order.size());
  for (std::size_t i = 0; i < order.size(); ++i)
    EXPECT_EQ(parsed.arrays[i].name, order[i]);
  EXPECT_EQ(parsed.arrays[0].offset, 0u);
  expect_contiguous_blocks(parsed);

  // Sizes in bytes of each block (2 particles).
  EXPECT_EQ(find(parsed, "TimeValue").size_header, 8u);
  EXPECT_EQ(find(parsed, "id").size_header, 16u);
  EXPECT_EQ(find(parsed, "velocity").size_header, 48u);
  EXPECT_EQ(find(parsed, "density").size_header, 16u);
  EXPECT_EQ(find(parsed, "Points").size_header, 48u);
  EXPECT_EQ(find(parsed, "types").size_header, 2u);
  // Total: 9 headers + 8 + 16 + 48 + 16 + 16 + 48 + 16 + 16 + 2 bytes.
  EXPECT_EQ(parsed.appended.size(), 9u * 8u + 186u);

  EXPECT_EQ(find(parsed, "id").type, "Int64");
  EXPECT_EQ(find(parsed, "types").type, "UInt8");
  EXPECT_EQ(find(parsed, "Points").components, 3);
  EXPECT_EQ(find(parsed, "velocity").components, 3);
  EXPECT_EQ(values<double>(find(parsed, "TimeValue")), std::vector<double>({0.125}));
  EXPECT_EQ(values<std::int64_t>(find(parsed, "id")), std::vector<std::int64_t>({7, 9}));
  EXPECT_EQ(values<double>(find(parsed, "Points")),
            std::vector<double>({0.1, 0.2, 0.0, 0.3, 0.4, 0.0}));
  EXPECT_EQ(values<double>(find(parsed, "velocity")),
            std::vector<double>({-1.0, 2.0, 0.0, 3.0, -4.0, 0.0}));
  EXPECT_EQ(values<double>(find(parsed, "density")), density);
  EXPECT_EQ(values<double>(find(parsed, "pressure")), pressure);
  EXPECT_EQ(values<std::int64_t>(find(parsed, "connectivity")), std::vector<std::int64_t>({0, 1}));
  EXPECT_EQ(values<std::int64_t>(find(parsed, "offsets")), std::vector<std::int64_t>({1, 2}));
  EXPECT_EQ(values<std::uint8_t>(find(parsed, "types")),
            std::vector<std::uint8_t>({kVtkVertex, kVtkVertex}));
}

TEST(VtkFiles, EmptyParticleFrameIsValid) {
  ParticleFrame frame;
  const Parsed parsed = parse(encode_particles(frame));
  EXPECT_NE(parsed.xml.find("NumberOfPoints=\"0\""), std::string::npos);
  expect_contiguous_blocks(parsed);
  EXPECT_EQ(find(parsed, "Points").size_header, 0u);
}

// A grid without cells still carries all three cell arrays, empty: the cell writer must not take
// an empty types array for a section that has none.
TEST(VtkFiles, EmptyParticleFrameKeepsEveryCellArray) {
  const Parsed parsed = parse(encode_particles(ParticleFrame{}));
  for (const char* name : {"connectivity", "offsets", "types"})
    EXPECT_EQ(find(parsed, name).size_header, 0u) << name;
}

TEST(VtkFiles, BoundaryMesh2DHasLinesAndDynamicFlags) {
  // Vertices 0 and 1 move with a body, vertex 2 is static; segments 0-1 and 1-2.
  const std::vector<double> positions = {0.0, 0.0, 1.0, 0.0, 1.0, 1.0};
  const std::vector<double> velocities = {0.5, 0.0, 0.5, 0.0, 0.0, 0.0};
  const std::vector<double> forces = {1.0, -2.0, 3.0, -4.0, 0.0, 0.0};
  const std::vector<std::uint32_t> segments = {0, 1, 1, 2};
  BoundaryFrame frame{2, 1.5, positions, velocities, forces, 2, segments};
  const Parsed parsed = parse(encode_boundary(frame));

  EXPECT_NE(parsed.xml.find("<Piece NumberOfPoints=\"3\" NumberOfCells=\"2\">"), std::string::npos);
  expect_contiguous_blocks(parsed);
  EXPECT_EQ(values<double>(find(parsed, "Points")),
            std::vector<double>({0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 1.0, 1.0, 0.0}));
  EXPECT_EQ(values<double>(find(parsed, "fluid_force")),
            std::vector<double>({1.0, -2.0, 0.0, 3.0, -4.0, 0.0, 0.0, 0.0, 0.0}));
  EXPECT_EQ(values<double>(find(parsed, "velocity")),
            std::vector<double>({0.5, 0.0, 0.0, 0.5, 0.0, 0.0, 0.0, 0.0, 0.0}));
  EXPECT_EQ(values<std::uint8_t>(find(parsed, "dynamic")), std::vector<std::uint8_t>({1, 1, 0}));
  EXPECT_EQ(values<std::int64_t>(find(parsed, "connectivity")),
            std::vector<std::int64_t>({0, 1, 1, 2}));
  EXPECT_EQ(values<std::int64_t>(find(parsed, "offsets")), std::vector<std::int64_t>({2, 4}));
  EXPECT_EQ(values<std::uint8_t>(find(parsed, "types")),
            std::vector<std::uint8_t>({kVtkLine, kVtkLine}));
  EXPECT_EQ(find(parsed, "connectivity").size_header, 32u);
}

TEST(VtkFiles, BoundaryMesh3DHasTriangles) {
  const std::vector<double> positions = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
  const std::vector<double> zeros(12, 0.0);
  const std::vector<std::uint32_t> triangles = {0, 1, 2, 0, 2, 3};
  BoundaryFrame frame{3, 0.0, positions, zeros, zeros, 4, triangles};
  const Parsed parsed = parse(encode_boundary(frame));
  expect_contiguous_blocks(parsed);
  EXPECT_EQ(values<double>(find(parsed, "Points")), positions);
  EXPECT_EQ(values<std::int64_t>(find(parsed, "offsets")), std::vector<std::int64_t>({3, 6}));
  EXPECT_EQ(values<std::uint8_t>(find(parsed, "types")),
            std::vector<std::uint8_t>({kVtkTriangle, kVtkTriangle}));
}

TEST(VtkFiles, BodyFramesArePolyDataWithNames) {
  const std::vector<double> positions = {0.025, 0.0, 0.025, 0.0725};
  const std::vector<double> velocities = {0.0, 0.0, 0.0, -0.05};
  const std::vector<double> angles = {0.0, 0.25};
  BodyFrame frame{2, 0.5, {"ab", "c"}, positions, velocities, angles};
  const std::string file = encode_bodies(frame);
  ASSERT_TRUE(file.starts_with("<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\""));
  const Parsed parsed = parse(file);
  // "ab" and "c" as ASCII codes, each ended by 0 (VTK's String array form).
  EXPECT_NE(parsed.xml.find("<Array type=\"String\" Name=\"body_name\" NumberOfTuples=\"2\" "
                            "format=\"ascii\">\n      97 98 0 99 0 \n"),
            std::string::npos)
      << parsed.xml;
  EXPECT_NE(parsed.xml.find("NumberOfPoints=\"2\" NumberOfVerts=\"2\""), std::string::npos);
  expect_contiguous_blocks(parsed);
  EXPECT_EQ(values<std::int64_t>(find(parsed, "body_index")), std::vector<std::int64_t>({0, 1}));
  EXPECT_EQ(values<double>(find(parsed, "angle")), angles);
  EXPECT_EQ(values<double>(find(parsed, "Points")),
            std::vector<double>({0.025, 0.0, 0.0, 0.025, 0.0725, 0.0}));
  EXPECT_EQ(values<std::int64_t>(find(parsed, "offsets")), std::vector<std::int64_t>({1, 2}));
  // The frames' axes: body 0 unrotated, body 1 turned by 0.25 rad.
  const std::vector<double> axis_x = values<double>(find(parsed, "axis_x"));
  const std::vector<double> axis_y = values<double>(find(parsed, "axis_y"));
  ASSERT_EQ(axis_x.size(), 6u);
  ASSERT_EQ(axis_y.size(), 6u);
  EXPECT_EQ(std::vector<double>(axis_x.begin(), axis_x.begin() + 3),
            std::vector<double>({1, 0, 0}));
  EXPECT_EQ(std::vector<double>(axis_y.begin(), axis_y.begin() + 3),
            std::vector<double>({0, 1, 0}));
  EXPECT_DOUBLE_EQ(axis_x[3], std::cos(0.25));
  EXPECT_DOUBLE_EQ(axis_x[4], std::sin(0.25));
  EXPECT_DOUBLE_EQ(axis_y[3], -std::sin(0.25));
  EXPECT_DOUBLE_EQ(axis_y[4], std::cos(0.25));
  EXPECT_EQ(values<double>(find(parsed, "axis_z")), std::vector<double>({0, 0, 1, 0, 0, 1}));
}

TEST(VtkFiles, CentreLinesArePolyDataLines) {
  const std::vector<std::size_t> counts = {3, 2};
  const std::vector<double> positions = {0, 0, 0.5, 0.1, 1, 0, 2, 2, 3, 2};
  const std::vector<double> velocities(10, 0.5);
  CentreLineFrame frame{2, 0.25, {"beam", "rod"}, counts, positions, velocities};
  const Parsed parsed = parse(encode_centre_lines(frame));
  EXPECT_NE(parsed.xml.find("NumberOfPoints=\"5\" NumberOfVerts=\"0\" NumberOfLines=\"2\""),
            std::string::npos)
      << parsed.xml;
  expect_contiguous_blocks(parsed);
  EXPECT_EQ(values<std::int64_t>(find(parsed, "connectivity")),
            std::vector<std::int64_t>({0, 1, 2, 3, 4}));
  EXPECT_EQ(values<std::int64_t>(find(parsed, "offsets")), std::vector<std::int64_t>({3, 5}));
  EXPECT_EQ(values<std::int64_t>(find(parsed, "line_index")),
            std::vector<std::int64_t>({0, 0, 0, 1, 1}));
  EXPECT_EQ(values<double>(find(parsed, "Points")),
            std::vector<double>({0, 0, 0, 0.5, 0.1, 0, 1, 0, 0, 2, 2, 0, 3, 2, 0}));
}

TEST(VtkFilesDeathTest, MismatchedSizesAreProgrammerErrors) {
  const std::vector<std::uint64_t> ids = {1, 2};
  const std::vector<double> positions = {0.0, 0.0, 1.0, 1.0};
  const std::vector<double> one = {1.0};
  ParticleFrame frame{2, 0.0, ids, positions, positions, one, one};
  EXPECT_DEATH(encode_particles(frame), "one density and one pressure per particle");

  const std::vector<std::uint32_t> bad_segment = {0, 5};
  BoundaryFrame boundary{2, 0.0, positions, positions, positions, 2, bad_segment};
  EXPECT_DEATH(encode_boundary(boundary), "element vertex index 5 out of range");
}

}  // namespace
}  // namespace fsi::output
