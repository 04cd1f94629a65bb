#pragma once
// LIGGGHTS writes its messages to a C FILE* ("screen"). OutputCapture provides such a FILE*
// that keeps the most recent lines (to quote LIGGGHTS' own error message when it stops),
// forwards ERROR/WARNING lines to stderr always, and echoes everything when asked.

#include <cstdio>
#include <deque>
#include <mutex>
#include <string>
#include <vector>

namespace fsi::client {

class OutputCapture {
 public:
  explicit OutputCapture(bool echo_everything, std::size_t kept_lines = 200);
  ~OutputCapture();
  OutputCapture(const OutputCapture&) = delete;
  OutputCapture& operator=(const OutputCapture&) = delete;

  std::FILE* stream() const { return stream_; }
  // Most recent complete lines, oldest first.
  std::vector<std::string> recent_lines() const;
  // The last line that starts with "ERROR", or an empty string.
  std::string last_error_line() const;

 private:
  static long write_callback(void* self, const char* data, std::size_t size);
  void take(const char* data, std::size_t size);

  bool echo_everything_;
  std::size_t kept_lines_;
  std::FILE* stream_ = nullptr;
  mutable std::mutex mutex_;
  std::string partial_;
  std::deque<std::string> lines_;
  std::string last_error_;
};

}  // namespace fsi::client
