#pragma once
// One coupled run as seen by fsi-client: rank 0 talks to fsi-server, every rank drives LIGGGHTS.
// Sequence (docs/protocol.md): handshake, set-up (script 1 with particle insertion, equilibration,
// script 2), initial forces, then Step -> Forces until Shutdown, with snapshots on request.

#include <mpi.h>

#include <chrono>
#include <cstdint>
#include <optional>
#include <string>

#include "fsi/protocol/auth.hpp"

namespace fsi::client {

struct ClientOptions {
  std::string host = "127.0.0.1";
  std::uint16_t port = 0;
  std::chrono::milliseconds connect_timeout{60000};
  // Longest silence of the server (no message, no heartbeat) once connected: a server that hangs
  // ends the client after this long.
  std::chrono::milliseconds peer_timeout{std::chrono::minutes(5)};
  // --token-file: the server must prove this token before its set-up is accepted, and the client
  // proves it to the server. None: the server is not authenticated.
  std::optional<protocol::Token> token;
  std::string liggghts_log;  // LIGGGHTS log file (rank 0); empty: none
  bool echo_liggghts = false;
  bool allow_unsafe_commands = false;  // run `shell` and files outside the run directory
  // After a successful run, wait for the next fsi-server at the same address and serve it too
  // (thesis §5.4.2 "Finalize"); connecting then waits without limit.
  bool persistent = false;
  // The balanced decomposition (docs/user-guide.md, "Ranks and balance"): the cuts between the
  // ranks' sub-domains follow the particles (off: LIGGGHTS' even cuts); the processor grid
  // follows the fluid's extent unless script 1 names one (`processors`).
  bool balance = true;
  bool automatic_grid = true;
  // Every this many LIGGGHTS steps the ranks' particle counts are compared; when the largest is
  // more than rebalance_threshold times the mean, the cuts move. 0: balanced at the set-up only.
  std::uint64_t rebalance_every = 100;
  double rebalance_threshold = 1.05;
};

// Runs the session; returns the process exit status. Faults end the whole MPI job: rank 0 tells
// the server what happened (if it still can) and every rank prints its message.
int run_client_session(MPI_Comm communicator, const ClientOptions& options);

}  // namespace fsi::client
