#pragma once
// Files the scene tests write: a folder of their own with coupled scenes in it, a closed
// unit-cube STL surface, and a scene's problems as text.

#include <gtest/gtest.h>

#include <array>
#include <filesystem>
#include <string>

#include "fsi/common/error.hpp"
#include "fsi/scene/scene.hpp"
#include "fsi/test_support/folder_per_test.hpp"
#include "fsi/test_support/thrown.hpp"

namespace fsi::scene::testing {

using test_support::message_thrown;

// Problems or diagnostics one to a line, for a failing expectation to show.
std::string listing(const auto& reports) {
  std::string text;
  for (const auto& report : reports)
    text += report.text() + "\n";
  return text;
}

// The shared folder per test (fsi/test_support/folder_per_test.hpp) with the scene tests' own
// writers. Base: ::testing::Test, or ::testing::TestWithParam<T> for parameterised suites.
template <class Base = ::testing::Test>
class FolderPerTestOf : public test_support::FolderPerTestOf<Base> {
 protected:
  using test_support::FolderPerTestOf<Base>::write;

  // Writes the scene `text` to `name` and builds it for --mbd-only: "(accepted)", or the problems
  // it was refused with; the scene in `built` when given and accepted.
  std::string mbd_only_outcome(const std::string& name, const std::string& text,
                               Scene* built = nullptr) const {
    try {
      Scene scene = build_scene(write(name, text), {}, SceneMode::MbdOnly);
      if (built != nullptr) *built = std::move(scene);
    } catch (const Error& error) {
      return error.what();
    }
    return "(accepted)";
  }

  // A coupled scene `name`: the language line, `blocks`, then LIGGGHTS running the folder's
  // "s.in" (written here) and Coupling { `coupling` }; the file's path.
  std::filesystem::path write_coupled_scene(
      const std::string& name, const std::string& blocks,
      const std::string& coupling = "refinement_resolution = 0.002") const {
    write("s.in", "# script\n");
    return write(name, "scene_language = 1\n" + blocks +
                           "LIGGGHTS { script1 = \"s.in\"; script2 = \"s.in\" }\n"
                           "Coupling { " +
                           coupling + " }\n");
  }
};
using FolderPerTest = FolderPerTestOf<>;

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
