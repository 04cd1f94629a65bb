#include <gtest/gtest.h>

#include <unistd.h>

#include <cerrno>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "fsi/common/error.hpp"
#include "fsi/output/atomic_file.hpp"

namespace fsi::output {
namespace {

namespace fs = std::filesystem;

std::string read(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

class AtomicFileTest : public ::testing::Test {
 protected:
  void SetUp() override {
    directory_ = fs::temp_directory_path() /
                 ("fsi_atomic_file_test_" + std::to_string(::getpid()) + "_" +
                  ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(directory_);
    fs::create_directories(directory_);
  }
  void TearDown() override { fs::remove_all(directory_); }
  fs::path directory_;
};

TEST_F(AtomicFileTest, ReplacesTheFileAndLeavesNoTemporary) {
  const fs::path path = directory_ / "run.json";
  write_file_atomically(path, "first");
  write_file_atomically(path, "second, longer", Durability::MachineCrash);
  EXPECT_EQ(read(path), "second, longer");
  EXPECT_FALSE(fs::exists(directory_ / "run.json.tmp"));
}

// A full disk while writing: the old file stays whole, the temporary goes, the message names the
// file, the system's reason and the fix. /dev/full fails every write with ENOSPC; the temporary
// name pointing there stands in for a disk that fills up during the write.
TEST_F(AtomicFileTest, FullDiskKeepsTheOldFileAndSaysSo) {
  const fs::path path = directory_ / "run.json";
  write_file_atomically(path, "the old manifest");
  fs::create_symlink("/dev/full", directory_ / "run.json.tmp");
  try {
    write_file_atomically(path, "the new manifest");
    FAIL() << "a write to a full disk did not throw";
  } catch (const fsi::Error& error) {
    EXPECT_NE(error.fault().find(path.string()), std::string::npos) << error.what();
    EXPECT_NE(error.fault().find("No space left on device"), std::string::npos) << error.what();
    EXPECT_NE(error.remedy().find("free space"), std::string::npos) << error.what();
  }
  EXPECT_EQ(read(path), "the old manifest");
  EXPECT_FALSE(fs::exists(fs::symlink_status(directory_ / "run.json.tmp")));
}

TEST_F(AtomicFileTest, MissingFolderNamesTheFile) {
  try {
    write_file_atomically(directory_ / "gone" / "sensors.csv", "x");
    FAIL() << "writing into a missing folder did not throw";
  } catch (const fsi::Error& error) {
    EXPECT_NE(error.fault().find("gone/sensors.csv.tmp"), std::string::npos) << error.what();
    EXPECT_NE(error.remedy().find("missing"), std::string::npos) << error.what();
  }
}

TEST(FileError, TheFixFollowsTheReason) {
  EXPECT_NE(file_error("cannot write", "/d/f", ENOSPC, "x").remedy().find("df -h /d"),
            std::string::npos);
  EXPECT_NE(file_error("cannot write", "/d/f", EROFS, "x").remedy().find("writable"),
            std::string::npos);
  EXPECT_NE(file_error("cannot write", "/d/f", EACCES, "x").remedy().find("writable"),
            std::string::npos);
}

}  // namespace
}  // namespace fsi::output
