#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <string>

#include "fsi/common/error.hpp"
#include "fsi/output/run_folder.hpp"
#include "fsi/test_support/folder_per_test.hpp"

namespace fsi::output {
namespace {

namespace fs = std::filesystem;

// Every file under the folder with its content: "nothing changed" compares two of these.
std::map<std::string, std::string> contents(const fs::path& folder) {
  std::map<std::string, std::string> files;
  for (const auto& entry : fs::recursive_directory_iterator(folder)) {
    files[fs::relative(entry.path(), folder).string()] =
        entry.is_regular_file() ? test_support::file_text(entry.path()) : "";
  }
  return files;
}

const char* kCompleted = R"({"format": "fsi-run-manifest", "format_version": 5,
  "scene": {"file": "/examples/static_tank/static_tank_coarse.scene"},
  "started_utc": "2026-12-02T11:40:12Z", "status": "completed", "steps": 400})";

class RunFolderTest : public test_support::FolderPerTest {
 protected:
  // What a coupled run leaves, and a file of the user's own.
  void write_run(const std::string& manifest) {
    write("run.json", manifest);
    write("sensors.csv", "# sensors\n# units: time [s]\ntime,F\n0,1\n1e-05,2\n");
    write("energy.csv", "# energy\ntime,coupling_energy\n0,0\n");
    write("fsi-server.log", "log\n");
    write("fsi-client.log", "log\n");
    write("snapshots/particles_000000000.csv", "id,x,y\n");
    write("vtk/fluid.pvd", "<VTKFile/>\n");
    write("vtk/fluid_000000000.vtu", "vtu");
    write("plots/sensors.png", "png");
    write("notes.txt", "my own notes");
  }
};

TEST_F(RunFolderTest, NothingOfOursIsNoEarlierRun) {
  EXPECT_FALSE(inspect_run_folder(folder_ / "absent"));
  EXPECT_FALSE(inspect_run_folder(folder_));
  write("notes.txt", "mine");
  write("server.port", "5000");  // fsi-run's, written before the server starts
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
  write("vtk/my_view.pvsm", "paraview state");
  remove_earlier_run(folder_);
  EXPECT_TRUE(fs::exists(folder_ / "vtk" / "my_view.pvsm"));
  EXPECT_FALSE(fs::exists(folder_ / "vtk" / "fluid.pvd"));
}

TEST_F(RunFolderTest, ARunThatFailedBeforeItsFirstStepHasNoResults) {
  write("run.json", R"({"status": "failed", "steps": 0, "scene": {"file": "s"}})");
  write("fsi-server.log", "error: the client never came\n");
  const auto earlier = claim_run_folder(folder_, false);
  ASSERT_TRUE(earlier);
  EXPECT_FALSE(earlier->has_results());
}

TEST_F(RunFolderTest, AFailedRunWithStepsIsKept) {
  write("run.json", R"({"status": "failed", "steps": 12})");
  EXPECT_THROW(claim_run_folder(folder_, false), fsi::Error);
}

TEST_F(RunFolderTest, ARunWithoutEndIsStillRunningOrKilled) {
  write("run.json", R"({"status": "started", "steps": 0, "started_utc": "x"})");
  try {
    claim_run_folder(folder_, false);
    FAIL() << "a run without a recorded end was replaced";
  } catch (const fsi::Error& error) {
    EXPECT_NE(std::string(error.what()).find("still running, or killed"), std::string::npos)
        << error.what();
  }
}

TEST_F(RunFolderTest, WithoutRunJsonTheSensorRowsDecide) {
  write("sensors.csv", "# sensors\ntime,F\n");
  ASSERT_TRUE(inspect_run_folder(folder_));
  EXPECT_FALSE(inspect_run_folder(folder_)->has_results());
  write("sensors.csv", "# sensors\ntime,F\n0,1\n");
  const auto earlier = inspect_run_folder(folder_);
  ASSERT_TRUE(earlier);
  EXPECT_TRUE(earlier->has_results());
  EXPECT_NE(earlier->summary().find("no run.json"), std::string::npos) << earlier->summary();
}

TEST_F(RunFolderTest, AnUnreadableRunJsonIsKeptAndNamed) {
  write("run.json", "{\"status\": \"comp");
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
