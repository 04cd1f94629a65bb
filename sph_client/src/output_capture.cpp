#include "output_capture.hpp"

#include <spdlog/spdlog.h>

#include <stdexcept>

namespace fsi::client {

OutputCapture::OutputCapture(bool echo_everything, std::size_t kept_lines)
    : echo_everything_(echo_everything), kept_lines_(kept_lines) {
  cookie_io_functions_t functions{};
  functions.write = [](void* self, const char* data, std::size_t size) -> ssize_t {
    return write_callback(self, data, size);
  };
  stream_ = fopencookie(this, "w", functions);
  if (!stream_) throw std::runtime_error("cannot create the LIGGGHTS output stream");
  std::setvbuf(stream_, nullptr, _IOLBF, 0);
}

OutputCapture::~OutputCapture() {
  if (stream_) std::fclose(stream_);
}

long OutputCapture::write_callback(void* self, const char* data, std::size_t size) {
  static_cast<OutputCapture*>(self)->take(data, size);
  return static_cast<long>(size);
}

void OutputCapture::take(const char* data, std::size_t size) {
  std::lock_guard lock(mutex_);
  if (echo_everything_) std::fwrite(data, 1, size, stdout);
  partial_.append(data, size);
  std::size_t start = 0;
  for (std::size_t end; (end = partial_.find('\n', start)) != std::string::npos; start = end + 1) {
    std::string line = partial_.substr(start, end - start);
    const bool error = line.rfind("ERROR", 0) == 0;
    if (!echo_everything_ && (error || line.rfind("WARNING", 0) == 0)) {
      if (error) {
        spdlog::error("LIGGGHTS: {}", line);
      } else {
        spdlog::warn("LIGGGHTS: {}", line);
      }
    }
    if (error) last_error_ = line;
    lines_.push_back(std::move(line));
    if (lines_.size() > kept_lines_) lines_.pop_front();
  }
  partial_.erase(0, start);
}

std::vector<std::string> OutputCapture::recent_lines() const {
  std::lock_guard lock(mutex_);
  return {lines_.begin(), lines_.end()};
}

std::string OutputCapture::last_error_line() const {
  std::lock_guard lock(mutex_);
  return last_error_;
}

}  // namespace fsi::client
