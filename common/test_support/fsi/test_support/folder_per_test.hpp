#pragma once
// A folder of its own for each unit test, and the text of a file: one place for every module's
// tests.

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace fsi::test_support {

// The whole content of the file at `path` ("" when it cannot be read).
inline std::string file_text(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// A fresh folder for each test, named after the test and this process, removed afterwards. ctest
// runs every test case (and every parameter) as a process of its own, in parallel, and two build
// trees on one machine may run the same test at once: the process id keeps their folders apart.
// Base: ::testing::Test, or ::testing::TestWithParam<T> for parameterised suites.
template <class Base = ::testing::Test>
class FolderPerTestOf : public Base {
 protected:
  void SetUp() override {
    const auto* test = ::testing::UnitTest::GetInstance()->current_test_info();
    std::string name = "fsi_" + std::string(test->test_suite_name()) + "_" + test->name() + "_" +
                       std::to_string(::getpid());
    for (char& c : name) {
      if (c == '/') c = '_';  // "Dimensions/Suite" and "Test/0" of parameterised suites
    }
    folder_ = std::filesystem::temp_directory_path() / name;
    std::filesystem::remove_all(folder_);
    std::filesystem::create_directories(folder_);
  }
  void TearDown() override { std::filesystem::remove_all(folder_); }

  // Writes `text` to `name` in the folder (making sub-folders); the file's path.
  std::string write(const std::filesystem::path& name, const std::string& text) const {
    const std::filesystem::path file = folder_ / name;
    std::filesystem::create_directories(file.parent_path());
    std::ofstream(file) << text;
    return file.string();
  }

  std::filesystem::path folder_;
};
using FolderPerTest = FolderPerTestOf<>;

}  // namespace fsi::test_support
