#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>

#include "fsi/common/error.hpp"
#include "fsi/output/run_folder.hpp"

namespace fsi::output {
namespace {

namespace fs = std::filesystem;

void write(const fs::path& path, const std::string& text) {
  fs::create_directories(path.parent_path());
  std::ofstream(path) << text;
}

// Every file under the folder with its content: "nothing changed" compares two of these.
std::map<std::string, std::string> contents(const fs::path& folder) {
  std::map<std::string, std::string> files;
  for (const auto& entry : fs::recursive_directory_iterator(folder)) {
    std::ifstream in(entry.path(), std::ios::binary);
    std::stringstream text;
    if (entry.is_regular_file()) text << in.rdbuf();
    files[fs::relative(entry.path(), folder).string()] = text.str();
  }
  return files;
}

const char* kCompleted = R"({"format": "fsi-run-manifest", "format_version": 5,
  "scene": {"file": "/examples/static_tank/static_tank_coarse.scene"},
  "started_utc": "2026-12-02T11:40:12Z", "status": "completed", "steps": 400})";

class RunFolderTest : public ::testing::Test {
 protected:
  void SetUp() override {
    folder_ = fs::temp_directory_path() /
              ("fsi_run_folder_test_" + std::to_string(::getpid()) + "_" +
               ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(folder_);
    fs::create_directories(folder_);
  }
  void TearDown() override { fs::remove_all(folder_); }
  // What a coupled run leaves, and a file of the user's own.
  void write_run(const std::string& manifest) {
    write(folder_ / "run.json", manifest);
    write(folder_ / "sensors.csv", "# sensors\n# units: time [s]\ntime,F\n0,1\n1e-05,2\n");
    write(folder_ / "energy.csv", "# energy\ntime,coupling_energy\n0,0\n");
    write(folder_ / "fsi-server.log", "log\n");
    write(folder_ / "fsi-client.log", "log\n");
    write(folder_ / "snapshots" / "particles_000000000.csv", "id,x,y\n");
    write(folder_ / "vtk" / "fluid.pvd", "<VTKFile/>\n");
    write(folder_ / "vtk" / "fluid_000000000.vtu", "vtu");
    write(folder_ / "plots" / "sensors.png", "png");
    write(folder_ / "notes.txt", "my own notes");
  }
  fs::path folder_;
};

TEST_F(RunFolderTest, NothingOfOursIsNoEarlierRun) {
  EXPECT_FALSE(inspect_run_folder(folder_ / "absent"));
  EXPECT_FALSE(inspect_run_folder(folder_));
  write(folder_ / "notes.txt", "mine");
  write(folder_ / "server.port", "5000");  // fsi-run's, written before the server starts
  EXPECT_FALSE(inspect_run_folder(folder_));
  EXPECT_FALSE(claim_run_folder(folder_, false));
}

TEST_F(RunFolderTest, ACompletedRunIsRefusedByNameAndNothingChanges) {
  write_run(kCompleted);
  const auto before = contents(folder_);
  try {
    claim_run_folder(folder_, false);
    FAIL() << "a folder with a completed run was claimed";
  } catch (const fsi::Error& error) {
    const std::string text = error.what();
    for (const char* expected :
         {"static_tank_coarse.scene", "started 2026-12-02 11:40:12 UTC", "status completed",
          "400 steps", "run.json", "sensors.csv", "snapshots/", "vtk/", "--overwrite"}) {
      EXPECT_NE(text.find(expected), std::string::npos) << expected << " not in: " << text;
    }
  }
  EXPECT_EQ(contents(folder_), before);
}

TEST_F(RunFolderTest, OverwriteRemovesOurFilesAndKeepsTheUsers) {
  write_run(kCompleted);
  const auto earlier = claim_run_folder(folder_, true);
  ASSERT_TRUE(earlier);
  EXPECT_TRUE(earlier->has_results());
  const auto removed = remove_earlier_run(folder_);
  EXPECT_EQ(removed.size(), 12u);  // 9 files, 3 emptied folders
  const auto left = contents(folder_);
  EXPECT_EQ(left.size(), 1u);
  EXPECT_EQ(left.count("notes.txt"), 1u);
  EXPECT_FALSE(inspect_run_folder(folder_));
}

TEST_F(RunFolderTest, OtherFilesInOurFoldersStay) {
  write_run(kCompleted);
  write(folder_ / "vtk" / "my_view.pvsm", "paraview state");
  remove_earlier_run(folder_);
  EXPECT_TRUE(fs::exists(folder_ / "vtk" / "my_view.pvsm"));
  EXPECT_FALSE(fs::exists(folder_ / "vtk" / "fluid.pvd"));
}

TEST_F(RunFolderTest, ARunThatFailedBeforeItsFirstStepHasNoResults) {
  write(folder_ / "run.json", R"({"status": "failed", "steps": 0, "scene": {"file": "s"}})");
  write(folder_ / "fsi-server.log", "error: the client never came\n");
  const auto earlier = claim_run_folder(folder_, false);
  ASSERT_TRUE(earlier);
  EXPECT_FALSE(earlier->has_results());
}

TEST_F(RunFolderTest, AFailedRunWithStepsIsKept) {
  write(folder_ / "run.json", R"({"status": "failed", "steps": 12})");
  EXPECT_THROW(claim_run_folder(folder_, false), fsi::Error);
}

TEST_F(RunFolderTest, ARunWithoutEndIsStillRunningOrKilled) {
  write(folder_ / "run.json", R"({"status": "started", "steps": 0, "started_utc": "x"})");
  try {
    claim_run_folder(folder_, false);
    FAIL() << "a run without a recorded end was replaced";
  } catch (const fsi::Error& error) {
    EXPECT_NE(std::string(error.what()).find("still running, or killed"), std::string::npos)
        << error.what();
  }
}

TEST_F(RunFolderTest, WithoutRunJsonTheSensorRowsDecide) {
  write(folder_ / "sensors.csv", "# sensors\ntime,F\n");
  ASSERT_TRUE(inspect_run_folder(folder_));
  EXPECT_FALSE(inspect_run_folder(folder_)->has_results());
  write(folder_ / "sensors.csv", "# sensors\ntime,F\n0,1\n");
  const auto earlier = inspect_run_folder(folder_);
  ASSERT_TRUE(earlier);
  EXPECT_TRUE(earlier->has_results());
  EXPECT_NE(earlier->summary().find("no run.json"), std::string::npos) << earlier->summary();
}

TEST_F(RunFolderTest, AnUnreadableRunJsonIsKeptAndNamed) {
  write(folder_ / "run.json", "{\"status\": \"comp");
  try {
    claim_run_folder(folder_, false);
    FAIL() << "a folder with a broken run.json was claimed";
  } catch (const fsi::Error& error) {
    EXPECT_NE(std::string(error.what()).find("run.json cannot be read"), std::string::npos)
        << error.what();
  }
}

}  // namespace
}  // namespace fsi::output
