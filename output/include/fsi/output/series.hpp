#pragma once
// A time series of VTK files with its ParaView collection index (.pvd). Each new file is written
// under a temporary name and renamed, then the index is rewritten the same way, so a run that
// crashes leaves a valid index of every complete file.

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "fsi/output/state_archive.hpp"

namespace fsi::output {

// The text of a .pvd collection: one DataSet per (time, file) with a timestep attribute.
struct CollectionEntry {
  double time = 0.0;
  std::string file;  // relative to the .pvd
};
std::string encode_collection(const std::vector<CollectionEntry>& entries);

class Series {
 public:
  // Files directory/<name>_<step>.<extension>, index directory/<name>.pvd. The directory must
  // exist.
  Series(std::filesystem::path directory, std::string name, std::string extension);

  // Writes one file of the series and rewrites the index. Returns the file's path.
  std::filesystem::path write(std::uint64_t step, double time, const std::string& bytes);

  std::filesystem::path index_path() const;
  const std::vector<CollectionEntry>& entries() const { return entries_; }

  // Checkpoints: the entries so far. restore_state rewrites the index with them and removes the
  // series' files that are not among them (written after the checkpoint by the run resumed).
  void save_state(StateWriter& out) const;
  void restore_state(StateReader& in);

 private:
  std::filesystem::path directory_;
  std::string name_;
  std::string extension_;
  std::vector<CollectionEntry> entries_;
};

}  // namespace fsi::output
