#pragma once
// Files of a run that are never seen half-written (docs/user-guide.md, "Files after a crash or a
// full disk"): a whole file is written under a temporary name and renamed over the old one, so
// a reader, a crash or a full disk at any moment leaves the old file or the new one, never a
// part. One helper for every whole-file write (run.json, snapshots, VTK files, .pvd indices;
// checkpoint files).

#include <filesystem>
#include <string>
#include <string_view>

#include "fsi/common/error.hpp"

namespace fsi::output {

enum class Durability {
  // Survives a crash of the program (the rename is atomic); the default.
  ProcessCrash,
  // Also survives a crash of the machine: the file's data and the folder's entry are synced to
  // the disk before and after the rename (slower: for checkpoints, not for every snapshot).
  MachineCrash,
};

// Writes `bytes` to `path` via `path.tmp` and a rename. On any failure the temporary file is
// removed, `path` keeps its previous content (or stays absent), and an fsi::Error names the file,
// the system's reason (e.g. "No space left on device") and the fix.
void write_file_atomically(const std::filesystem::path& path, std::string_view bytes,
                           Durability durability = Durability::ProcessCrash);

// Syncs a folder's entries (created, renamed, removed files) to the disk; best effort.
void sync_folder(const std::filesystem::path& folder) noexcept;

// The error every output file reports when the system refuses a write: what (the action, the
// file, strerror of `error_number`), where (`what_file`, e.g. "sensor output") and how to fix it
// (free space for ENOSPC/EDQUOT, a writable folder for EACCES/EROFS/EPERM, ...).
Error file_error(const std::string& action, const std::filesystem::path& path, int error_number,
                 const std::string& what_file);

// Opens `path` for writing (created, kept if it exists) and closes it again: an unwritable folder
// is reported before a run starts. Throws file_error(..., what_file).
void check_writable(const std::filesystem::path& path, const std::string& what_file);

}  // namespace fsi::output
