#include "fsi/coupling/output.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <system_error>

#include "fsi/common/error.hpp"
#include "fsi/output/atomic_file.hpp"

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
                       const std::vector<std::string>& names, const std::vector<std::string>& units,
                       std::optional<std::uint64_t> resume_at)
    : columns_(names.size()), path_(path), last_flush_(std::chrono::steady_clock::now()) {
  std::string header = "# " + title + "\n# units: time [s]";
  for (std::size_t i = 0; i < names.size(); ++i)
    header += ", " + names[i] + " [" + units[i] + "]";
  header += "\ntime";
  for (const auto& name : names)
    header += "," + name;
  header += "\n";
  if (!resume_at) {
    descriptor_ = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (descriptor_ < 0) throw output::file_error("cannot create", path, errno, "sensor output");
    append(header);
    return;
  }
  // Resumed: the earlier run's file, its header unchanged, cut back to the checkpoint's length.
  descriptor_ = ::open(path.c_str(), O_RDWR | O_CLOEXEC);
  if (descriptor_ < 0) {
    throw Error(std::string("cannot open ") + path + " to continue it: " + std::strerror(errno),
                "resumed sensor output",
                "resume in the folder of the run that wrote the checkpoint (--resume DIR)");
  }
  std::string start(header.size(), '\0');
  const ssize_t read = ::pread(descriptor_, start.data(), start.size(), 0);
  const off_t size = ::lseek(descriptor_, 0, SEEK_END);
  if (read != static_cast<ssize_t>(header.size()) || start != header) {
    ::close(descriptor_);
    descriptor_ = -1;
    throw Error(path + " has another header than this scene writes (its columns or title differ)",
                "resumed sensor output",
                "resume with the scene that wrote the checkpoint, unchanged in its sensors");
  }
  if (size < 0 || static_cast<std::uint64_t>(size) < *resume_at) {
    ::close(descriptor_);
    descriptor_ = -1;
    throw Error(path + " holds " + std::to_string(size) + " bytes, the checkpoint recorded " +
                    std::to_string(*resume_at) + " (the file was cut or replaced)",
                "resumed sensor output",
                "resume from a run folder whose files are as the run left them");
  }
  if (::ftruncate(descriptor_, static_cast<off_t>(*resume_at)) != 0)
    throw output::file_error("cannot cut back", path, errno, "sensor output");
}

std::uint64_t SensorFile::length() {
  flush();
  const off_t end = ::lseek(descriptor_, 0, SEEK_END);
  if (end < 0) throw output::file_error("cannot measure", path_, errno, "sensor output");
  return static_cast<std::uint64_t>(end);
}

namespace {

// printf's %.17g (the round-trip text of a double), after `separator`.
void append_number(std::string& text, const char* separator, double value) {
  char digits[40];
  const int length = std::snprintf(digits, sizeof digits, "%s%.17g", separator, value);
  text.append(digits, static_cast<std::size_t>(length));
}

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
                       const std::vector<probes::ProbeDefinition>& probes, int dimension,
                       std::optional<std::uint64_t> resume_at)
    : SensorFile(path.string(), title, names_of(columns_of(sensors, probes, dimension)),
                 units_of(columns_of(sensors, probes, dimension)), resume_at) {}

SensorFile::~SensorFile() {
  if (descriptor_ < 0) return;
  try {
    flush();
  } catch (const std::exception&) {
    // The run has ended already; its error was reported where it happened.
  }
  ::close(descriptor_);
}

void SensorFile::write(double time, const std::vector<double>& values) {
  FSI_ASSERT(values.size() == columns_, "a row of another width than its CSV file's header");
  append_number(pending_, "", time);
  for (double value : values)
    append_number(pending_, ",", value);
  pending_ += '\n';
  const auto now = std::chrono::steady_clock::now();
  if (now - last_flush_ > std::chrono::seconds(1)) {
    flush();
    last_flush_ = now;
  }
}

void SensorFile::flush() {
  if (pending_.empty()) return;
  append(pending_);
  pending_.clear();
}

void SensorFile::append(const std::string& text) {
  const off_t whole = ::lseek(descriptor_, 0, SEEK_END);
  std::size_t done = 0;
  while (done < text.size()) {
    const ssize_t written = ::write(descriptor_, text.data() + done, text.size() - done);
    if (written < 0 && errno == EINTR) continue;
    if (written <= 0) {
      const int error_number = written < 0 ? errno : ENOSPC;
      // A part of a row must not look like a row to a reader.
      if (whole >= 0 && ::ftruncate(descriptor_, whole) == 0) ::lseek(descriptor_, whole, SEEK_SET);
      pending_.clear();
      throw output::file_error("cannot write", path_, error_number, "sensor output");
    }
    done += static_cast<std::size_t>(written);
  }
}

void write_snapshot_csv(const std::string& path, const ParticleSnapshot& snapshot) {
  const bool spatial = snapshot.dimension == 3;
  std::string text = "# SPH particles at step " + std::to_string(snapshot.step) + ", t = ";
  append_number(text, "", snapshot.time);
  text +=
      spatial ? " s\nid,x,y,z,vx,vy,vz,density,pressure\n" : " s\nid,x,y,vx,vy,density,pressure\n";
  const auto dimension = static_cast<std::size_t>(snapshot.dimension);
  for (std::size_t i = 0; i < snapshot.ids.size(); ++i) {
    text += std::to_string(snapshot.ids[i]);
    for (const auto* values : {&snapshot.positions, &snapshot.velocities}) {
      for (std::size_t k = 0; k < dimension; ++k)
        append_number(text, ",", (*values)[dimension * i + k]);
    }
    append_number(text, ",", snapshot.density[i]);
    append_number(text, ",", snapshot.pressure[i]);
    text += '\n';
  }
  output::write_file_atomically(path, text);
}

}  // namespace fsi::coupling
