#include "fsi/coupling/output.hpp"

#include <cerrno>
#include <cstring>
#include <system_error>

#include "fsi/common/error.hpp"

namespace fsi::coupling {

void create_run_folder(const std::string& folder) {
  std::error_code error;
  std::filesystem::create_directories(folder, error);
  if (error) {
    throw Error("cannot create output folder " + folder + ": " + error.message(), "--output",
                "choose a writable folder");
  }
}

SensorFile::SensorFile(const std::string& path, const std::string& title,
                       const std::vector<std::string>& names, const std::vector<std::string>& units)
    : path_(path), last_flush_(std::chrono::steady_clock::now()) {
  file_ = std::fopen(path.c_str(), "w");
  if (!file_) {
    throw Error("cannot write " + path + ": " + std::strerror(errno), "output folder",
                "choose a writable --output folder");
  }
  std::fprintf(file_, "# %s\n# units: time [s]", title.c_str());
  for (std::size_t i = 0; i < names.size(); ++i)
    std::fprintf(file_, ", %s [%s]", names[i].c_str(), units[i].c_str());
  std::fprintf(file_, "\ntime");
  for (const auto& name : names)
    std::fprintf(file_, ",%s", name.c_str());
  std::fprintf(file_, "\n");
  std::fflush(file_);
}

namespace {

std::vector<probes::Column> columns_of(const std::vector<scene::SensorSpec>& sensors,
                                       const std::vector<probes::ProbeDefinition>& probes,
                                       int dimension) {
  std::vector<probes::Column> columns;
  for (const auto& sensor : sensors)
    columns.push_back({sensor.name, sensor.unit});
  for (const auto& probe : probes) {
    for (auto& column : probes::columns(probe, dimension))
      columns.push_back(std::move(column));
  }
  return columns;
}

std::vector<std::string> names_of(const std::vector<probes::Column>& columns) {
  std::vector<std::string> names;
  for (const auto& column : columns)
    names.push_back(column.name);
  return names;
}

std::vector<std::string> units_of(const std::vector<probes::Column>& columns) {
  std::vector<std::string> units;
  for (const auto& column : columns)
    units.push_back(column.unit);
  return units;
}

}  // namespace

SensorFile::SensorFile(const std::filesystem::path& path, const std::string& title,
                       const std::vector<scene::SensorSpec>& sensors,
                       const std::vector<probes::ProbeDefinition>& probes, int dimension)
    : SensorFile(path.string(), title, names_of(columns_of(sensors, probes, dimension)),
                 units_of(columns_of(sensors, probes, dimension))) {}

SensorFile::~SensorFile() {
  if (file_) std::fclose(file_);
}

void SensorFile::write(double time, const std::vector<double>& values) {
  std::fprintf(file_, "%.17g", time);
  for (double value : values)
    std::fprintf(file_, ",%.17g", value);
  std::fputc('\n', file_);
  // A crash loses at most about one second of rows.
  const auto now = std::chrono::steady_clock::now();
  if (now - last_flush_ > std::chrono::seconds(1)) {
    flush();
    last_flush_ = now;
  }
}

void SensorFile::flush() {
  if (std::fflush(file_) != 0) {
    throw Error("cannot write " + path_ + ": " + std::strerror(errno), "sensor output",
                "free disk space");
  }
}

void write_snapshot_csv(const std::string& path, const ParticleSnapshot& snapshot) {
  std::FILE* file = std::fopen(path.c_str(), "w");
  if (!file) {
    throw Error("cannot write " + path + ": " + std::strerror(errno), "snapshot output",
                "free disk space");
  }
  const bool spatial = snapshot.dimension == 3;
  std::fprintf(file, "# SPH particles at step %llu, t = %.17g s\n%s\n",
               static_cast<unsigned long long>(snapshot.step), snapshot.time,
               spatial ? "id,x,y,z,vx,vy,vz,density,pressure" : "id,x,y,vx,vy,density,pressure");
  const auto dimension = static_cast<std::size_t>(snapshot.dimension);
  for (std::size_t i = 0; i < snapshot.ids.size(); ++i) {
    std::fprintf(file, "%llu", static_cast<unsigned long long>(snapshot.ids[i]));
    for (const auto* values : {&snapshot.positions, &snapshot.velocities}) {
      for (std::size_t k = 0; k < dimension; ++k)
        std::fprintf(file, ",%.17g", (*values)[dimension * i + k]);
    }
    std::fprintf(file, ",%.17g,%.17g\n", snapshot.density[i], snapshot.pressure[i]);
  }
  std::fclose(file);
}

}  // namespace fsi::coupling
