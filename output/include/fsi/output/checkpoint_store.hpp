#pragma once
// The checkpoints of a run (issue 16; docs/user-guide.md, "Checkpoints"): folders under
// OUTPUT/checkpoints, one per coupled step, each holding the files of both sides at that step
// and a manifest (checkpoint.json: format version, step, time, every file's size and SHA-256).
// A checkpoint counts only when it is complete: its files are written into
// "step-NNNNNNNNN.partial", synced, hashed into the manifest, and the folder is renamed to
// "step-NNNNNNNNN" only then. A crash, a kill or a full disk at any moment leaves the previous
// checkpoints as they were and at most a ".partial" folder that nothing trusts. The newest
// `keep` complete checkpoints are kept; older ones and stale partial folders are removed after a
// commit. A checkpoint is read back only after its files match the manifest.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace fsi::output {

// Version of checkpoint.json, of the folder layout and of the parts' states; a reader refuses
// another one by name. 2 (2026-12-06): the fluid health keeps an unsettled release; 3
// (2026-12-07): the particle pairs of the snapshots; 4 (2026-12-07): the structure's work sensors.
inline constexpr int kCheckpointFormatVersion = 4;

struct CheckpointFile {
  std::string name;  // relative to the checkpoint folder, no subfolders
  std::uint64_t bytes = 0;
  std::string sha256;  // lower-case hex
};

struct Checkpoint {
  std::filesystem::path folder;
  std::uint64_t step = 0;
  double time = 0.0;
  std::string written_utc;
  std::vector<CheckpointFile> files;
};

class CheckpointStore {
 public:
  // `root` is OUTPUT/checkpoints (created on the first checkpoint); keep >= 1.
  explicit CheckpointStore(std::filesystem::path root, int keep = 2);

  const std::filesystem::path& root() const { return root_; }

  // Starts the checkpoint of `step`: an empty folder step-N.partial (a leftover of that name is
  // removed). Throws fsi::Error (what, where, fix) when the folder cannot be made.
  void begin(std::uint64_t step);
  // Writes one file of the pending checkpoint, durably. Throws fsi::Error on a write failure
  // (full disk, ...); the partial folder is then abandoned by the caller (abandon()).
  void add(const std::string& name, std::string_view bytes);
  // Hashes the pending checkpoint's files, writes its manifest, syncs and renames it complete,
  // then removes older checkpoints beyond `keep` and stale partial folders. Returns it.
  Checkpoint commit(double time);
  // Removes the pending partial folder (after a failure); never throws.
  void abandon() noexcept;

  // The complete checkpoints, oldest first, read from their manifests without hashing the files
  // (fast); folders without a readable manifest are skipped and named in `skipped`.
  std::vector<Checkpoint> list(std::vector<std::string>* skipped = nullptr) const;
  // The newest checkpoint whose files all match its manifest; the ones passed over (a partial
  // folder, a bad manifest, a file missing, cut short or changed) are named with the reason in
  // `skipped`. nullopt: none.
  std::optional<Checkpoint> newest_valid(std::vector<std::string>* skipped = nullptr) const;

 private:
  std::filesystem::path root_;
  int keep_;
  std::optional<std::uint64_t> pending_;
  std::vector<std::string> pending_files_;
};

// Reads one file of a checkpoint and checks it against the manifest; throws fsi::Error naming
// the checkpoint and the file when it is missing or does not match.
std::string read_checkpoint_file(const Checkpoint& checkpoint, const std::string& name);

// "step-000001200" for step 1200.
std::string checkpoint_folder_name(std::uint64_t step);

// SHA-256 of `bytes`, lower-case hex.
std::string sha256_hex(std::string_view bytes);

}  // namespace fsi::output
