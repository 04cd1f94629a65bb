#pragma once
// A fault that one rank sees must reach fsi-server, and only rank 0 talks to it. The failing rank
// cannot wait for rank 0 in a collective call (rank 0 may itself wait in one inside LIGGGHTS for
// the failing rank), so rank 0 keeps a watcher thread that takes fault reports from any rank on a
// communicator of their own (MPI_THREAD_MULTIPLE), hands them to the session, which tells the
// server, and ends the job. The watcher also notices a SIGTERM from mpirun (another rank crashed
// or aborted) and reports that. Without MPI_THREAD_MULTIPLE there is no watcher: a rank > 0 then
// ends the job with its message on its own stderr only.

#include <mpi.h>

#include <atomic>
#include <cstdint>
#include <functional>
#include <mutex>
#include <string>
#include <thread>

namespace fsi::client {

class FaultRelay {
 public:
  // Collective over `world` (duplicates it). thread_multiple: MPI_Init_thread provided
  // MPI_THREAD_MULTIPLE; without it the relay only knows it cannot relay.
  FaultRelay(MPI_Comm world, bool thread_multiple);
  ~FaultRelay();
  FaultRelay(const FaultRelay&) = delete;
  FaultRelay& operator=(const FaultRelay&) = delete;

  bool active() const { return active_; }

  // Rank 0: what to do with a fault report (rank, error code, text); called on the watcher
  // thread, which ends the job (MPI_Abort) when it returns. Empty: no session to tell.
  using Handler = std::function<void(int rank, std::uint32_t code, const std::string& text)>;
  void set_handler(Handler handler);

  // Rank > 0: sends the report to rank 0 (waits at most `seconds` for it to leave). False when
  // the relay is inactive or the report could not be sent.
  bool tell_root(std::uint32_t code, const std::string& text, double seconds = 2.0);

  // The SIGTERM mpirun sends every rank when another one crashed or aborted (installed by
  // fsi-client's main on every rank; only rank 0's watcher reports it).
  static void note_termination_signal(int signal);

  // Every rank: a crash (SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT) prints "fsi-client rank R of N:
  // crashed with signal S" on stderr before the process dies as it would have (mpirun -q, which
  // fsi-run uses, says nothing of it; rank 0 then reports the job ended from outside).
  static void install_crash_report(int rank, int size);

 private:
  void watch();
  void handle(int rank, std::uint32_t code, const std::string& text);
  MPI_Comm communicator_ = MPI_COMM_NULL;
  int rank_ = 0;
  bool active_ = false;
  std::atomic<bool> stopping_{false};
  std::mutex handler_mutex_;
  Handler handler_;
  std::thread watcher_;
};

}  // namespace fsi::client
