#include "fsi/output/run_folder.hpp"

#include <sys/stat.h>

#include <algorithm>
#include <ctime>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>
#include <system_error>

#include "fsi/common/error.hpp"

namespace fsi::output {
namespace {

namespace fs = std::filesystem;

// What our programs write into a run folder: fsi-server (run.json, sensors.csv, energy.csv, its
// log, snapshots/, vtk/), fsi-client under fsi-run (its logs) and fsi-plot (plots/). Temporary
// names of the atomic writes (NAME.tmp) belong to the same files.
const std::vector<std::string> kTopFiles = {"run.json", "sensors.csv", "energy.csv",
                                            "fsi-server.log", "fsi-client.log"};
struct OwnFolder {
  const char* name;
  const char* file_pattern;
};
const std::vector<OwnFolder> kOwnFolders = {
    {"snapshots", R"(particles_\d+\.csv(\.tmp)?)"},
    {"vtk", R"([A-Za-z]+(_\d+\.(vtu|vtp)|\.pvd)(\.tmp)?)"},
    {"plots", R"(.*\.(png|mp4)(\.tmp)?)"},
};

bool own_top_file(const std::string& name) {
  for (const std::string& file : kTopFiles) {
    if (name == file || name == file + ".tmp") return true;
  }
  // fsi-client --log-all-ranks: FILE.rank<r>.
  return std::regex_match(name, std::regex(R"(fsi-client\.log\.rank\d+)"));
}

std::vector<fs::path> own_files_in(const fs::path& folder, const OwnFolder& own) {
  std::vector<fs::path> files;
  std::error_code error;
  const std::regex pattern(own.file_pattern);
  for (const auto& entry : fs::directory_iterator(folder / own.name, error)) {
    if (entry.is_regular_file(error) &&
        std::regex_match(entry.path().filename().string(), pattern)) {
      files.push_back(entry.path());
    }
  }
  return files;
}

std::string utc_text(std::time_t seconds) {
  std::tm parts{};
  gmtime_r(&seconds, &parts);
  char text[40];
  std::strftime(text, sizeof text, "%Y-%m-%d %H:%M:%S UTC", &parts);
  return text;
}

std::string modification_time(const fs::path& path) {
  struct stat status {};
  if (::stat(path.c_str(), &status) != 0) return {};
  return utc_text(status.st_mtime) + " (file date)";
}

// Data rows of sensors.csv, counted up to 1 (enough to know there are results).
std::uint64_t has_sensor_rows(const fs::path& path) {
  std::ifstream in(path);
  std::string line;
  bool header = false;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    if (header) return 1;
    header = true;
  }
  return 0;
}

void read_manifest(const fs::path& path, EarlierRun& run) {
  run.manifest = true;
  std::ifstream in(path);
  nlohmann::json manifest;
  try {
    manifest = nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& bad) {
    run.manifest_problem = std::string("run.json cannot be read: ") + bad.what();
    return;
  }
  try {
    if (manifest.contains("scene") && manifest["scene"].is_object())
      run.scene = manifest["scene"].value("file", "");
    run.status = manifest.value("status", "");
    if (manifest.contains("steps") && manifest["steps"].is_number_unsigned())
      run.steps = manifest["steps"].get<std::uint64_t>();
    const std::string started = manifest.value("started_utc", "");
    if (!started.empty()) {
      // "2026-12-02T11:40:12Z" as "2026-12-02 11:40:12 UTC".
      std::string text = started;
      if (text.size() == 20 && text[10] == 'T' && text[19] == 'Z')
        text = text.substr(0, 10) + " " + text.substr(11, 8) + " UTC";
      run.started = text;
    }
  } catch (const nlohmann::json::exception& bad) {
    run.manifest_problem = std::string("run.json has an unexpected shape: ") + bad.what();
  }
  if (run.started.empty()) run.started = modification_time(path);
}

std::string list(const std::vector<std::string>& names) {
  std::string text;
  for (const std::string& name : names)
    text += (text.empty() ? "" : ", ") + name;
  return text;
}

}  // namespace

bool EarlierRun::has_results() const {
  if (manifest) {
    if (!manifest_problem.empty()) return true;
    const bool failed_before_stepping = status == "failed" && steps && *steps == 0;
    return !failed_before_stepping;
  }
  return sensor_rows > 0 || snapshots;
}

std::string EarlierRun::summary() const {
  std::vector<std::string> parts;
  if (!scene.empty()) parts.push_back("scene " + scene);
  if (!started.empty()) parts.push_back("started " + started);
  if (status == "started") {
    parts.push_back("status started, no end recorded (still running, or killed)");
  } else if (!status.empty()) {
    parts.push_back("status " + status);
  }
  if (steps) parts.push_back(std::to_string(*steps) + " steps");
  if (!manifest) parts.push_back("no run.json (the run was killed before writing it)");
  if (!manifest_problem.empty()) parts.push_back(manifest_problem);
  return list(parts);
}

std::optional<EarlierRun> inspect_run_folder(const fs::path& folder) {
  std::error_code error;
  if (!fs::is_directory(folder, error)) return std::nullopt;
  EarlierRun run;
  for (const auto& entry : fs::directory_iterator(folder, error)) {
    const std::string name = entry.path().filename().string();
    if (entry.is_regular_file(error) && own_top_file(name)) run.found.push_back(name);
  }
  for (const OwnFolder& own : kOwnFolders) {
    const std::vector<fs::path> files = own_files_in(folder, own);
    if (files.empty()) continue;
    run.found.push_back(std::string(own.name) + "/");
    if (std::string(own.name) != "plots") run.snapshots = true;
  }
  if (run.found.empty()) return std::nullopt;
  std::sort(run.found.begin(), run.found.end());
  if (fs::exists(folder / "run.json", error)) read_manifest(folder / "run.json", run);
  if (fs::exists(folder / "sensors.csv", error))
    run.sensor_rows = has_sensor_rows(folder / "sensors.csv");
  return run;
}

std::optional<EarlierRun> claim_run_folder(const fs::path& folder, bool overwrite) {
  std::optional<EarlierRun> earlier = inspect_run_folder(folder);
  if (earlier && earlier->has_results() && !overwrite) {
    throw Error("this folder holds the results of an earlier run (" + earlier->summary() + "; " +
                    list(earlier->found) + ")",
                "--output " + folder.string(),
                "choose another --output folder to keep them, or add --overwrite to replace "
                "that run's files (files of your own in the folder stay)");
  }
  return earlier;
}

std::vector<fs::path> remove_earlier_run(const fs::path& folder) {
  std::vector<fs::path> removed;
  std::error_code error;
  auto remove = [&](const fs::path& path) {
    if (fs::remove(path, error)) {
      removed.push_back(path);
    } else if (error) {
      throw Error("cannot remove " + path.string() + " of the earlier run: " + error.message(),
                  "--overwrite", "make the --output folder writable, or choose another one");
    }
  };
  for (const auto& entry : fs::directory_iterator(folder, error)) {
    if (entry.is_regular_file(error) && own_top_file(entry.path().filename().string()))
      remove(entry.path());
  }
  for (const OwnFolder& own : kOwnFolders) {
    for (const fs::path& file : own_files_in(folder, own))
      remove(file);
    const fs::path subfolder = folder / own.name;
    if (fs::is_directory(subfolder, error) && fs::is_empty(subfolder, error)) remove(subfolder);
  }
  return removed;
}

}  // namespace fsi::output
