// fsi-server SCENE --output DIR [--overwrite] [--port P] [--port-file F] [--listen ADDR]
//            [--set KEY=EXPR ...]
// The multibody side of the co-simulation: owns the clock and the set-up of both sides, serves
// boundary positions and velocities to fsi-client and applies the fluid forces it returns.
#include <spdlog/sinks/base_sink.h>
#include <spdlog/sinks/basic_file_sink.h>
#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>
#include <unistd.h>
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <mutex>
#include <numbers>
#include <optional>

#include "fsi/common/error.hpp"
#include "fsi/common/version.hpp"
#include "fsi/coupling/mbd_only.hpp"
#include "fsi/coupling/output.hpp"
#include "fsi/coupling/session.hpp"
#include "fsi/output/atomic_file.hpp"
#include "fsi/output/run_folder.hpp"
#include "fsi/protocol/auth.hpp"
#include "fsi/scene/physics_checks.hpp"
#include "fsi/scene/scene.hpp"

namespace {

// stderr on a terminal: log messages as usual, plus one status line kept at the bottom and
// rewritten in place ("\r", erase to the end of the line); a message clears it and redraws it
// below. No colours (the status line's escape sequences are the only ones).
class TerminalSink : public spdlog::sinks::base_sink<std::mutex> {
 public:
  // An empty status ends the line: the last status stays on the screen.
  void set_status(const std::string& status) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (status.empty()) {
      if (!status_.empty()) std::fputs("\n", stderr);
    } else {
      std::fputs("\r\033[K", stderr);
      std::fputs(status.c_str(), stderr);
    }
    status_ = status;
    std::fflush(stderr);
  }

 protected:
  void sink_it_(const spdlog::details::log_msg& message) override {
    spdlog::memory_buf_t formatted;
    formatter_->format(message, formatted);
    if (!status_.empty()) std::fputs("\r\033[K", stderr);
    std::fwrite(formatted.data(), 1, formatted.size(), stderr);
    if (!status_.empty()) std::fputs(status_.c_str(), stderr);
    std::fflush(stderr);
  }
  void flush_() override { std::fflush(stderr); }

 private:
  std::string status_;
};

// The default logger "fsi-server" writes to stderr and, once the output folder is known, to
// DIR/fsi-server.log. Progress lines go through the logger "progress": to the log file and, when
// stderr is not a terminal, to stderr; on a terminal stderr gets the live status line instead.
// Returns the terminal sink when stderr is a terminal (and live is wanted), else nullptr.
std::shared_ptr<TerminalSink> configure_logging(const std::string& level,
                                                const std::string& log_file, bool live,
                                                bool append = false) {
  std::shared_ptr<TerminalSink> terminal;
  spdlog::sink_ptr console;
  if (live && isatty(STDERR_FILENO)) {
    terminal = std::make_shared<TerminalSink>();
    console = terminal;
  } else {
    console = std::make_shared<spdlog::sinks::stderr_color_sink_mt>();
  }
  std::vector<spdlog::sink_ptr> sinks{console};
  std::vector<spdlog::sink_ptr> progress_sinks;
  if (!terminal) progress_sinks.push_back(console);
  if (!log_file.empty()) {
    sinks.push_back(std::make_shared<spdlog::sinks::basic_file_sink_mt>(log_file, !append));
    progress_sinks.push_back(sinks.back());
  }
  auto logger = std::make_shared<spdlog::logger>("fsi-server", sinks.begin(), sinks.end());
  auto progress =
      std::make_shared<spdlog::logger>("progress", progress_sinks.begin(), progress_sinks.end());
  for (const auto& each : {logger, progress}) {
    each->set_pattern("[%H:%M:%S.%e] [fsi-server] [%l] %v");
    each->set_level(spdlog::level::from_str(level));
    // A line reaches fsi-server.log (and fsi-run, which shows it) when it is written, not when
    // the file's buffer fills: a log that stops mid-line for minutes reads as a hung run.
    each->flush_on(spdlog::level::info);
  }
  spdlog::drop_all();
  spdlog::set_default_logger(logger);
  spdlog::register_logger(progress);
  return terminal;
}

// The Fluid block's values, one line each with its rule and inputs (docs/user-guide.md, "The
// Fluid block"); empty without the block.
std::vector<std::string> fluid_block_lines(const fsi::scene::Scene& scene) {
  if (!scene.fluid_parameters) return {};
  const fsi::scene::FluidDerivation& fluid = *scene.fluid_parameters;
  std::vector<std::string> lines = {
      "Fluid block: each value, its rule and inputs (a value set in the block wins over its "
      "rule; docs/user-guide.md, \"The Fluid block\"):"};
  for (const fsi::scene::FluidValue& value : fluid.values)
    lines.push_back("  " + fsi::scene::explain(fluid, value));
  lines.push_back("  " + fsi::scene::explain_time_step(fluid, scene.solver.step_size,
                                                       scene.solver.step_size_derived,
                                                       scene.solver.end_time));
  return lines;
}

void print_summary(const fsi::scene::Scene& scene, bool mbd_only) {
  std::printf("scene %s is valid:\n", scene.file.c_str());
  std::printf("  %d bodies, %d constraints, %zu sensors\n", scene.model.body_count(),
              scene.model.constraint_count(), scene.sensors.size());
  const bool spatial = scene.dimension == 3;
  std::printf("  dimension %d\n", scene.dimension);
  // An --mbd-only run has no fluid and no coupling: its summary leaves them out.
  if (mbd_only) {
    std::printf("  boundary mesh: %zu vertices, %zu %s (for the VTK output)\n",
                scene.boundary.vertex_count, scene.boundary.element_count(),
                spatial ? "triangles" : "segments");
    std::printf("  time: %g s in steps of %g s (%s)\n", scene.solver.end_time,
                scene.solver.step_size, scene.solver.integrator_description().c_str());
    if (scene.solver.step_size_derived)
      std::printf(
          "  the step is the coupled run's: SolverOptions.Timeint.step_size is left out "
          "and the Fluid block's rule derives it (docs/user-guide.md, \"The Fluid "
          "block\"); write step_size to choose another\n");
  } else {
    std::printf("  boundary mesh: %zu vertices (%zu dynamic), %zu %s, refinement resolution %g m\n",
                scene.boundary.vertex_count, scene.boundary.dynamic_vertex_count,
                scene.boundary.element_count(), spatial ? "triangles" : "segments",
                scene.boundary.refinement_resolution);
    std::printf("  fluid: %zu particles, spacing %g m, mass %g %s, density %g kg/m^3\n",
                scene.fluid.count(), scene.fluid.spacing, scene.fluid.mass, spatial ? "kg" : "kg/m",
                scene.fluid.density);
    const std::string fill = fsi::scene::fluid_box_fill(scene);
    if (!fill.empty()) std::printf("    %s\n", fill.c_str());
    // The settling is counted in steps: a smaller step (a larger c) settles for less time.
    std::printf("  time: %g s in steps of %g s (%s); %llu equilibration steps = %g s of settling\n",
                scene.solver.end_time, scene.solver.step_size,
                scene.solver.integrator_description().c_str(),
                static_cast<unsigned long long>(scene.liggghts.equilibration_steps),
                static_cast<double>(scene.liggghts.equilibration_steps) * scene.solver.step_size);
    for (const fsi::scene::DampingZone& zone : scene.damping_zones) {
      static constexpr const char* kSides[] = {"x", "y", "z"};
      const std::string grows = zone.axis < 0 ? std::string("uniform")
                                              : std::string("growing toward ") +
                                                    (zone.toward_upper ? "upper " : "lower ") +
                                                    kSides[zone.axis];
      std::string box;
      for (const auto* corner : {&zone.lower, &zone.upper}) {
        box += box.empty() ? "(" : " to (";
        for (int k = 0; k < scene.dimension; ++k) {
          char value[32];
          std::snprintf(value, sizeof value, "%s%g", k ? ", " : "",
                        (*corner)[static_cast<std::size_t>(k)]);
          box += value;
        }
        box += ")";
      }
      std::printf(
          "  damping zone (%s): %s, drag rate up to %g 1/s, %s, from the coupled run's "
          "first step\n",
          zone.location.text().c_str(), box.c_str(), zone.rate, grows.c_str());
    }
  }
  for (const fsi::scene::PlacedWavemaker& placed : scene.wavemakers) {
    const fsi::scene::PaddleWave& wave = placed.wave;
    std::string paddle = "piston wavemaker";
    if (wave.flap()) {
      char hinge[160];
      std::snprintf(hinge, sizeof hinge,
                    "flap wavemaker hinged %g m below the still surface, swinging up to %.3g deg",
                    wave.hinge_depth,
                    std::atan(wave.largest_offset / wave.hinge_depth) * 180.0 / std::numbers::pi);
      paddle = hinge;
    }
    std::printf(
        "  %s (%s): H = %g m, T = %g s in h = %g m: k = %.5g 1/m (wavelength "
        "%.4g m, kh = %.3g), stroke S = %.5g m%s (H/S = %.4g), phase speed %.4g m/s, group "
        "speed %.4g m/s, steepness H/lambda = %.3g (breaks above %.3g)\n",
        paddle.c_str(), placed.location.text().c_str(), wave.height, wave.period, wave.depth,
        wave.wavenumber, wave.wavelength, wave.wavenumber * wave.depth, wave.stroke,
        wave.flap() ? " at the surface" : "", wave.height_per_stroke, wave.phase_speed,
        wave.group_speed, wave.height / wave.wavelength, wave.breaking_height / wave.wavelength);
    if (wave.spectrum != "regular") {
      std::printf(
          "    irregular: %s spectrum (gamma %g), H and T above are H_m0 and T_p and the stroke "
          "the peak's; %zu components from %.4g to %.4g 1/s, repeating after %.4g s; the "
          "paddle's largest excursion at the surface %.4g m\n",
          wave.spectrum.c_str(), wave.peak_enhancement, wave.components.size(),
          wave.components.front().omega, wave.components.back().omega, wave.repeat_period,
          wave.largest_offset);
    }
  }
  if (scene.assembly) {
    for (const std::string& line : scene.assembly->lines())
      std::printf("  %s\n", line.c_str());
  }
  for (const std::string& line : fluid_block_lines(scene))
    std::printf("  %s\n", line.c_str());
}

std::size_t count(const std::vector<fsi::scene::Diagnostic>& diagnostics,
                  fsi::scene::Severity severity) {
  return static_cast<std::size_t>(std::count_if(
      diagnostics.begin(), diagnostics.end(),
      [&](const fsi::scene::Diagnostic& diagnostic) { return diagnostic.severity == severity; }));
}

// `above`: the run's own warnings (its step and integrator), printed before the headline; they
// count among its warnings (a user read "0 warning(s)" under an integrator_damping warning).
std::string diagnostics_headline(const fsi::scene::Scene& scene,
                                 const std::vector<fsi::scene::Diagnostic>& diagnostics,
                                 std::size_t above) {
  return "physics checks of " + scene.file +
         " (thesis §6.2 rules of thumb; docs/user-guide.md, \"Physics checks\"): " +
         std::to_string(count(diagnostics, fsi::scene::Severity::Warning) + above) + " warning(s)" +
         (above > 0 ? " (" + std::to_string(above) + " above)" : std::string()) + ", " +
         std::to_string(count(diagnostics, fsi::scene::Severity::Info)) +
         " note(s) (a check skipped, or what a check found worth knowing; each on a line below)";
}

// --check: every warning and skipped check, on stdout after the summary.
void print_diagnostics(const fsi::scene::Scene& scene,
                       const std::vector<fsi::scene::Diagnostic>& diagnostics, std::size_t above) {
  std::printf("%s\n", diagnostics_headline(scene, diagnostics, above).c_str());
  for (const fsi::scene::Diagnostic& diagnostic : diagnostics)
    std::printf("  %s\n", diagnostic.text().c_str());
}

// A run: the same at start-up in the log; warnings at warning level.
void log_diagnostics(const fsi::scene::Scene& scene,
                     const std::vector<fsi::scene::Diagnostic>& diagnostics, std::size_t above) {
  if (count(diagnostics, fsi::scene::Severity::Warning) + above > 0) {
    spdlog::warn("{}", diagnostics_headline(scene, diagnostics, above));
  } else {
    spdlog::info("{}", diagnostics_headline(scene, diagnostics, above));
  }
  for (const fsi::scene::Diagnostic& diagnostic : diagnostics) {
    if (diagnostic.severity == fsi::scene::Severity::Warning) {
      spdlog::warn("{}", diagnostic.text());
    } else {
      spdlog::info("{}", diagnostic.text());
    }
  }
}

// A coupled run advances with the fluid's step: an error-controlled method of the scene serves
// only --mbd-only runs of it, which the user should hear before the run, not find in run.json.
fsi::scene::Diagnostic coupled_step_notice(const fsi::scene::Scene& scene) {
  fsi::scene::Diagnostic notice;
  notice.severity = fsi::scene::Severity::Warning;
  notice.check = "integration_method";
  notice.location = scene.solver.method_location;
  char step[32];
  std::snprintf(step, sizeof step, "%g", scene.solver.step_size);
  notice.message = "Timeint.method chooses " + scene.solver.integrator_description() +
                   ", which applies to --mbd-only runs; this coupled run integrates with " +
                   scene.solver.integrator_description(true) + " at the coupled step " + step +
                   " s";
  notice.fix = "run with --mbd-only for the error-controlled method, or write method = \"fixed\"";
  return notice;
}

// Everything the command line says.
struct CommandLine {
  std::string scene_file;
  std::string output;
  bool overwrite = false;
  std::string resume;  // --resume DIR: the run folder to continue
  int port = 0;
  std::string port_file;
  std::string listen = "127.0.0.1";
  std::vector<std::string> overrides;
  double accept_timeout = 120.0;
  double reconnect_timeout = 0.0;
  double peer_timeout = 300.0;
  std::string token_file;
  bool allow_unauthenticated = false;
  bool check_only = false;
  bool mbd_only = false;
  bool print_params = false;
  bool help_params = false;
  std::string parameter_doc;
  double progress_interval = 10.0;
  bool no_live = false;
  std::string log_level = "info";
  std::string text;  // as typed, for run.json

  fsi::scene::SceneMode mode() const {
    return mbd_only ? fsi::scene::SceneMode::MbdOnly : fsi::scene::SceneMode::Coupled;
  }
};

void declare_run_options(CLI::App& app, CommandLine& line) {
  app.add_option("scene", line.scene_file,
                 "Scene parameter file (*.scene); required, except with --resume (then the run's "
                 "own, with its --set, from its run.json)");
  app.add_option("--output", line.output,
                 "Output folder of the run (created): sensors.csv, run.json, fsi-server.log, "
                 "snapshots/, vtk/; required for a run. A folder that holds an earlier run's "
                 "results is refused, naming that run, unless --overwrite");
  app.add_flag("--overwrite", line.overwrite,
               "Replace the results of an earlier run in --output (its run.json, sensors.csv, "
               "energy.csv, logs, snapshots/, vtk/, plots/; other files stay; default: off)");
  app.add_option(
      "--resume", line.resume,
      "Continue the run in this folder from its newest complete checkpoint "
      "(checkpoints/; Output.checkpoint_every_steps or checkpoint_every_seconds): the "
      "same scene and --set, a client started as usual (any rank count); sensors.csv "
      "and the series go on from the checkpoint. Takes the place of --output (default: none)");
  app.add_option("--set", line.overrides,
                 "Override a scene parameter, KEY=EXPR (repeatable; default: none)");
  app.add_flag("--check", line.check_only,
               "Validate the scene (all problems at once) and exit (default: off)");
  app.add_flag("--mbd-only", line.mbd_only,
               "Run the scene's multibody part alone, without fsi-client (fluid forces zero); "
               "writes sensors.csv and run.json into --output (default: off)");
  app.add_flag("--print-params", line.print_params,
               "Print the evaluated parameter tree and exit (default: off)");
  app.add_flag("--help-params", line.help_params,
               "List every scene parameter and exit (default: off)");
  app.add_option("--write-parameter-doc", line.parameter_doc,
                 "Write the parameter reference (markdown) to this file and exit (default: none)");
  app.add_option("--progress-interval", line.progress_interval,
                 "Seconds between progress lines in the log (time, percent, steps/s, ETA, fluid "
                 "health); on a terminal a live status line is updated four times a second too")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  app.add_flag("--no-live", line.no_live,
               "No live status line on a terminal, progress only as periodic log lines (default: "
               "off)");
  app.add_option("--log-level", line.log_level, "trace, debug, info, warn, error")
      ->capture_default_str()
      ->check(CLI::IsMember({"trace", "debug", "info", "warn", "error"}));
}

void declare_network_options(CLI::App& app, CommandLine& line) {
  app.add_option("--port", line.port, "TCP port to listen on (0: the system chooses)")
      ->capture_default_str()
      ->check(CLI::Range(0, 65535));
  app.add_option("--port-file", line.port_file,
                 "Write the listening port into this file once listening (default: none)");
  app.add_option("--listen", line.listen,
                 "Address to listen on (default loopback; 0.0.0.0 for all interfaces)")
      ->capture_default_str();
  app.add_option("--accept-timeout", line.accept_timeout,
                 "Seconds to wait for fsi-client to connect")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  app.add_option("--reconnect-timeout", line.reconnect_timeout,
                 "Seconds to wait for fsi-client to connect again when it dies during the coupled "
                 "steps: the run goes back to its newest checkpoint and the new client (the same "
                 "command line) continues from there (0: the run ends with the client; default 0)")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  app.add_option("--peer-timeout", line.peer_timeout,
                 "Seconds of silence from fsi-client after which the server gives up (a stopped or "
                 "hung client). A computing client sends a heartbeat every 0.5 s, so long "
                 "steps and the equilibration do not count as silence. At least 2")
      ->capture_default_str()
      ->check(CLI::Range(2.0, 1e9));
  app.add_option("--token-file", line.token_file,
                 "Shared token (a file only you can read, e.g. `openssl rand -hex 32 > FILE; chmod "
                 "600 FILE`): fsi-client must prove it holds the same token, and this server "
                 "proves it to the client (HMAC-SHA256 challenge-response; default: none)");
  app.add_flag("--allow-unauthenticated", line.allow_unauthenticated,
               "Listen on a non-loopback --listen address without --token-file (anyone who "
               "reaches the port can take the client's place; default: off)");
}

int write_parameter_doc(const std::string& path) {
  std::ofstream out(path);
  out << "# Scene parameters\n\n<!-- generated by fsi-server --write-parameter-doc; do not edit "
         "-->\n\n"
      << "Scene files use the language of thesis §5.6 (blocks, `key = expression`, references to "
         "earlier parameters, `%`/`//` comments, `include`). Blocks not listed here (e.g. "
         "`Geometry`) are your own parameter blocks, except a name within two letters of a "
         "listed block (`Flap` of `Clamp`, `Sensr` of `Sensor`): that is taken for a typo and "
         "refused with the name it resembles, so give your block another name.\n\n"
         "A scene states the language version it is written for as its first entry (comments may "
         "stand above it): `scene_language = 1`. A file for a newer version is refused before "
         "the rest is read; a scene without the line is an error that names the line to add "
         "(docs/user-guide.md, \"Scene language versions\").\n\n"
         "Units of 2D scenes are per metre of depth (kg/m, N/m, J/m; a beam's mass per length "
         "kg/m^2, its bending stiffness N m): a 2D scene is a slice 1 m deep, because the "
         "fluid's forces are. A mechanism without fluid (--mbd-only) is the same slice: give its "
         "real values as they are (a rod's rho A in kg/m, EI in N m^2, EA in N) and read the "
         "outputs as real N and J (docs/user-guide.md, \"Units of a 2D scene\").\n"
      << fsi::scene::render_markdown(fsi::scene::scene_schema());
  return out ? 0 : 1;
}

// The scene as the command line modifies it; nullopt when it has problems (logged).
std::optional<fsi::scene::Scene> load_scene(const CommandLine& line) {
  try {
    std::vector<fsi::scene::Override> parsed;
    for (const auto& item : line.overrides)
      parsed.push_back(fsi::scene::parse_override(item));
    return fsi::scene::build_scene(line.scene_file, parsed, line.mode());
  } catch (const fsi::Error& error) {
    spdlog::error("{}", error.what());
    return std::nullopt;
  }
}

// What --check prints and a run logs and records: the fluid's rules of thumb (warnings only: a
// scene may break one on purpose; an --mbd-only run builds no fluid), and what the run will do
// with the scene's method and end time.
struct SceneNotes {
  std::vector<fsi::scene::Diagnostic> diagnostics;
  std::vector<fsi::scene::Diagnostic> run_warnings;
};

SceneNotes scene_notes(const fsi::scene::Scene& scene, bool mbd_only) {
  SceneNotes notes;
  if (!mbd_only) notes.diagnostics = fsi::scene::physics_checks(scene);
  if (!mbd_only && scene.solver.method != fsi::scene::IntegrationMethod::FixedStep)
    notes.diagnostics.push_back(coupled_step_notice(scene));
  notes.run_warnings = fsi::scene::end_time_check(scene);
  for (fsi::scene::Diagnostic& warning : fsi::scene::integrator_check(scene))
    notes.run_warnings.push_back(std::move(warning));
  return notes;
}

int print_check(const fsi::scene::Scene& scene, const SceneNotes& notes, const CommandLine& line) {
  print_summary(scene, line.mbd_only);
  std::printf("%s", fsi::scene::blocks_needed(scene, line.mode()).c_str());
  for (const fsi::scene::Diagnostic& warning : notes.run_warnings)
    std::printf("  %s\n", warning.text().c_str());
  print_diagnostics(scene, notes.diagnostics, notes.run_warnings.size());
  return 0;
}

// Who may connect is decided before anything else of a run: the token, or loopback, or an
// explicit --allow-unauthenticated. False: refused (logged).
bool decide_access(const CommandLine& line, std::optional<fsi::protocol::Token>& token) {
  if (!line.token_file.empty()) {
    try {
      token = fsi::protocol::read_token_file(line.token_file);
      return true;
    } catch (const fsi::Error& error) {
      spdlog::error("{}", error.what());
      return false;
    }
  }
  if (fsi::protocol::is_loopback_address(line.listen)) return true;
  if (!line.allow_unauthenticated) {
    spdlog::error(
        "--listen {}: refusing to listen on a non-loopback address without --token-file: "
        "anyone who reaches the port could connect as fsi-client\n  how to fix: give "
        "fsi-server and fsi-client the same --token-file (docs/user-guide.md, "
        "\"Authentication\"), or add --allow-unauthenticated on a network you trust",
        line.listen);
    return false;
  }
  spdlog::warn(
      "--listen {} without --token-file (--allow-unauthenticated): ANY host that reaches the "
      "port can connect as fsi-client; use --token-file unless the network is trusted",
      line.listen);
  return true;
}

std::chrono::milliseconds milliseconds(double seconds) {
  return std::chrono::milliseconds(static_cast<long>(seconds * 1000));
}

fsi::coupling::ServerOptions server_options(const CommandLine& line, const SceneNotes& notes,
                                            const std::shared_ptr<TerminalSink>& terminal) {
  fsi::coupling::ServerOptions options;
  options.listen_address = line.listen;
  options.port = static_cast<std::uint16_t>(line.port);
  options.port_file = line.port_file;
  options.output_dir = line.output;
  options.resume = !line.resume.empty();
  options.accept_timeout = milliseconds(line.accept_timeout);
  options.reconnect_timeout = milliseconds(line.reconnect_timeout);
  options.peer_timeout = milliseconds(line.peer_timeout);
  options.progress_interval = milliseconds(line.progress_interval);
  if (terminal) {
    options.live_status = [terminal](const std::string& status) { terminal->set_status(status); };
  }
  options.command_line = line.text;
  options.overrides = line.overrides;
  for (const fsi::scene::Diagnostic& warning : notes.run_warnings)
    options.warnings.push_back(warning.text());
  for (const fsi::scene::Diagnostic& diagnostic : notes.diagnostics) {
    if (diagnostic.severity == fsi::scene::Severity::Warning)
      options.warnings.push_back(diagnostic.text());
  }
  return options;
}

// A run: the output folder and its log, then the coupled session or the structure alone.
int run(fsi::scene::Scene& scene, const CommandLine& line, const SceneNotes& notes) {
  if (line.output.empty()) {
    spdlog::error("--output is required for a run (a folder for sensors.csv, run.json, snapshots)");
    return 2;
  }
  std::optional<fsi::protocol::Token> token;
  if (!decide_access(line, token)) return 2;
  if (line.mbd_only && scene.model.coordinate_count() == 0) {
    std::fprintf(stderr,
                 "error: --mbd-only runs the multibody system, and the scene %s has no bodies "
                 "(static ground only)\n  fix: run it coupled (without --mbd-only)\n",
                 scene.file.c_str());
    return 2;
  }
  // Before anything is written: the folder must not hold another run's results (a resume
  // continues the run it holds).
  std::optional<fsi::output::EarlierRun> earlier;
  if (line.resume.empty()) {
    try {
      earlier = fsi::output::claim_run_folder(line.output, line.overwrite);
      if (earlier) fsi::output::remove_earlier_run(line.output);
    } catch (const fsi::Error& refused) {
      spdlog::error("{}", refused.what());
      return 2;
    }
  } else if (!std::filesystem::is_directory(line.output)) {
    spdlog::error(
        "--resume {}: no such run folder\n  how to fix: give --resume the --output "
        "folder of the run to continue",
        line.output);
    return 2;
  } else if (line.mbd_only) {
    spdlog::error(
        "--resume continues coupled runs; an --mbd-only run has no checkpoints\n  how "
        "to fix: run it again without --resume");
    return 2;
  }
  const std::filesystem::path log_file = std::filesystem::path(line.output) / "fsi-server.log";
  try {
    fsi::coupling::create_run_folder(line.output);
    fsi::output::check_writable(log_file, "the server's log");
  } catch (const fsi::Error& unwritable) {
    spdlog::error("{}", unwritable.what());
    return 2;
  }
  const std::shared_ptr<TerminalSink> terminal =
      configure_logging(line.log_level, log_file.string(), !line.no_live, !line.resume.empty());
  if (earlier) {
    spdlog::info("replaced the files of an earlier run in {} ({}){}", line.output,
                 earlier->summary(), earlier->has_results() ? " (--overwrite)" : "");
  }
  for (const fsi::scene::Diagnostic& warning : notes.run_warnings)
    spdlog::warn("{}", warning.text());
  for (const std::string& fluid_line : fluid_block_lines(scene))
    spdlog::info("{}", fluid_line);
  if (const std::string fill = fsi::scene::fluid_box_fill(scene); !fill.empty() && !line.mbd_only)
    spdlog::info("{}", fill);
  log_diagnostics(scene, notes.diagnostics, notes.run_warnings.size());
  if (scene.assembly) {
    for (const std::string& text : scene.assembly->lines())
      spdlog::info("{}", text);
  }
  fsi::coupling::ServerOptions options = server_options(line, notes, terminal);
  options.token = token;
  if (line.mbd_only) {
    fsi::coupling::MbdOnlyOptions mbd_options;
    mbd_options.output_dir = line.output;
    mbd_options.command_line = options.command_line;
    mbd_options.warnings = options.warnings;
    mbd_options.overrides = options.overrides;
    return fsi::coupling::run_mbd_only(scene, mbd_options);
  }
  int status = 1;
  try {
    status = fsi::coupling::run_coupled_session(scene, options);
  } catch (const fsi::Error& failure) {
    spdlog::error("{}", failure.what());
  }
  if (terminal) terminal->set_status("");
  return status;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "fsi-server: the multibody side of the FSI co-simulation. Reads a scene, waits for "
      "fsi-client (mpirun -np N fsi-client --server HOST:PORT) and runs the coupled steps."};
  app.set_version_flag("--version", fsi::version_text());
  CommandLine line;
  declare_run_options(app, line);
  declare_network_options(app, line);
  CLI11_PARSE(app, argc, argv);
  for (int i = 0; i < argc; ++i)
    line.text += (i ? " " : "") + std::string(argv[i]);
  if (!line.resume.empty()) {
    if (!line.output.empty() && std::filesystem::path(line.output).lexically_normal() !=
                                    std::filesystem::path(line.resume).lexically_normal()) {
      std::fprintf(stderr,
                   "fsi-server: --resume %s and --output %s name different folders\n  fix: give "
                   "--resume the run folder alone (it is the output folder)\n",
                   line.resume.c_str(), line.output.c_str());
      return 2;
    }
    line.output = line.resume;
    // `--resume DIR` alone: the scene and its --set as the run recorded them.
    if (line.scene_file.empty()) {
      if (!line.overrides.empty()) {
        std::fprintf(stderr,
                     "fsi-server: --set without a scene: give the scene with its --set, or "
                     "neither (--resume then takes both from %s/run.json)\n",
                     line.resume.c_str());
        return 2;
      }
      try {
        std::ifstream in(std::filesystem::path(line.resume) / "run.json");
        const nlohmann::json run = nlohmann::json::parse(in);
        line.scene_file = run.at("scene").at("file").get<std::string>();
        line.overrides = run.at("scene").at("overrides").get<std::vector<std::string>>();
      } catch (const std::exception& unreadable) {
        std::fprintf(stderr,
                     "fsi-server: --resume %s without a scene: its run.json does not name the "
                     "scene (%s)\n  fix: give the scene file and its --set as the run had them\n",
                     line.resume.c_str(), unreadable.what());
        return 2;
      }
    }
  }

  if (line.help_params) {
    std::cout << fsi::scene::render_help(fsi::scene::scene_schema());
    return 0;
  }
  if (!line.parameter_doc.empty()) return write_parameter_doc(line.parameter_doc);
  if (line.scene_file.empty()) {
    std::fprintf(stderr, "fsi-server: a scene file is required (see --help)\n");
    return 2;
  }
  configure_logging(line.log_level, "", false);
  std::optional<fsi::scene::Scene> scene = load_scene(line);
  if (!scene) return 2;
  if (line.print_params) {
    std::cout << fsi::scene::to_text(scene->parameters);
    return 0;
  }
  const SceneNotes notes = scene_notes(*scene, line.mbd_only);
  if (line.check_only) return print_check(*scene, notes, line);
  return run(*scene, line, notes);
}
