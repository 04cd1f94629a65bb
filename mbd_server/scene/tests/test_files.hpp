#pragma once
// Files the scene tests write: a closed unit-cube STL surface, and a scene's problems as text.

#include <array>
#include <filesystem>
#include <string>

#include "fsi/common/error.hpp"
#include "fsi/scene/scene.hpp"

namespace fsi::scene::testing {

// The unit cube [0, 1]^3 as ASCII STL, 12 triangles (11 with drop_last_triangle: a hole).
inline std::string unit_box_stl(bool drop_last_triangle = false) {
  const double c[8][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0},
                          {0, 0, 1}, {1, 0, 1}, {0, 1, 1}, {1, 1, 1}};
  const int faces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                           {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  std::string text = "solid box\n";
  int written = 0;
  for (const auto& f : faces) {
    for (const auto& t :
         {std::array<int, 3>{f[0], f[1], f[2]}, std::array<int, 3>{f[0], f[2], f[3]}}) {
      if (drop_last_triangle && ++written == 12) break;
      text += " facet normal 0 0 0\n  outer loop\n";
      for (int v : t) {
        text += "   vertex " + std::to_string(c[v][0]) + " " + std::to_string(c[v][1]) + " " +
                std::to_string(c[v][2]) + "\n";
      }
      text += "  endloop\n endfacet\n";
    }
  }
  return text + "endsolid box\n";
}

// The problems build_scene reports for a file, "(accepted)" if it builds.
inline std::string build_error(const std::filesystem::path& file) {
  try {
    build_scene(file.string());
  } catch (const fsi::Error& error) {
    return error.what();
  }
  return "(accepted)";
}

}  // namespace fsi::scene::testing
