#include "fsi/output/atomic_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace fsi::output {

namespace fs = std::filesystem;

Error file_error(const std::string& action, const fs::path& path, int error_number,
                 const std::string& what_file) {
  std::string fix;
  switch (error_number) {
    case ENOSPC:
    case EDQUOT:
      fix = "free space on the disk of " + path.parent_path().string() + " (df -h " +
            path.parent_path().string() + ") or choose an --output folder on a disk with room";
      break;
    case EACCES:
    case EPERM:
    case EROFS:
      fix = "make " + path.parent_path().string() +
            " writable for this user, or choose a writable --output folder";
      break;
    case ENOENT:
    case ENOTDIR:
      fix = "the folder " + path.parent_path().string() +
            " is missing (removed during the run?); choose an --output folder that exists";
      break;
    default:
      fix = "check the disk and the --output folder";
  }
  return Error(action + " " + path.string() + ": " + std::strerror(error_number), what_file, fix);
}

namespace {

// write(2) until everything is written; false with errno set otherwise.
bool write_all(int descriptor, std::string_view bytes) {
  while (!bytes.empty()) {
    const ssize_t written = ::write(descriptor, bytes.data(), bytes.size());
    if (written < 0) {
      if (errno == EINTR) continue;
      return false;
    }
    bytes.remove_prefix(static_cast<std::size_t>(written));
  }
  return true;
}

}  // namespace

void sync_folder(const fs::path& folder) noexcept {
  const int descriptor = ::open(folder.empty() ? "." : folder.c_str(), O_RDONLY | O_DIRECTORY);
  if (descriptor < 0) return;
  ::fsync(descriptor);
  ::close(descriptor);
}

void write_file_atomically(const fs::path& path, std::string_view bytes, Durability durability) {
  const fs::path temporary = fs::path(path.string() + ".tmp");
  const int descriptor = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (descriptor < 0) throw file_error("cannot create", temporary, errno, "output file");
  bool written = write_all(descriptor, bytes);
  int error_number = written ? 0 : errno;
  if (written && durability == Durability::MachineCrash && ::fsync(descriptor) != 0) {
    written = false;
    error_number = errno;
  }
  if (::close(descriptor) != 0 && written) {
    written = false;
    error_number = errno;
  }
  if (!written) {
    ::unlink(temporary.c_str());
    throw file_error("cannot write", path, error_number, "output file");
  }
  if (std::rename(temporary.c_str(), path.c_str()) != 0) {
    error_number = errno;
    ::unlink(temporary.c_str());
    throw file_error("cannot rename " + temporary.string() + " to", path, error_number,
                     "output file");
  }
  if (durability == Durability::MachineCrash) sync_folder(path.parent_path());
}

void check_writable(const fs::path& path, const std::string& what_file) {
  const int descriptor = ::open(path.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
  if (descriptor < 0) throw file_error("cannot write", path, errno, what_file);
  ::close(descriptor);
}

}  // namespace fsi::output
