#include "fsi/output/series.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>

#include "fsi/common/error.hpp"

namespace fsi::output {

namespace fs = std::filesystem;

void write_file_atomically(const fs::path& path, const std::string& bytes) {
  const fs::path temporary = fs::path(path.string() + ".tmp");
  std::FILE* file = std::fopen(temporary.c_str(), "wb");
  if (!file) {
    throw Error("cannot create " + temporary.string() + ": " + std::strerror(errno), "VTK output",
                "choose a writable --output folder with free space");
  }
  const std::size_t written = std::fwrite(bytes.data(), 1, bytes.size(), file);
  const bool closed = std::fclose(file) == 0;
  if (written != bytes.size() || !closed) {
    std::remove(temporary.c_str());
    throw Error("cannot write " + temporary.string() + " (" + std::to_string(written) + " of " +
                    std::to_string(bytes.size()) + " bytes written)",
                "VTK output", "free disk space in the --output folder");
  }
  std::error_code error;
  fs::rename(temporary, path, error);
  if (error) {
    throw Error(
        "cannot rename " + temporary.string() + " to " + path.string() + ": " + error.message(),
        "VTK output", "check the permissions of the --output folder");
  }
}

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

}  // namespace fsi::output
