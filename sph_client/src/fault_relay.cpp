#include "fault_relay.hpp"

#include <unistd.h>

#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <vector>

#include "fsi/protocol/messages.hpp"

namespace fsi::client {
namespace {

constexpr int kFaultTag = 0x46;  // 'F'
constexpr auto kPollInterval = std::chrono::milliseconds(20);
std::atomic<int> g_termination_signal{0};

// Formatted before any crash: a signal handler may only write(2).
char g_crash_prefix[96];
std::size_t g_crash_prefix_length = 0;

extern "C" void on_crash(int signal) {
  char text[160];
  std::memcpy(text, g_crash_prefix, g_crash_prefix_length);
  std::size_t length = g_crash_prefix_length;
  char digits[4];
  int count = 0;
  for (int value = signal; value > 0 && count < 4; value /= 10)
    digits[count++] = static_cast<char>('0' + value % 10);
  while (count > 0)
    text[length++] = digits[--count];
  text[length++] = '\n';
  [[maybe_unused]] const ssize_t written = ::write(STDERR_FILENO, text, length);
  std::signal(signal, SIG_DFL);
  std::raise(signal);
}

}  // namespace

FaultRelay::FaultRelay(MPI_Comm world, bool thread_multiple) {
  MPI_Comm_rank(world, &rank_);
  MPI_Comm_dup(world, &communicator_);
  active_ = thread_multiple;
  if (active_ && rank_ == 0) watcher_ = std::thread([this] { watch(); });
}

FaultRelay::~FaultRelay() {
  stopping_ = true;
  if (watcher_.joinable()) watcher_.join();
}

void FaultRelay::set_handler(Handler handler) {
  std::lock_guard lock(handler_mutex_);
  handler_ = std::move(handler);
}

void FaultRelay::note_termination_signal(int signal) {
  g_termination_signal = signal;
}

void FaultRelay::install_crash_report(int rank, int size) {
  const int length = std::snprintf(g_crash_prefix, sizeof g_crash_prefix,
                                   "fsi-client rank %d of %d: crashed with signal ", rank, size);
  g_crash_prefix_length = length > 0 ? static_cast<std::size_t>(length) : 0;
  for (const int signal : {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT})
    std::signal(signal, on_crash);
}

bool FaultRelay::tell_root(std::uint32_t code, const std::string& text, double seconds) {
  if (!active_ || rank_ == 0) return false;
  // The code, then the text; a report is small, so it goes out eagerly.
  std::vector<char> report(sizeof code + text.size());
  std::memcpy(report.data(), &code, sizeof code);
  std::memcpy(report.data() + sizeof code, text.data(), text.size());
  MPI_Request request;
  MPI_Isend(report.data(), static_cast<int>(report.size()), MPI_CHAR, 0, kFaultTag, communicator_,
            &request);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  int done = 0;
  while (true) {
    MPI_Test(&request, &done, MPI_STATUS_IGNORE);
    if (done) return true;
    if (std::chrono::steady_clock::now() > deadline) {
      MPI_Cancel(&request);
      return false;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
}

void FaultRelay::watch() {
  while (!stopping_) {
    int pending = 0;
    MPI_Status status;
    MPI_Iprobe(MPI_ANY_SOURCE, kFaultTag, communicator_, &pending, &status);
    if (pending) {
      int size = 0;
      MPI_Get_count(&status, MPI_CHAR, &size);
      std::vector<char> report(static_cast<std::size_t>(size));
      MPI_Recv(report.data(), size, MPI_CHAR, status.MPI_SOURCE, kFaultTag, communicator_,
               MPI_STATUS_IGNORE);
      std::uint32_t code = 0;
      std::string text;
      if (report.size() >= sizeof code) {
        std::memcpy(&code, report.data(), sizeof code);
        text.assign(report.data() + sizeof code, report.size() - sizeof code);
      }
      handle(status.MPI_SOURCE, code, text);
      return;
    }
    if (const int signal = g_termination_signal.load(); signal != 0) {
      handle(-1, static_cast<std::uint32_t>(protocol::ErrorCode::PeerAborted),
             "the MPI job was ended from outside (signal " + std::to_string(signal) +
                 " to rank 0): another rank crashed or was killed, or mpirun was stopped");
      return;
    }
    std::this_thread::sleep_for(kPollInterval);
  }
}

void FaultRelay::handle(int rank, std::uint32_t code, const std::string& text) {
  {
    std::lock_guard lock(handler_mutex_);
    if (handler_) handler_(rank, code, text);
  }
  MPI_Abort(MPI_COMM_WORLD, 1);
}

}  // namespace fsi::client
