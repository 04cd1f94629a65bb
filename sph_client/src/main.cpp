// fsi-client: `mpirun -np N fsi-client --server HOST:PORT`. Rank 0 connects to fsi-server (retrying
// until it listens), all ranks run LIGGGHTS with `fix fsi/sph`, one LIGGGHTS step per server step.
#include <mpi.h>
#include <spdlog/sinks/basic_file_sink.h>
#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>
#include <CLI/CLI.hpp>

#include <algorithm>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "client_session.hpp"
#include "fsi/common/error.hpp"
#include "fsi/common/version.hpp"
#include "fsi/protocol/auth.hpp"
#include "fsi/protocol/channel.hpp"

namespace {

// Rank-aware logs: rank 0 logs at the chosen level to stderr and --log-file; the other ranks only
// report warnings and errors (what one rank sees must still be told, e.g. fix fsi/sph's
// close-approach warning for a particle of rank 1), unless --log-all-ranks, which gives each
// rank r > 0 its own file FILE.rank<r> (one file per rank: no interleaved lines). The files are
// appended to: a resumed run continues the log of the run it resumes.
void configure_logging(int rank, const std::string& level, const std::string& log_file,
                       bool all_ranks) {
  std::vector<spdlog::sink_ptr> sinks{std::make_shared<spdlog::sinks::stderr_color_sink_mt>()};
  const bool verbose = rank == 0 || all_ranks;
  if (!log_file.empty() && verbose) {
    const std::string path = rank == 0 ? log_file : log_file + ".rank" + std::to_string(rank);
    sinks.push_back(std::make_shared<spdlog::sinks::basic_file_sink_mt>(path, false));
  }
  auto logger = std::make_shared<spdlog::logger>("fsi-client", sinks.begin(), sinks.end());
  logger->set_pattern("[%H:%M:%S.%e] [fsi-client rank " + std::to_string(rank) + "] [%l] %v");
  const spdlog::level::level_enum chosen = spdlog::level::from_str(level);
  logger->set_level(verbose ? chosen : std::max(chosen, spdlog::level::warn));
  logger->flush_on(spdlog::level::info);
  spdlog::set_default_logger(logger);
}

}  // namespace

int main(int argc, char** argv) {
  // Rank 0's fault watcher (fault_relay.hpp) calls MPI beside the main thread.
  int threading = MPI_THREAD_SINGLE;
  MPI_Init_thread(&argc, &argv, MPI_THREAD_MULTIPLE, &threading);
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);

  CLI::App app{
      "fsi-client: the SPH side of the FSI co-simulation. Run it under MPI "
      "(mpirun -np N fsi-client --server HOST:PORT); rank 0 talks to fsi-server, all "
      "ranks drive LIGGGHTS."};
  app.set_version_flag("--version", fsi::version_text());
  std::string server;
  double connect_timeout = 60.0;
  fsi::client::ClientOptions options;
  app.add_option("--server", server, "Address of fsi-server as HOST:PORT")->required();
  app.add_option("--connect-timeout", connect_timeout,
                 "Seconds to keep retrying while the server does not listen yet")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  double peer_timeout = 300.0;
  app.add_option("--peer-timeout", peer_timeout,
                 "Seconds of silence from fsi-server after which the client gives up (a stopped "
                 "or hung server). A computing server sends a heartbeat every 0.5 s, so long "
                 "structure solves do not count as silence. At least 2")
      ->check(CLI::Range(2.0, 1e9))
      ->capture_default_str();
  std::string token_file;
  app.add_option("--token-file", token_file,
                 "Shared token (same content as fsi-server's --token-file): the server must prove "
                 "it holds it before its set-up is accepted, and this client proves it in turn; "
                 "default: none)");
  app.add_option("--liggghts-log", options.liggghts_log,
                 "Write LIGGGHTS' log to this file (default: none)");
  app.add_flag("--echo", options.echo_liggghts,
               "Show LIGGGHTS' screen output (rank 0; default: off, only its warnings and errors)");
  app.add_flag("--persistent", options.persistent,
               "After a run, wait for the next fsi-server at the same address and serve it too "
               "(until interrupted); a failed run still ends the client (default: off)");
  app.add_flag("--allow-unsafe-commands", options.allow_unsafe_commands,
               "Run script commands that are refused by default: 'shell' and file names outside "
               "the run directory (absolute, ~ or ..). Only for scenes you trust (default: off)");
  std::string balance = "on";
  app.add_option("--balance", balance,
                 "Move the cuts between the ranks' sub-domains so that each rank owns an equal "
                 "share of the particles, at the set-up and as the fluid moves (off: LIGGGHTS' "
                 "even cuts; docs/user-guide.md, 'Ranks and balance')")
      ->capture_default_str()
      ->check(CLI::IsMember({"on", "off"}));
  std::string grid = "auto";
  app.add_option("--grid", grid,
                 "Processor grid when script 1 has no 'processors' command: auto (the fewest cuts "
                 "through the fluid's bounding box) or liggghts (LIGGGHTS' choice from the box). "
                 "A 'processors' command in script 1 always wins")
      ->capture_default_str()
      ->check(CLI::IsMember({"auto", "liggghts"}));
  app.add_option("--rebalance-every", options.rebalance_every,
                 "Compare the ranks' particle counts every this many LIGGGHTS steps and re-balance "
                 "when the largest exceeds --rebalance-threshold times the mean; 0: balance at the "
                 "set-up only")
      ->capture_default_str();
  app.add_option("--rebalance-threshold", options.rebalance_threshold,
                 "Largest particle count over the mean that is tolerated before a re-balance "
                 "(at least 1)")
      ->capture_default_str()
      ->check(CLI::Range(1.0, 1e9));
  std::string log_level = "info";
  app.add_option("--log-level", log_level, "trace, debug, info, warn, error")
      ->capture_default_str()
      ->check(CLI::IsMember({"trace", "debug", "info", "warn", "error"}));
  std::string log_file;
  app.add_option(
      "--log-file", log_file,
      "Also write rank 0's log to this file, appended (fsi-run passes DIR/fsi-client.log; a "
      "resumed run continues it; default: none)");
  bool log_all_ranks = false;
  app.add_flag("--log-all-ranks", log_all_ranks,
               "Log on every rank, rank r > 0 into FILE.rank<r> (default: off: rank 0 logs, the "
               "others report errors only)");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& error) {
    const int status = rank == 0 ? app.exit(error) : (error.get_exit_code() == 0 ? 0 : 2);
    MPI_Finalize();
    return status;
  }
  const auto colon = server.rfind(':');
  unsigned long port = 0;
  try {
    if (colon == std::string::npos) throw std::invalid_argument("no colon");
    port = std::stoul(server.substr(colon + 1));
    if (port == 0 || port > 65535) throw std::out_of_range("port");
  } catch (const std::exception&) {
    if (rank == 0) {
      std::fprintf(stderr, "fsi-client: --server '%s' is not HOST:PORT with a port 1..65535\n",
                   server.c_str());
    }
    MPI_Finalize();
    return 2;
  }
  try {
    configure_logging(rank, log_level, log_file, log_all_ranks);
  } catch (const spdlog::spdlog_ex& error) {
    std::fprintf(stderr, "fsi-client (rank %d): --log-file %s: %s\n", rank, log_file.c_str(),
                 error.what());
    MPI_Finalize();
    return 2;
  }
  options.balance = balance == "on";
  options.automatic_grid = grid == "auto";
  options.host = server.substr(0, colon);
  if (!token_file.empty()) {
    try {
      options.token = fsi::protocol::read_token_file(token_file);
    } catch (const fsi::Error& error) {
      if (rank == 0) std::fprintf(stderr, "fsi-client: error: %s\n", error.what());
      MPI_Finalize();
      return 2;
    }
  } else if (rank == 0 && !fsi::protocol::is_loopback_address(options.host) &&
             options.host != "localhost") {
    std::fprintf(stderr,
                 "fsi-client: warning: connecting to %s without --token-file: the server is not "
                 "authenticated, and this client runs the LIGGGHTS commands it sends\n",
                 server.c_str());
  }
  options.port = static_cast<std::uint16_t>(port);
  options.connect_timeout = std::chrono::milliseconds(static_cast<long>(connect_timeout * 1000));
  options.peer_timeout = std::chrono::milliseconds(static_cast<long>(peer_timeout * 1000));

  const int status = fsi::client::run_client_session(MPI_COMM_WORLD, options);
  MPI_Finalize();
  return status;
}
