// fsi-run SCENE --np N --output DIR [--overwrite] [--set KEY=EXPR ...]
// Starts fsi-server (port chosen by the OS, written to a port file) and `mpirun -np N fsi-client`
// on localhost, waits for both and exits with the server's status. A client that outlives the
// server by more than the grace period is terminated.
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>
#include <CLI/CLI.hpp>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "fsi/common/error.hpp"
#include "fsi/common/version.hpp"
#include "fsi/output/run_folder.hpp"

extern char** environ;

namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

volatile sig_atomic_t g_interrupted = 0;

void on_signal(int) {
  g_interrupted = 1;
}

// The machine's 1-minute load average (/proc/loadavg), or none where it cannot be read.
std::optional<double> load_average() {
  std::ifstream in("/proc/loadavg");
  double load = 0.0;
  if (in >> load) return load;
  return std::nullopt;
}

// MPI ranks poll while they wait for each other: on a machine whose cores other processes keep
// busy, N > 1 ranks lose most of their time (a user's 2-rank run took 20 times as long as 1 rank
// on a 2-core machine at load 1.5-7; docs/user-guide.md, "Ranks and balance"). Empty when the
// ranks fit beside the load.
std::string busy_machine_warning(double load, unsigned cores, int ranks) {
  if (ranks < 2 || cores == 0 || load + ranks <= cores + 0.5) return {};
  char text[512];
  std::snprintf(text, sizeof text,
                "fsi-run: warning: this machine is busy (load average %.1f on %u cores): %d MPI "
                "ranks that poll while they wait for each other lose most of their time to the "
                "other busy processes, and --np 1 may well be faster here (docs/user-guide.md, "
                "\"Ranks and balance\")\n",
                load, cores, ranks);
  return text;
}

pid_t spawn(const std::vector<std::string>& command) {
  std::vector<char*> argv;
  for (const std::string& word : command)
    argv.push_back(const_cast<char*>(word.c_str()));
  argv.push_back(nullptr);
  pid_t pid = 0;
  posix_spawnattr_t attributes;
  posix_spawnattr_init(&attributes);
  // Own process group: a terminal's Ctrl-C reaches us, and we stop the children in order.
  posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETPGROUP);
  posix_spawnattr_setpgroup(&attributes, 0);
  const int status = posix_spawnp(&pid, argv[0], nullptr, &attributes, argv.data(), environ);
  posix_spawnattr_destroy(&attributes);
  if (status != 0) {
    std::fprintf(stderr, "fsi-run: cannot start %s: %s\n", argv[0], std::strerror(status));
    return -1;
  }
  return pid;
}

// Exit status of a finished child, or nullopt while it runs.
std::optional<int> poll(pid_t pid) {
  int status = 0;
  const pid_t done = waitpid(pid, &status, WNOHANG);
  if (done != pid) return std::nullopt;
  if (WIFEXITED(status)) return WEXITSTATUS(status);
  if (WIFSIGNALED(status)) return 128 + WTERMSIG(status);
  return 1;
}

int wait_for(pid_t pid, std::chrono::milliseconds grace, const char* name) {
  const auto deadline = Clock::now() + grace;
  while (Clock::now() < deadline) {
    if (auto status = poll(pid)) return *status;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  std::fprintf(stderr, "fsi-run: %s still running %.0f s after the server ended; terminating it\n",
               name, std::chrono::duration<double>(grace).count());
  kill(-pid, SIGTERM);
  const auto kill_deadline = Clock::now() + std::chrono::seconds(5);
  while (Clock::now() < kill_deadline) {
    if (auto status = poll(pid)) return *status;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  kill(-pid, SIGKILL);
  int status = 0;
  waitpid(pid, &status, 0);
  return 128 + SIGKILL;
}

fs::path own_directory() {
  return fs::canonical("/proc/self/exe").parent_path();
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "Runs one coupled simulation on this machine: fsi-server on an OS-chosen loopback "
      "port and `mpirun -np N fsi-client` connected to it. Exits with the server's "
      "status. Check a scene first with `fsi-server SCENE --check` (its particle count, step "
      "and rules of thumb); a structure-only scene runs with `fsi-server SCENE --mbd-only "
      "--output DIR`. What a run costs and how to trade speed for accuracy (particle spacing, "
      "step, speed of sound, ranks, fsi-study): docs/user-guide.md, \"Speed and accuracy\", "
      "and the measured costs in docs/performance.md."};
  app.set_version_flag("--version", fsi::version_text());
  std::string scene;
  int ranks = 1;
  std::string output;
  std::vector<std::string> overrides;
  std::vector<std::string> server_arguments;
  std::vector<std::string> client_arguments;
  double client_grace = 10.0;
  std::string mpirun = "mpirun";
  app.add_option("scene", scene,
                 "Scene parameter file; required, except with --resume (then the run's own, with "
                 "its --set, from its run.json)")
      ->check(CLI::ExistingFile);
  app.add_option("--np", ranks, "Number of MPI ranks of fsi-client")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  auto* output_option = app.add_option(
      "--output", output,
      "Output folder of the run (created). A folder that holds an earlier run's results is "
      "refused, naming that run, unless --overwrite (required unless --resume)");
  std::string resume;
  app.add_option("--resume", resume,
                 "Continue the run in this folder from its newest complete checkpoint (the same "
                 "scene and --set; --np may differ); in place of --output (default: none)")
      ->excludes(output_option)
      ->check(CLI::ExistingDirectory);
  bool overwrite = false;
  app.add_flag("--overwrite", overwrite,
               "Replace the results of an earlier run in --output (its run.json, sensors.csv, "
               "energy.csv, logs, snapshots/, vtk/, plots/; other files stay; default: off)");
  app.add_option("--set", overrides,
                 "Override a scene parameter, KEY=EXPR (repeatable; default: none)");
  app.add_option("--server-arg", server_arguments,
                 "Extra argument for fsi-server (repeatable; default: none)")
      ->allow_extra_args(false);
  app.add_option("--client-arg", client_arguments,
                 "Extra argument for fsi-client (repeatable; default: none)")
      ->allow_extra_args(false);
  std::string log_level = "info";
  app.add_option("--log-level", log_level,
                 "Log level of fsi-server and fsi-client: trace, debug, info, warn, error; their "
                 "logs go to DIR/fsi-server.log and DIR/fsi-client.log (rank 0)")
      ->capture_default_str()
      ->check(CLI::IsMember({"trace", "debug", "info", "warn", "error"}));
  app.add_option("--client-grace", client_grace,
                 "Seconds the client may outlive the server before it is terminated")
      ->capture_default_str();
  app.add_option("--mpirun", mpirun,
                 "MPI launcher; one named mpirun* (Open MPI) is started with -q, which leaves out "
                 "its notices after a job that the client ended with a clear message")
      ->capture_default_str();
  std::string bind_to = "none";
  app.add_option("--bind-to", bind_to,
                 "Open MPI's --bind-to for the client's ranks (an mpirun* launcher only): none "
                 "lets the OS place them, so that runs started side by side share the cores; "
                 "core pins rank i to core i, for a machine given to one run (two runs pinned "
                 "alike share core 0 and each takes twice as long)")
      ->capture_default_str()
      ->check(CLI::IsMember({"none", "core", "socket"}));
  bool no_live = false;
  app.add_flag("--no-live", no_live,
               "fsi-server's progress as a log line every --progress-interval seconds instead of "
               "a line rewritten in place on a terminal (default: off)");
  double progress_interval = 10.0;
  app.add_option("--progress-interval", progress_interval,
                 "Seconds between fsi-server's progress lines in its log")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  std::string token_file;
  app.add_option("--token-file", token_file,
                 "Shared token file given to both fsi-server and fsi-client (--token-file): they "
                 "authenticate each other (default: none)")
      ->check(CLI::ExistingFile);
  CLI11_PARSE(app, argc, argv);
  if (scene.empty() && resume.empty()) {
    std::fprintf(stderr, "fsi-run: a scene file is required (see --help)\n");
    return 2;
  }
  if (resume.empty() && output.empty()) {
    std::fprintf(stderr, "fsi-run: --output DIR (a new run) or --resume DIR is required\n");
    return 2;
  }
  if (!resume.empty()) output = resume;

  const fs::path bin = own_directory();
  const fs::path server = bin / "fsi-server";
  const fs::path client = bin / "fsi-client";
  for (const fs::path& program : {server, client}) {
    if (!fs::exists(program)) {
      std::fprintf(stderr, "fsi-run: %s not found; build the project (scripts/build)\n",
                   program.c_str());
      return 2;
    }
  }
  // Before anything is written into the folder (the port file below): the server refuses too,
  // but only after this launcher has touched the folder.
  try {
    if (resume.empty()) fsi::output::claim_run_folder(output, overwrite);
  } catch (const fsi::Error& refused) {
    std::fprintf(stderr, "fsi-run: error: %s\n", refused.what());
    return 2;
  }
  std::error_code error;
  fs::create_directories(output, error);
  if (error) {
    std::fprintf(stderr, "fsi-run: cannot create output folder %s: %s\n", output.c_str(),
                 error.message().c_str());
    return 2;
  }
  const fs::path port_file = fs::path(output) / "server.port";
  fs::remove(port_file, error);

  struct sigaction action {};
  action.sa_handler = on_signal;
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);

  std::vector<std::string> server_command{server.string(),
                                          resume.empty() ? "--output" : "--resume",
                                          output,
                                          "--port",
                                          "0",
                                          "--port-file",
                                          port_file.string()};
  // Without a scene, a resume takes the run's own (fsi-server reads it from run.json).
  if (!scene.empty()) server_command.insert(server_command.begin() + 1, scene);
  for (const std::string& item : overrides) {
    server_command.push_back("--set");
    server_command.push_back(item);
  }
  if (!token_file.empty())
    server_command.insert(server_command.end(), {"--token-file", token_file});
  if (overwrite) server_command.push_back("--overwrite");
  server_command.insert(server_command.end(), {"--log-level", log_level});
  if (no_live) server_command.push_back("--no-live");
  if (app.count("--progress-interval") > 0) {
    server_command.insert(server_command.end(),
                          {"--progress-interval", std::to_string(progress_interval)});
  }
  server_command.insert(server_command.end(), server_arguments.begin(), server_arguments.end());
  const pid_t server_pid = spawn(server_command);
  if (server_pid < 0) return 2;

  // The server writes the port file once it listens.
  std::string port;
  const auto deadline = Clock::now() + std::chrono::seconds(60);
  while (port.empty()) {
    if (auto status = poll(server_pid)) {
      std::fprintf(stderr, "fsi-run: fsi-server ended with status %d before listening\n", *status);
      return *status;
    }
    if (g_interrupted || Clock::now() > deadline) {
      std::fprintf(stderr, "fsi-run: %s\n",
                   g_interrupted
                       ? "interrupted"
                       : "fsi-server did not listen within 60 s (no port file); giving up");
      kill(-server_pid, SIGTERM);
      wait_for(server_pid, std::chrono::seconds(5), "fsi-server");
      return 1;
    }
    std::ifstream in(port_file);
    std::string text;
    // The server writes the file atomically (rename), so any content is complete.
    if (in >> text && !text.empty()) port = text;
    if (port.empty()) std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }

  if (const std::optional<double> load = load_average()) {
    const std::string busy =
        busy_machine_warning(*load, std::thread::hardware_concurrency(), ranks);
    if (!busy.empty()) std::fputs(busy.c_str(), stderr);
  }

  std::vector<std::string> client_command{mpirun};
  // Open MPI's -q: mpirun's own notices about an aborted job ("MPI_ABORT was invoked ...") would
  // follow the clear message fsi-client and fsi-server already gave, and say less. Only for a
  // launcher named mpirun (Debian's is Open MPI's); another --mpirun gets no flag it may not know.
  if (fs::path(mpirun).filename().string().rfind("mpirun", 0) == 0) {
    client_command.push_back("-q");
    // Open MPI pins rank i of every job to core i: two runs side by side would share core 0
    // (measured: each at 0.53 of its speed alone, docs/performance.md "Cost model").
    client_command.insert(client_command.end(), {"--bind-to", bind_to});
  }
  client_command.insert(client_command.end(), {"-np", std::to_string(ranks)});
  if (geteuid() == 0) client_command.push_back("--allow-run-as-root");
  client_command.insert(
      client_command.end(),
      {"--oversubscribe", client.string(), "--server", "127.0.0.1:" + port, "--log-level",
       log_level, "--log-file", (fs::path(output) / "fsi-client.log").string()});
  if (!token_file.empty())
    client_command.insert(client_command.end(), {"--token-file", token_file});
  client_command.insert(client_command.end(), client_arguments.begin(), client_arguments.end());
  const pid_t client_pid = spawn(client_command);
  if (client_pid < 0) {
    kill(-server_pid, SIGTERM);
    wait_for(server_pid, std::chrono::seconds(10), "fsi-server");
    return 2;
  }

  std::optional<int> server_status;
  std::optional<int> client_status;
  bool forwarded = false;
  while (!server_status) {
    server_status = poll(server_pid);
    if (!client_status) client_status = poll(client_pid);
    if (g_interrupted && !forwarded) {
      std::fprintf(stderr, "fsi-run: interrupted; stopping server and client\n");
      kill(-server_pid, SIGTERM);
      kill(-client_pid, SIGTERM);
      forwarded = true;
    }
    if (!server_status) std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  if (!client_status) {
    client_status =
        wait_for(client_pid, std::chrono::milliseconds(static_cast<long>(client_grace * 1000)),
                 "fsi-client");
  }
  if (*server_status != 0) {
    std::fprintf(stderr, "fsi-run: fsi-server exited with status %d (fsi-client: %d)\n",
                 *server_status, *client_status);
  } else if (*client_status != 0) {
    std::fprintf(stderr,
                 "fsi-run: warning: fsi-client exited with status %d after a "
                 "successful server run\n",
                 *client_status);
  }
  return *server_status;
}
