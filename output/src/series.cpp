#include "fsi/output/series.hpp"

#include <cstdio>
#include <set>
#include <system_error>

#include "fsi/output/atomic_file.hpp"

namespace fsi::output {

namespace fs = std::filesystem;

std::string encode_collection(const std::vector<CollectionEntry>& entries) {
  std::string text =
      "<?xml version=\"1.0\"?>\n"
      "<VTKFile type=\"Collection\" version=\"1.0\" byte_order=\"LittleEndian\">\n"
      "  <Collection>\n";
  for (const auto& entry : entries) {
    char time[40];
    std::snprintf(time, sizeof time, "%.17g", entry.time);
    text += "    <DataSet timestep=\"" + std::string(time) + "\" part=\"0\" file=\"" + entry.file +
            "\"/>\n";
  }
  text += "  </Collection>\n</VTKFile>\n";
  return text;
}

Series::Series(fs::path directory, std::string name, std::string extension)
    : directory_(std::move(directory)), name_(std::move(name)), extension_(std::move(extension)) {}

fs::path Series::index_path() const {
  return directory_ / (name_ + ".pvd");
}

fs::path Series::write(std::uint64_t step, double time, const std::string& bytes) {
  char suffix[40];
  std::snprintf(suffix, sizeof suffix, "_%09llu.", static_cast<unsigned long long>(step));
  const std::string file_name = name_ + suffix + extension_;
  const fs::path path = directory_ / file_name;
  write_file_atomically(path, bytes);
  entries_.push_back({time, file_name});
  write_file_atomically(index_path(), encode_collection(entries_));
  return path;
}

void Series::save_state(StateWriter& out) const {
  out.section("series " + name_);
  out.put(static_cast<std::uint64_t>(entries_.size()));
  for (const CollectionEntry& entry : entries_) {
    out.put(entry.time);
    out.put(entry.file);
  }
}

void Series::restore_state(StateReader& in) {
  in.section("series " + name_);
  entries_.resize(in.count("entries"));
  std::set<std::string> kept;
  for (CollectionEntry& entry : entries_) {
    entry.time = in.f64("entry time");
    entry.file = in.text("entry file");
    kept.insert(entry.file);
  }
  std::error_code error;
  const std::string prefix = name_ + "_";
  const std::string suffix = "." + extension_;
  for (const auto& file : fs::directory_iterator(directory_, error)) {
    const std::string name = file.path().filename().string();
    if (name.starts_with(prefix) && name.ends_with(suffix) && !kept.contains(name))
      fs::remove(file.path(), error);
  }
  if (!entries_.empty() || fs::exists(index_path()))
    write_file_atomically(index_path(), encode_collection(entries_));
}

}  // namespace fsi::output
