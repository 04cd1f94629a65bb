#pragma once
// Files of a run folder: sensors.csv (one column per sensor, flushed on a schedule) and
// particle snapshots (snapshots/particles_<step>.csv).

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "fsi/scene/scene.hpp"

namespace fsi::coupling {

// Creates the run folder `folder` (and its parents) given by --output; an fsi::Error saying so if
// it cannot.
void create_run_folder(const std::string& folder);

class SensorFile {
 public:
  // names/units exclude the time column.
  SensorFile(const std::string& path, const std::string& title,
             const std::vector<std::string>& names, const std::vector<std::string>& units);
  // One column per sensor of the scene, named and united as declared, then the probes' columns
  // (fsi::probes::columns) in `dimension`.
  SensorFile(const std::filesystem::path& path, const std::string& title,
             const std::vector<scene::SensorSpec>& sensors,
             const std::vector<probes::ProbeDefinition>& probes = {}, int dimension = 2);
  ~SensorFile();
  SensorFile(const SensorFile&) = delete;
  SensorFile& operator=(const SensorFile&) = delete;

  void write(double time, const std::vector<double>& values);
  void flush();

 private:
  std::FILE* file_ = nullptr;
  std::string path_;
  std::chrono::steady_clock::time_point last_flush_;
};

struct ParticleSnapshot {
  std::uint64_t step = 0;
  double time = 0.0;
  std::vector<std::uint64_t> ids;
  int dimension = 2;  // values per particle in positions and velocities
  std::vector<double> positions, velocities, density, pressure;
};

void write_snapshot_csv(const std::string& path, const ParticleSnapshot& snapshot);

}  // namespace fsi::coupling
