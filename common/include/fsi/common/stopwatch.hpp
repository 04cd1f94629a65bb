#pragma once
#include <chrono>

namespace fsi {

// Accumulates wall time over several start/stop intervals (monotonic clock).
class Stopwatch {
 public:
  using Clock = std::chrono::steady_clock;

  void start() {
    started_ = Clock::now();
    running_ = true;
  }
  // Adds the interval since start() to the total and returns that interval in seconds.
  double stop() {
    const double interval = std::chrono::duration<double>(Clock::now() - started_).count();
    total_ += interval;
    running_ = false;
    return interval;
  }
  // The total, with the interval still running (a record written while the run goes on).
  double seconds() const {
    return running_ ? total_ + std::chrono::duration<double>(Clock::now() - started_).count()
                    : total_;
  }
  void reset() { total_ = 0.0; }
  // Continues the total of an earlier process (a resumed run).
  void add(double seconds) { total_ += seconds; }

 private:
  Clock::time_point started_{Clock::now()};
  double total_ = 0.0;
  bool running_ = false;
};

// Adds the lifetime of the scope to a Stopwatch.
class ScopedTimer {
 public:
  explicit ScopedTimer(Stopwatch& watch) : watch_(watch) { watch_.start(); }
  ~ScopedTimer() { watch_.stop(); }
  ScopedTimer(const ScopedTimer&) = delete;
  ScopedTimer& operator=(const ScopedTimer&) = delete;

 private:
  Stopwatch& watch_;
};

}  // namespace fsi
