#pragma once
// Files of a run folder: sensors.csv (one column per sensor, whole rows appended on a schedule)
// and particle snapshots (snapshots/particles_<step>.csv, each written whole or not at all).

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "fsi/scene/scene.hpp"

namespace fsi::coupling {

// Creates the run folder `folder` (and its parents) given by --output; an fsi::Error saying so if
// it cannot.
void create_run_folder(const std::string& folder);

class SensorFile {
 public:
  // names/units exclude the time column. resume_at: a resumed run continues the file of the run
  // it resumes, cut back to the length it had at the checkpoint (rows written after it go); the
  // file must exist with the same header and at least that length, else fsi::Error says so.
  SensorFile(const std::string& path, const std::string& title,
             const std::vector<std::string>& names, const std::vector<std::string>& units,
             std::optional<std::uint64_t> resume_at = std::nullopt);
  // One column per sensor of the scene, named and united as declared, then the probes' columns
  // (fsi::probes::columns) in `dimension`.
  SensorFile(const std::filesystem::path& path, const std::string& title,
             const std::vector<scene::SensorSpec>& sensors,
             const std::vector<probes::ProbeDefinition>& probes = {}, int dimension = 2,
             std::optional<std::uint64_t> resume_at = std::nullopt);
  ~SensorFile();
  SensorFile(const SensorFile&) = delete;
  SensorFile& operator=(const SensorFile&) = delete;

  // Appends a row; rows reach the file about once a second and at flush(). Throws an fsi::Error
  // naming the file when the system refuses the write (a full disk).
  // values: one per column (the header's, time excluded); another count is a bug (asserted).
  void write(double time, const std::vector<double>& values);
  std::size_t columns() const { return columns_; }
  void flush();
  // Flushes and returns the file's length: whole rows up to the last one written (a checkpoint
  // records it, a resume cuts the file back to it).
  std::uint64_t length();

 private:
  // The file holds whole rows only: rows are written whole, and a write the disk refuses is cut
  // back to the last whole row before the error is thrown. A crash loses the rows not yet
  // written (at most about a second's).
  void append(const std::string& text);
  int descriptor_ = -1;
  std::size_t columns_ = 0;  // values per row, time excluded
  std::string path_;
  std::string pending_;  // whole rows not yet written
  std::chrono::steady_clock::time_point last_flush_;
};

struct ParticleSnapshot {
  std::uint64_t step = 0;
  double time = 0.0;
  std::vector<std::uint64_t> ids;
  int dimension = 2;  // values per particle in positions and velocities
  std::vector<double> positions, velocities, density, pressure;
};

// The snapshot's CSV text, written whole or not at all (fsi::output::write_file_atomically).
void write_snapshot_csv(const std::string& path, const ParticleSnapshot& snapshot);

}  // namespace fsi::coupling
