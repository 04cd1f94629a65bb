#pragma once
// The server's side of one coupled run (thesis §4.4, Fig. 4.10; docs/protocol.md): accept the
// client, send the set-up, then per step integrate the structure with the fluid forces f(t) held
// constant, send the boundary state at t+dt, receive f(t+dt). Writes sensors.csv, particle
// snapshots and run.json into the output folder.

#include <chrono>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "fsi/protocol/auth.hpp"
#include "fsi/scene/scene.hpp"

namespace fsi::coupling {

struct ServerOptions {
  std::string listen_address = "127.0.0.1";
  std::uint16_t port = 0;  // 0: the operating system chooses
  std::string port_file;   // written (atomically) once listening
  std::string output_dir;
  std::chrono::milliseconds accept_timeout{std::chrono::minutes(2)};
  std::chrono::milliseconds handshake_timeout{std::chrono::seconds(30)};
  // --token-file: the client must prove this token, and the server proves it to the client
  // (docs/protocol.md, "Authentication"). None: clients are not authenticated.
  std::optional<protocol::Token> token;
  // Longest silence of the client (no message, no heartbeat) while the server waits for it: a
  // client that hangs (stopped, deadlocked) ends the run after this long. A client of protocol
  // 1.0 sends no heartbeats; then the wait for Ready (set-up and equilibration) is not bounded.
  std::chrono::milliseconds peer_timeout{std::chrono::minutes(5)};
  // Progress (progress.hpp): a log line every progress_interval on the logger "progress" (the
  // default logger if there is none); if live_status is set, it also gets the line about four
  // times a second (a terminal's status line) and an empty string when the coupled phase ends.
  std::chrono::milliseconds progress_interval{std::chrono::seconds(10)};
  std::function<void(const std::string&)> live_status;
  // fsi-server --resume: continue the run in output_dir from its newest complete checkpoint
  // (docs/user-guide.md, "Checkpoints and resume").
  bool resume = false;
  // --reconnect-timeout: when the client dies during the coupled steps (its connection closes
  // or falls silent), roll back to the newest checkpoint and wait this long for a client to
  // connect again (on the same port), which then takes the checkpoint's fluid; zero: the run
  // ends (docs/user-guide.md, "Checkpoints and resume").
  std::chrono::milliseconds reconnect_timeout{0};
  std::string command_line;            // recorded in run.json
  std::vector<std::string> overrides;  // --set KEY=EXPR, recorded in run.json (scene.overrides)
  std::vector<std::string> warnings;   // the scene's physics warnings, recorded in run.json
};

class FluidSide;

// Runs the session loop against any fluid side (tcp_fluid_side.hpp, or a test's in-process
// fake); the listening and handshake options are the TCP side's. Returns the process exit status
// (0 success, 1 failure). Never throws for faults of the run: they are logged, reported to the
// fluid side, and recorded in run.json.
int run_session(scene::Scene& scene, const ServerOptions& options, FluidSide& fluid);

// Runs the session with fsi-client over TCP; returns the process exit status (0 success, 1
// failure). Never throws for faults of the run: they are logged, told to the client if possible,
// and recorded in run.json.
int run_coupled_session(scene::Scene& scene, const ServerOptions& options);

}  // namespace fsi::coupling
