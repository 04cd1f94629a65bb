#include "fsi/output/checkpoint_store.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "fsi/common/error.hpp"
#include "fsi/test_support/folder_per_test.hpp"

namespace fsi::output {
namespace {

namespace fs = std::filesystem;

using test_support::file_text;

using CheckpointStoreTest = test_support::FolderPerTest;

bool mentions(const std::vector<std::string>& lines, const std::string& text) {
  for (const std::string& line : lines)
    if (line.find(text) != std::string::npos) return true;
  return false;
}

void store_checkpoint(CheckpointStore& store, std::uint64_t step, const std::string& state) {
  store.begin(step);
  store.add("server.state", state);
  store.add("fluid.state", "particles of step " + std::to_string(step));
  store.commit(1e-5 * static_cast<double>(step));
}

TEST_F(CheckpointStoreTest, Sha256OfTheStandardTestVectors) {
  EXPECT_EQ(sha256_hex("abc"), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  EXPECT_EQ(sha256_hex(""), "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
}

TEST_F(CheckpointStoreTest, ACommittedCheckpointIsReadBackWithItsManifest) {
  CheckpointStore store(folder_ / "checkpoints");
  store_checkpoint(store, 100, std::string("state\0with a zero", 17));
  const auto newest = store.newest_valid();
  ASSERT_TRUE(newest.has_value());
  EXPECT_EQ(newest->step, 100u);
  EXPECT_DOUBLE_EQ(newest->time, 1e-3);
  EXPECT_EQ(newest->folder, folder_ / "checkpoints" / "step-000000100");
  ASSERT_EQ(newest->files.size(), 2u);
  EXPECT_EQ(read_checkpoint_file(*newest, "server.state"), std::string("state\0with a zero", 17));
  EXPECT_EQ(newest->files[0].bytes, 17u);
  const std::string manifest = file_text(newest->folder / "checkpoint.json");
  EXPECT_NE(manifest.find("\"format_version\": 4"), std::string::npos) << manifest;
  EXPECT_NE(manifest.find(newest->files[1].sha256), std::string::npos) << manifest;
  EXPECT_FALSE(fs::exists(folder_ / "checkpoints" / "step-000000100.partial"));
}

TEST_F(CheckpointStoreTest, KeepsTheNewestTwo) {
  CheckpointStore store(folder_ / "checkpoints");
  for (std::uint64_t step : {10, 20, 30})
    store_checkpoint(store, step, "s");
  const auto kept = store.list();
  ASSERT_EQ(kept.size(), 2u);
  EXPECT_EQ(kept[0].step, 20u);
  EXPECT_EQ(kept[1].step, 30u);
  EXPECT_FALSE(fs::exists(folder_ / "checkpoints" / "step-000000010"));
}

// A kill while a checkpoint is written leaves its .partial folder: never used, and the next
// commit clears it.
TEST_F(CheckpointStoreTest, AnUnfinishedCheckpointIsNeverUsed) {
  CheckpointStore store(folder_ / "checkpoints");
  store_checkpoint(store, 20, "good");
  {
    CheckpointStore killed(folder_ / "checkpoints");
    killed.begin(30);
    killed.add("server.state", "half");
    // no commit: the process "died" here
  }
  std::vector<std::string> skipped;
  const auto newest = store.newest_valid(&skipped);
  ASSERT_TRUE(newest.has_value());
  EXPECT_EQ(newest->step, 20u);
  EXPECT_TRUE(mentions(skipped, "step-000000030.partial: unfinished")) << skipped.size();
  store_checkpoint(store, 40, "next");
  EXPECT_FALSE(fs::exists(folder_ / "checkpoints" / "step-000000030.partial"));
}

// A folder renamed complete but without its manifest (a hand-made copy, a damaged disk) and a
// damaged file: both passed over for the older good checkpoint, each with its reason.
TEST_F(CheckpointStoreTest, ADamagedCheckpointIsPassedOverWithItsReason) {
  CheckpointStore store(folder_ / "checkpoints", 3);
  store_checkpoint(store, 10, "good");
  store_checkpoint(store, 20, "to be damaged");
  store_checkpoint(store, 30, "to be cut");
  std::ofstream(folder_ / "checkpoints" / "step-000000020" / "server.state") << "to be DAMAGED";
  fs::resize_file(folder_ / "checkpoints" / "step-000000030" / "fluid.state", 3);
  std::vector<std::string> skipped;
  const auto newest = store.newest_valid(&skipped);
  ASSERT_TRUE(newest.has_value());
  EXPECT_EQ(newest->step, 10u);
  EXPECT_TRUE(mentions(skipped, "step-000000030: fluid.state holds 3 bytes"));
  EXPECT_TRUE(mentions(skipped, "step-000000020: server.state does not match its SHA-256"));

  const auto all = store.list();
  ASSERT_EQ(all.size(), 3u);
  try {
    read_checkpoint_file(all[1], "server.state");
    FAIL() << "a changed file was read";
  } catch (const fsi::Error& error) {
    EXPECT_NE(error.fault().find("server.state does not match"), std::string::npos) << error.what();
  }
  fs::remove(folder_ / "checkpoints" / "step-000000010" / "checkpoint.json");
  skipped.clear();
  EXPECT_FALSE(store.newest_valid(&skipped).has_value());
  EXPECT_TRUE(mentions(skipped, "step-000000010: no checkpoint.json"));
}

TEST_F(CheckpointStoreTest, AnotherFormatVersionIsRefusedByName) {
  CheckpointStore store(folder_ / "checkpoints");
  store_checkpoint(store, 10, "good");
  const fs::path manifest = folder_ / "checkpoints" / "step-000000010" / "checkpoint.json";
  std::string text = file_text(manifest);
  // Version 2: a checkpoint of the releases before 2026-12-07 (no particle pairs in the
  // session's state).
  text.replace(text.find("\"format_version\": 4"), 19, "\"format_version\": 2");
  std::ofstream(manifest) << text;
  std::vector<std::string> skipped;
  EXPECT_FALSE(store.newest_valid(&skipped).has_value());
  EXPECT_TRUE(mentions(skipped,
                       "checkpoint format version 2, this program reads 4 (resume it with "
                       "the release that wrote it)"));
}

// A full disk while writing a checkpoint (/dev/full stands in for it): the write fails with the
// system's reason, abandon() removes the partial folder, the previous checkpoint is intact.
TEST_F(CheckpointStoreTest, AFullDiskKeepsThePreviousCheckpoint) {
  CheckpointStore store(folder_ / "checkpoints");
  store_checkpoint(store, 10, "good");
  store.begin(20);
  fs::create_symlink("/dev/full",
                     folder_ / "checkpoints" / "step-000000020.partial" / "server.state.tmp");
  try {
    store.add("server.state", "does not fit");
    FAIL() << "a write to a full disk did not throw";
  } catch (const fsi::Error& error) {
    EXPECT_NE(error.fault().find("No space left on device"), std::string::npos) << error.what();
  }
  store.abandon();
  EXPECT_FALSE(fs::exists(folder_ / "checkpoints" / "step-000000020.partial"));
  const auto newest = store.newest_valid();
  ASSERT_TRUE(newest.has_value());
  EXPECT_EQ(newest->step, 10u);
  EXPECT_EQ(read_checkpoint_file(*newest, "server.state"), "good");
}

TEST_F(CheckpointStoreTest, BadFileNamesAndKeepAreRefused) {
  EXPECT_THROW(CheckpointStore(folder_, 0), fsi::Error);
  CheckpointStore store(folder_ / "checkpoints");
  EXPECT_THROW(store.add("early", "x"), fsi::Error);
  store.begin(1);
  EXPECT_THROW(store.add("sub/file", "x"), fsi::Error);
  EXPECT_THROW(store.add("checkpoint.json", "x"), fsi::Error);
}

}  // namespace
}  // namespace fsi::output
