#include "fsi/scene/physics_checks.hpp"

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <numbers>
#include <optional>

#include "fsi/common/error.hpp"
#include "fsi/common/text.hpp"
#include "fsi/contact/fix_arguments.hpp"
#include "fsi/contact/force_law.hpp"
#include "fsi/contact/script_text.hpp"
#include "fsi/scene/fluid_region.hpp"
#include "fsi/scene/rounded_corners.hpp"
#include "viscosity_match.hpp"

namespace fsi::scene {
namespace {

constexpr double kAcousticLimit = 0.25;  // thesis §6.2: dt <= 0.25 h / c
// Largest dt c / h measured stable with this code's wall force law (docs/validation.md).
constexpr double kMeasuredStableRatio = 0.125;
constexpr double kContactStepFraction = 0.1;  // dt <= sqrt(m / k_eff) / 10
constexpr double kSoundToFlowSpeed = 10.0;
constexpr double kRepulsionLow = 2.0;
constexpr double kRepulsionHigh = 20.0;
// The true-shape wall: a reference pressure below this fraction of rho0 g H is far from the
// column's pressures.
constexpr double kTrueShapeReferenceLow = 0.05;
// ... and a particle that starts closer than this fraction of d to a mesh is inside it.
constexpr double kTrueShapeStartFraction = 0.45;
constexpr double kNeighboursLow = 30.0;
constexpr double kNeighboursHigh = 100.0;
constexpr double kWallViscosityFactor = 3.0;
// A value that meets a limit exactly (the coarse tank's dt c / h = 0.125) is not beyond it.
constexpr double kTolerance = 1e-9;
// The rules of thumb are printed to three significant digits: a value beyond its limit by less
// than that (dt = 6.66667e-06 s against 0.125 h/c = 6.6666e-06 s) is not worth a warning that
// would read "above 6.67e-06 s ... use <= 6.67e-06 s".
constexpr double kRuleTolerance = 1e-3;

constexpr std::string_view kSphBlock = "LIGGGHTS_SPH_parameters";

using Point = Eigen::Vector2d;

// Three significant digits; thousands up to millions without an exponent (17500, not 1.75e+04).
std::string number(double value) {
  const double size = std::abs(value);
  if (size >= 1e3 && size < 1e7) {
    const double unit = std::pow(10.0, std::floor(std::log10(size)) - 2.0);
    char text[32];
    std::snprintf(text, sizeof text, "%.0f", std::round(value / unit) * unit);
    return text;
  }
  return significant(value, 3);
}

// A point in number()'s format (not fsi::point_text's %g: these are the checks' readable numbers).
std::string readable_point(const Point& point) {
  return "(" + number(point.x()) + ", " + number(point.y()) + ")";
}

// --- LIGGGHTS scripts as the checks read them ---------------------------------------------------

// Calls visit(words, line) for every command of a LIGGGHTS script, read as fsi-client and
// LIGGGHTS read it (fsi/contact/script_text.hpp); `line` is the command's first line (1-based).
template <class Visit>
void for_each_command(const std::string& script, Visit visit) {
  for (const contact::ScriptCommand& command : contact::script_commands(script))
    visit(command.words, command.line);
}

// A script word with LIGGGHTS' ${name} and $c replaced by the LIGGGHTS_SPH_parameters values the
// server puts in front of script 1; nullopt when it names another variable.
std::optional<std::string> substitute(const std::string& word, const LiggghtsSetup& liggghts) {
  return contact::substitute_variables(word, [&](const std::string& name) {
    for (const auto& [key, value] : liggghts.variables) {
      if (key == name) return std::optional<std::string>(value);
    }
    return std::optional<std::string>();
  });
}

std::optional<double> script_number(const std::string& word, const LiggghtsSetup& liggghts) {
  const auto text = substitute(word, liggghts);
  if (!text) return std::nullopt;
  double value = 0.0;
  const auto [end, error] = std::from_chars(text->data(), text->data() + text->size(), value);
  if (error != std::errc() || end != text->data() + text->size() || !std::isfinite(value))
    return std::nullopt;
  return value;
}

struct Quantity {
  double value = 0.0;
  SourceLocation location;
};

struct GravityInput {
  double magnitude = 0.0;
  std::optional<Eigen::Vector3d> direction;  // unit vector (2D: z = 0); unknown for |g| only
  SourceLocation location;
};

// The `fix ID group fsi/sph ...` line in force (the last one of script 1, then script 2), read by
// the contact core's own parser (the one fsi-client uses) once the LIGGGHTS_SPH_parameters values
// are substituted, so the checks judge exactly the force law the fix will evaluate.
struct FsiFixLine {
  std::vector<std::string> words;  // as the script writes them
  SourceLocation location;
  std::optional<contact::FixFsiSphArguments> arguments;  // when the line substitutes and parses
  std::string refusal;                                   // otherwise: why not
};

std::optional<FsiFixLine> fsi_fix_line(const LiggghtsSetup& liggghts, int dimension) {
  std::optional<FsiFixLine> fix;
  for (const auto* script : {&liggghts.script1_text, &liggghts.script2_text}) {
    const std::string& name =
        script == &liggghts.script1_text ? liggghts.script1_name : liggghts.script2_name;
    for_each_command(*script, [&](const std::vector<std::string>& tokens, int line) {
      if (tokens.size() < 4 || tokens[0] != "fix" || tokens[3] != "fsi/sph") return;
      fix = FsiFixLine{tokens, SourceLocation{name, line, 1}, std::nullopt, ""};
    });
  }
  if (!fix) return fix;
  std::vector<std::string> substituted;
  for (std::size_t i = 4; i < fix->words.size(); ++i) {
    const auto word = substitute(fix->words[i], liggghts);
    if (!word) {
      fix->refusal = "'" + fix->words[i] + "' is not a LIGGGHTS_SPH_parameters value";
      return fix;
    }
    substituted.push_back(*word);
  }
  try {
    fix->arguments = contact::parse_fix_fsi_sph_arguments(substituted, dimension);
  } catch (const std::invalid_argument& refused) {
    // The parser's first line says what is wrong; the usage text after it belongs to --help.
    std::string reason = refused.what();
    reason = reason.substr(0, reason.find("; usage:"));
    reason = reason.substr(0, reason.find('\n'));
    constexpr std::string_view kPrefix = "fix fsi/sph: ";
    if (reason.starts_with(kPrefix)) reason.erase(0, kPrefix.size());
    fix->refusal = reason;
  }
  return fix;
}

// The value of a required wall keyword (k, t, r0 or cutoff) in the parsed force law.
double wall_value(const contact::ForceLaw& law, std::string_view keyword) {
  if (keyword == "k") return law.repulsion_scale;
  if (keyword == "t") return law.viscous_scale;
  if (keyword == "r0") return law.equilibrium_distance;
  return law.cutoff;
}

// The inputs of one check, each from its declaration or, failing that, from the conventional
// LIGGGHTS variable; remembers why an input is missing.
class Inputs {
 public:
  explicit Inputs(const Scene& scene)
      : scene_(scene),
        root_(scene.parameters),
        fix_(fsi_fix_line(scene.liggghts, scene.dimension)) {}

  const std::optional<FsiFixLine>& fix_line() const { return fix_; }

  bool complete() const { return missing_.empty(); }
  const std::vector<std::string>& missing() const { return missing_; }
  void add_missing(std::string reason) { missing_.push_back(std::move(reason)); }

  // A positive number of LIGGGHTS_SPH_parameters.
  std::optional<Quantity> sph(std::string_view key) {
    const Parameter* parameter = find_sph(key);
    const std::string quoted = "'" + std::string(key) + "'";
    if (parameter == nullptr) {
      add_missing("no " + quoted + " in LIGGGHTS_SPH_parameters");
    } else if (parameter->value.kind != ValueKind::Number) {
      add_missing(quoted + " in LIGGGHTS_SPH_parameters is not a number");
    } else if (!(parameter->value.number > 0.0)) {
      add_missing(quoted + " in LIGGGHTS_SPH_parameters is not positive");
    } else {
      return Quantity{parameter->value.number, parameter->location};
    }
    return std::nullopt;
  }

  // A wall-force value of `fix ... fsi/sph` (keyword k, t, r0 or cutoff) as the fix will use it,
  // at its script line; without such a fix in the scripts, the conventional variable.
  std::optional<Quantity> wall(std::string_view keyword, std::string_view variable) {
    if (!fix_) return sph(variable);
    const std::vector<std::string>& words = fix_->words;
    const std::string at = fix_->location.text();
    for (std::size_t i = 4; i + 1 < words.size(); ++i) {
      if (words[i] != keyword) continue;
      const std::string& word = words[i + 1];
      // `${name}` alone: the value is a parameter of the scene; point the user there.
      if (word.size() > 3 && word.starts_with("${") && word.ends_with('}') &&
          find_sph(word.substr(2, word.size() - 3)) != nullptr)
        return sph(word.substr(2, word.size() - 3));
      if (!script_number(word, scene_.liggghts)) {
        add_missing("fix fsi/sph " + std::string(keyword) + " '" + word + "' at " + at +
                    " is not a number or a LIGGGHTS_SPH_parameters value");
      } else if (!fix_->arguments) {
        add_missing("fix fsi/sph at " + at + " is refused: " + fix_->refusal);
      } else if (const double value = wall_value(fix_->arguments->law, keyword); !(value > 0.0)) {
        add_missing("fix fsi/sph " + std::string(keyword) + " at " + at + " is not positive");
      } else {
        return Quantity{value, fix_->location};
      }
      return std::nullopt;
    }
    // The true-shape wall derives k, r0 and cutoff from `spacing` and `pressure`.
    if (fix_->arguments && fix_->arguments->uses_true_shape && keyword != "t") {
      return Quantity{wall_value(fix_->arguments->law, keyword), fix_->location};
    }
    add_missing("fix fsi/sph at " + at + " has no " + std::string(keyword));
    return std::nullopt;
  }

  Quantity time_step() const {
    return {scene_.solver.step_size, !scene_.solver.step_size_location.file.empty()
                                         ? scene_.solver.step_size_location
                                         : where("SolverOptions.Timeint.step_size")};
  }
  bool has_fluid_region() const { return root_.child("FluidRegion") != nullptr; }

  std::optional<Quantity> density() {
    if (has_fluid_region()) return Quantity{scene_.fluid.density, where("FluidRegion.density")};
    return sph("SPHdensity");
  }
  std::optional<Quantity> spacing() {
    if (has_fluid_region()) return Quantity{scene_.fluid.spacing, where("FluidRegion.spacing")};
    return sph("particlespacing");
  }
  // Per particle; 2D: per unit depth.
  std::optional<Quantity> particle_mass() {
    if (has_fluid_region()) return Quantity{scene_.fluid.mass, where("FluidRegion.density")};
    if (const Parameter* mass = find_sph("SPHparticlemass")) return sph(mass->key);
    const auto rho = density();
    const auto d = spacing();
    if (!rho || !d) return std::nullopt;
    return Quantity{rho->value * std::pow(d->value, scene_.fluid.dimension), d->location};
  }

  // The Gravity block if the scene has one, else the LIGGGHTS variable 'gravity'.
  std::optional<GravityInput> gravity() {
    if (const Block* block = root_.child("Gravity")) {
      const Parameter* acceleration = block->find("acceleration");
      if (acceleration == nullptr) return GravityInput{0.0, std::nullopt, block->location};
      const auto& components = acceleration->value.vector;
      Eigen::Vector3d g = Eigen::Vector3d::Zero();
      for (std::size_t k = 0; k < std::min<std::size_t>(3, components.size()); ++k)
        g[static_cast<Eigen::Index>(k)] = components[k];
      GravityInput input{g.norm(), std::nullopt, acceleration->location};
      if (input.magnitude > 0.0) input.direction = g / input.magnitude;
      return input;
    }
    if (const Parameter* g = find_sph("gravity"); g && g->value.kind == ValueKind::Number)
      return GravityInput{std::abs(g->value.number), std::nullopt, g->location};
    add_missing("no Gravity block and no 'gravity' in LIGGGHTS_SPH_parameters");
    return std::nullopt;
  }

  // Height of the fluid box along gravity (along y in 2D, z in 3D when only |g| is known).
  std::optional<Quantity> fluid_height(const GravityInput& gravity) {
    if (!has_fluid_region()) {
      add_missing("no FluidRegion (the height of the fluid is not known)");
      return std::nullopt;
    }
    const auto dimension = static_cast<std::size_t>(scene_.fluid.dimension);
    Eigen::Vector3d extent = Eigen::Vector3d::Zero();
    const Parameter* lower = root_.lookup("FluidRegion.lower");
    if (lower && root_.children("FluidRegion").size() == 1) {
      const auto& upper = root_.lookup("FluidRegion.upper")->value.vector;
      for (std::size_t k = 0; k < dimension; ++k)
        extent[static_cast<Eigen::Index>(k)] = upper.at(k) - lower->value.vector.at(k);
    } else {
      // A polygon or an STL surface: the extent of its particles, plus the d/2 around each.
      const auto& xyz = scene_.fluid.positions;
      for (std::size_t k = 0; k < dimension; ++k) {
        double low = xyz.at(k), high = low;
        for (std::size_t i = k; i < xyz.size(); i += dimension) {
          low = std::min(low, xyz[i]);
          high = std::max(high, xyz[i]);
        }
        extent[static_cast<Eigen::Index>(k)] = high - low + scene_.fluid.spacing;
      }
    }
    const double height = gravity.direction ? extent.cwiseAbs().dot(gravity.direction->cwiseAbs())
                                            : extent[static_cast<Eigen::Index>(dimension - 1)];
    return Quantity{height, where(root_.lookup("FluidRegion.upper") ? "FluidRegion.upper"
                                  : root_.lookup("FluidRegion.stl") ? "FluidRegion.stl"
                                                                    : "FluidRegion.points")};
  }

  SourceLocation where(std::string_view path) const {
    if (const Parameter* parameter = root_.lookup(path)) return parameter->location;
    return root_.location;
  }

 private:
  const Parameter* find_sph(std::string_view key) const { return sph_parameter(scene_, key); }

  const Scene& scene_;
  const Block& root_;
  std::optional<FsiFixLine> fix_;
  std::vector<std::string> missing_;
};

class Report {
 public:
  explicit Report(const Scene& scene) : scene_(scene) {}

  void warn(std::string_view check, SourceLocation location, std::string message, std::string fix) {
    diagnostics_.push_back({Severity::Warning, std::string(check), std::move(location),
                            std::move(message), std::move(fix)});
  }
  // What a check found worth knowing but not wrong: the advice goes into the message.
  void note(std::string_view check, SourceLocation location, std::string message) {
    diagnostics_.push_back(
        {Severity::Info, std::string(check), std::move(location), std::move(message), ""});
  }
  void skip(std::string_view check, std::string_view title, const std::vector<std::string>& why) {
    std::string reasons;
    for (const std::string& reason : why)
      reasons += (reasons.empty() ? "" : "; ") + reason;
    diagnostics_.push_back({Severity::Info, std::string(check), SourceLocation{scene_.file, 0, 0},
                            reasons + ": " + std::string(title) + " check skipped", ""});
  }
  std::vector<Diagnostic> take() { return std::move(diagnostics_); }

 private:
  const Scene& scene_;
  std::vector<Diagnostic> diagnostics_;
};

bool above(double value, double limit) {
  return value > limit * (1.0 + kRuleTolerance);
}
bool below(double value, double limit) {
  return value < limit * (1.0 - kRuleTolerance);
}

// --- 0. the structure's integrator ------------------------------------------------------------

// Radau IIA with one stage is implicit Euler: per step an oscillation of angular frequency w
// keeps 1 / sqrt(1 + (w h)^2) of its amplitude, per period T = 2 pi / w about exp(-2 pi^2 h / T)
// (to first order in h / T). Dynamics at a fixed step loses what the user came to measure.
void check_integrator_damping(const Scene& scene, Report& report) {
  const SolverSettings& solver = scene.solver;
  if (solver.family != mbd::TableauFamily::RadauIIA || solver.stages != 1 ||
      solver.method != IntegrationMethod::FixedStep || !(solver.step_size > 0.0))
    return;
  const double h = solver.step_size * solver.substeps;  // the structure's step
  const auto kept = [h](double period) {
    const double w = 2.0 * std::numbers::pi / period;
    return std::pow(1.0 + w * h * w * h, -0.5 * period / h);
  };
  std::string losses;
  // Decades from 10 s down to the shortest period the step resolves (4 steps), e.g. a
  // connecting rod's 5 ms bending mode at h = 1e-4 s.
  for (const double period : {10.0, 1.0, 0.1, 0.01, 0.001, 1e-4, 1e-5}) {
    if (period < 4.0 * h) break;
    losses += (losses.empty() ? "" : ", ") + number(100.0 * (1.0 - kept(period))) +
              " % per period of " + number(period) + " s";
  }
  report.warn("integrator_damping", solver.stages_location,
              "Radau IIA with 1 stage is implicit Euler (first order): at the structure step " +
                  number(h) + " s an oscillation loses " + losses +
                  " of its amplitude (about a factor exp(-2 pi^2 h / T) per period T), numerical "
                  "damping that is not in the model; it damps every motion, not only "
                  "oscillations: a drive spinning a flexible body works against it (a user's "
                  "spin-up of a beam at 6 rad/s, h = 0.005 s, lost 80 % of the drive's work and "
                  "its beam stayed bent by 0.1-0.5 m where it should straighten)",
              "use stages = 2 or 3 (orders 3 and 5) for dynamics; keep 1 stage only to settle "
              "quickly to a static state");
}

// An error-controlled method (IDA, adaptive Radau) follows every mode it sees, an undamped
// beam's highest (its elements' bending, kHz) among them: its steps stay tiny whatever its
// tolerance (docs/theory.md, "SUNDIALS IDA with a beam"; a user's spin-up of a beam: IDA took
// 2 295 658 steps and 284 s at the defaults, 13 % fewer at a 100 times looser tolerance, where
// the fixed step took 1 500 steps and 5 s).
void check_error_controlled_beams(const Scene& scene, Report& report) {
  const SolverSettings& solver = scene.solver;
  if (solver.method == IntegrationMethod::FixedStep) return;
  const mbd::Model& model = scene.model;
  std::string undamped;
  for (mbd::BodyId body = 0; body < model.body_count(); ++body) {
    const bool beam = model.is_beam(body);
    if (!beam && !model.is_cable(body)) continue;
    const double damping =
        beam ? model.beam(body).bending_damping : model.cable(body).bending_damping;
    if (damping > 0.0) continue;
    undamped += (undamped.empty() ? "'" : ", '") + model.body_name(body) + "'";
  }
  if (undamped.empty()) return;
  report.warn(
      "integration_method", solver.method_location,
      std::string(solver.method == IntegrationMethod::Ida ? "SUNDIALS IDA" : "adaptive Radau") +
          " follows every mode of the undamped beam(s) " + undamped +
          ", up to their elements' highest bending modes: its steps stay tiny whatever its "
          "tolerance (a user's spin-up of a beam: IDA took 2.3 million steps and 284 s, 13 % "
          "fewer at a 100 times looser tolerance, where the fixed step took 1 500 steps and 5 s)",
      "use method = \"fixed\" (Radau IIA damps the unresolved modes), or give the beams the "
      "physical damping of those modes, bending_damping and axial_damping (docs/theory.md, "
      "\"SUNDIALS IDA with a beam\")");
}

// --- 1. time step against the acoustic limit -------------------------------------------------

void check_acoustic_time_step(const Scene& scene, Report& report) {
  Inputs in(scene);
  const Quantity dt = in.time_step();
  const auto h = in.sph("smoothinglength");
  const auto c = in.sph("cAB");
  if (!in.complete()) return report.skip("acoustic_time_step", "acoustic time-step", in.missing());
  const double ratio = dt.value * c->value / h->value;
  if (!above(ratio, kMeasuredStableRatio)) return;
  const double measured_step = kMeasuredStableRatio * h->value / c->value;
  std::string message = "time step dt = " + number(dt.value) +
                        " s gives dt c/h = " + number(ratio) + " (h = " + number(h->value) +
                        " m, c = " + number(c->value) + " m/s): ";
  if (above(ratio, kAcousticLimit)) {
    message += "above the acoustic CFL limit dt <= 0.25 h/c = " +
               number(kAcousticLimit * h->value / c->value) + " s (thesis §6.2), and ";
  } else {
    message += "within the acoustic CFL limit 0.25 h/c of thesis §6.2, but ";
  }
  message += "above 0.125 h/c = " + number(measured_step) +
             " s, the largest ratio measured stable with this code (docs/validation.md, 'Time "
             "step': the thesis-resolution static tank blew up at dt c/h = 0.163 and ran stably "
             "at 0.081 and 0.125)";
  report.warn("acoustic_time_step", dt.location, message,
              "use SolverOptions.Timeint.step_size <= " + number(measured_step) + " s");
}

// --- 2. time step against the stiffness of the wall contact ----------------------------------

// The true-shape wall holds its first layer near 0.7 d, far from the law's steep core: the
// stiffness a particle feels is that of the integrated wall force at its rest distance, -dF/dz,
// stiffest under the column's deepest pressure.
void check_true_shape_time_step(const Scene& scene, Inputs& in, Report& report) {
  constexpr std::string_view kCheck = "contact_time_step";
  const auto& arguments = *in.fix_line()->arguments;
  const Quantity dt = in.time_step();
  const auto m = in.particle_mass();
  const auto rho = in.density();
  const auto g = in.gravity();
  const auto height = g ? in.fluid_height(*g) : std::nullopt;
  if (!in.complete()) return report.skip(kCheck, "true-shape contact time-step", in.missing());
  const double d = arguments.true_shape.spacing;
  const double deepest =
      std::max(rho->value * g->magnitude * height->value, arguments.true_shape.pressure);
  const double rest = contact::rest_distance(arguments.law, deepest, d, scene.dimension);
  const double step = 1e-4 * d;
  const double stiffness = (contact::flat_wall_force(arguments.law, rest - step, scene.dimension) -
                            contact::flat_wall_force(arguments.law, rest + step, scene.dimension)) /
                           (2.0 * step);
  if (!(stiffness > 0.0)) return;
  const double time_scale = std::sqrt(m->value / stiffness);
  const double limit = kContactStepFraction * time_scale;
  if (!above(dt.value, limit)) return;
  report.warn(kCheck, dt.location,
              "time step dt = " + number(dt.value) + " s is " + number(dt.value / time_scale) +
                  " sqrt(m/k_eff), above 1/10 of the wall-contact time scale sqrt(m/k_eff) = " +
                  number(time_scale) + " s (particle mass m = " + number(m->value) +
                  " kg/m; k_eff = -dF/dz = " + number(stiffness) +
                  " N/m^2 of the true-shape wall at the first layer's rest distance " +
                  number(rest / d) + " d under the deepest pressure " + number(deepest) + " Pa)",
              "use SolverOptions.Timeint.step_size <= " + number(limit) + " s");
}

void check_contact_time_step(const Scene& scene, Report& report) {
  constexpr std::string_view kCheck = "contact_time_step";
  constexpr std::string_view kTitle = "contact time-step";
  if (scene.dimension == 3) {
    // k_eff = r_c max|df/dd| is the stiffness of a segment per unit depth; a triangle surface
    // integrates the law over an area instead, for which no estimate is derived yet.
    return report.skip(kCheck, kTitle,
                       {"a 3D scene (the contact stiffness estimate is for 2D segments only)"});
  }
  Inputs in(scene);
  if (const auto& fix = in.fix_line();
      fix && fix->arguments && fix->arguments->law.repulsion_law != contact::RepulsionLaw::Thesis) {
    in.add_missing("fix fsi/sph uses law " +
                   std::string(contact::name(fix->arguments->law.repulsion_law)) +
                   ", the estimate covers the thesis law only");
  }
  if (in.fix_line() && in.fix_line()->arguments && in.fix_line()->arguments->uses_true_shape) {
    return check_true_shape_time_step(scene, in, report);
  }
  const Quantity dt = in.time_step();
  const auto m = in.particle_mass();
  const auto k = in.wall("k", "SPH_wall_rep");
  const auto r0 = in.wall("r0", "SPH_wall_equilibriumdist");
  const auto rc = in.wall("cutoff", "SPH_wall_cutoff");
  if (r0 && rc && above(r0->value, rc->value))
    in.add_missing("SPH_wall_equilibriumdist exceeds SPH_wall_cutoff (fix fsi/sph refuses it)");
  if (!in.complete()) return report.skip(kCheck, kTitle, in.missing());
  // The law the fix evaluates (thesis eq. 4.2), steepest at contact. Over a wall piece of length
  // rc (2D) it gives the stiffness k_eff = rc max|f'| = k (4 rc^2 - 2 (rc - r0)^2) / (r0 (2 rc -
  // r0)), 4k for r0 = rc.
  contact::ForceLaw law;
  law.repulsion_scale = k->value;
  law.equilibrium_distance = r0->value;
  law.cutoff = rc->value;
  const double stiffness = rc->value * law.steepest_repulsion_slope();
  const double time_scale = std::sqrt(m->value / stiffness);
  const double limit = kContactStepFraction * time_scale;
  if (!above(dt.value, limit)) return;
  report.warn(
      kCheck, dt.location,
      "time step dt = " + number(dt.value) + " s is " + number(dt.value / time_scale) +
          " sqrt(m/k_eff), above 1/10 of the wall-contact time scale sqrt(m/k_eff) = " +
          number(time_scale) + " s (particle mass m = " + number(m->value) +
          " kg/m; contact stiffness k_eff = r_c max|df/dd| = k (4 r_c^2 - 2 (r_c - r0)^2) / (r0 "
          "(2 r_c - r0)) = " +
          number(stiffness) + " N/m^2 with k = " + number(k->value) +
          " N/m^2, r0 = " + number(r0->value) + " m, r_c = " + number(rc->value) +
          " m): a stiff contact needs small steps (thesis §6.2)",
      "use SolverOptions.Timeint.step_size <= " + number(limit) +
          " s, or a smaller SPH_wall_rep if the walls hold with it");
}

// --- 3. speed of sound against the expected flow speed ---------------------------------------

struct FlowSpeed {
  double value = 0.0;
  std::string source;
};

// Largest distance of a body's mesh points from its centre of mass (body coordinates).
double body_radius(const View& body) {
  double radius = 0.0;
  for (const View& mesh : body.blocks("Mesh")) {
    for (const auto& point : mesh.matrix("points"))
      radius = std::max(radius, std::hypot(point.at(0), point.at(1)));
  }
  return radius;
}

// Prescribed velocities (VelocityConstraint; angular ones times the body's radius) and the initial
// velocity of the fluid.
FlowSpeed prescribed_speed(const Scene& scene) {
  const View root(scene.parameters, scene_schema());
  FlowSpeed fastest;
  for (const View& constraint : root.blocks("VelocityConstraint")) {
    const std::string body_name = constraint.string("body");
    const std::string coordinate = constraint.string("coordinate");
    double speed = std::abs(constraint.number("velocity"));
    if (coordinate == "angle") {
      for (const View& body : root.blocks("RigidBody2D")) {
        if (body.string("name") == body_name) speed *= body_radius(body);
      }
    }
    if (speed > fastest.value) {
      fastest = {speed, "VelocityConstraint on " + body_name + "." + coordinate};
    }
  }
  for (const View& region : root.blocks("FluidRegion")) {
    double speed = 0.0;
    for (double component : region.vector("velocity"))
      speed = std::hypot(speed, component);
    if (speed > fastest.value) fastest = {speed, "initial velocity of the FluidRegion"};
  }
  return fastest;
}

void check_speed_of_sound(const Scene& scene, Report& report) {
  constexpr std::string_view kCheck = "speed_of_sound";
  constexpr std::string_view kTitle = "speed-of-sound";
  Inputs in(scene);
  const auto c = in.sph("cAB");
  if (!in.complete()) return report.skip(kCheck, kTitle, in.missing());
  FlowSpeed flow = prescribed_speed(scene);
  Inputs fall(scene);  // free fall from the top of the fluid, if gravity and a FluidRegion exist
  if (const auto g = fall.gravity()) {
    if (const auto height = fall.fluid_height(*g)) {
      const double speed = std::sqrt(2.0 * g->magnitude * height->value);
      if (speed >= flow.value) {
        flow = {speed, "free fall from the top of the fluid, sqrt(2 g H) with g = " +
                           number(g->magnitude) + " m/s^2, H = " + number(height->value) + " m"};
      }
    }
  }
  if (!(flow.value > 0.0)) {
    std::vector<std::string> why = fall.missing();
    why.push_back(
        "no gravity, no VelocityConstraint and no initial fluid velocity give a flow speed");
    return report.skip(kCheck, kTitle, why);
  }
  const double wanted = kSoundToFlowSpeed * flow.value;
  if (!below(c->value, wanted)) return;
  const double variation = (flow.value / c->value) * (flow.value / c->value);
  report.warn(
      kCheck, c->location,
      "speed of sound c = " + number(c->value) +
          " m/s is below 10x the expected flow "
          "speed U = " +
          number(flow.value) + " m/s (" + flow.source +
          "): density "
          "variations of about (U/c)^2 = " +
          number(100.0 * variation) +
          " %, more than the 1 % of c = 10 U (thesis §6.2, 'Equation of state': c about "
          "10x the expected bulk flow speed, density variations of a few percent)",
      "raise cAB to >= " + number(wanted) + " m/s (and the time step with it: dt <= 0.125 h/c)");
}

// --- 4. repulsion scale against the hydrostatic pressure -------------------------------------

// The true-shape wall (fix fsi/sph spacing/pressure) has no k to judge by the thesis' rule: it
// rests the first layer at kTrueShapeRestFraction d under its reference pressure, closer under
// more. Judge where the layer rests over the column's hydrostatic pressures instead.
void check_true_shape_wall(const Scene& scene, Inputs& in, Report& report) {
  constexpr std::string_view kCheck = "wall_repulsion";
  const auto& arguments = *in.fix_line()->arguments;
  const auto rho = in.density();
  const auto g = in.gravity();
  const auto height = g ? in.fluid_height(*g) : std::nullopt;
  if (g && !(g->magnitude > 0.0)) in.add_missing("gravity is zero (no hydrostatic pressure)");
  if (!in.complete()) return report.skip(kCheck, "true-shape wall", in.missing());
  const double d = arguments.true_shape.spacing;
  const double reference = arguments.true_shape.pressure;
  const double deepest = rho->value * g->magnitude * height->value;
  const double bottom_rest = contact::rest_distance(arguments.law, deepest, d, scene.dimension) / d;
  const double top_rest =
      contact::rest_distance(arguments.law, rho->value * g->magnitude * d, d, scene.dimension) / d;
  if (!above(reference, deepest) && !below(reference, kTrueShapeReferenceLow * deepest)) return;
  report.warn(kCheck, in.fix_line()->location,
              "the true-shape wall's reference pressure " + number(reference) + " Pa is " +
                  number(reference / deepest) + " rho0 g H (H = " + number(height->value) +
                  " m, rho0 g H = " + number(deepest) + " Pa): the first particle layer rests at " +
                  number(bottom_rest) + " d at the bottom and " + number(top_rest) +
                  " d one spacing below the free surface, instead of " +
                  number(contact::kTrueShapeRestFraction) +
                  " d where the pressure is "
                  "the reference (docs/theory.md, \"The true shape\")",
              "set the fix's pressure to the hydrostatic pressure where the forces matter most, "
              "e.g. rho0 g H / 2 = " +
                  number(0.5 * deepest) + " Pa");
}

void check_wall_repulsion(const Scene& scene, Report& report) {
  constexpr std::string_view kCheck = "wall_repulsion";
  constexpr std::string_view kTitle = "wall-repulsion";
  Inputs in(scene);
  if (in.fix_line() && in.fix_line()->arguments && in.fix_line()->arguments->uses_true_shape) {
    return check_true_shape_wall(scene, in, report);
  }
  const auto k = in.wall("k", "SPH_wall_rep");
  const auto rho = in.density();
  const auto g = in.gravity();
  const auto height = g ? in.fluid_height(*g) : std::nullopt;
  if (g && !(g->magnitude > 0.0))
    in.add_missing("gravity is zero (the rule scales k with the hydrostatic pressure)");
  if (!in.complete()) return report.skip(kCheck, kTitle, in.missing());
  const double pressure = rho->value * g->magnitude * height->value;
  const double ratio = k->value / pressure;
  const double low = kRepulsionLow * pressure;
  const double high = kRepulsionHigh * pressure;
  const bool too_soft = below(ratio, kRepulsionLow);
  if (!too_soft && !above(ratio, kRepulsionHigh)) return;
  report.warn(kCheck, k->location,
              "wall repulsion k = " + number(k->value) + " N/m^2 is " + number(ratio) +
                  " rho0 g h_max, " + (too_soft ? "below" : "above") +
                  " the thesis' 2-20 rho0 g h_max = " + number(low) + "-" + number(high) +
                  " N/m^2 (rho0 = " + number(rho->value) + " kg/m^3, g = " + number(g->magnitude) +
                  " m/s^2, fluid height h_max = " + number(height->value) + " m; thesis §6.2)" +
                  (too_soft ? ": particles may pass through the walls"
                            : ": a stiffer contact than needed, which needs smaller time steps "
                              "and disturbs the density next to the walls (thesis Fig. 6.2)"),
              "set SPH_wall_rep between " + number(low) + " and " + number(high) +
                  " N/m^2, as small as keeps the particles out of the walls");
}

// --- 5. particles per kernel support ----------------------------------------------------------

void check_kernel_neighbours(const Scene& scene, Report& report) {
  Inputs in(scene);
  const auto h = in.sph("smoothinglength");
  const auto d = in.spacing();
  if (!in.complete())
    return report.skip("kernel_neighbours", "particles-per-kernel-support", in.missing());
  const double pi = std::numbers::pi;
  const double support = 2.0 * h->value;
  const bool planar = scene.fluid.dimension == 2;
  const double count = planar ? pi * std::pow(support / d->value, 2)
                              : 4.0 / 3.0 * pi * std::pow(support / d->value, 3);
  if (!below(count, kNeighboursLow) && !above(count, kNeighboursHigh)) return;
  // The spacing that gives N particles: d = 2h (pi/N)^(1/2) in 2D, 2h (4 pi/(3 N))^(1/3) in 3D.
  auto spacing_for = [&](double particles) {
    return planar ? support * std::sqrt(pi / particles)
                  : support * std::cbrt(4.0 * pi / (3.0 * particles));
  };
  report.warn("kernel_neighbours", d->location,
              std::string(planar ? "pi (2h)^2 / d^2" : "4/3 pi (2h)^3 / d^3") + " = " +
                  number(count) + " particles lie within the kernel support radius 2h (h = " +
                  number(h->value) + " m, lattice spacing d = " + number(d->value) +
                  " m), outside the thesis' 30-100 (§3.1.2; §6.2: h = 1.6-2.6 d in 2D)",
              "choose the spacing between " + number(spacing_for(kNeighboursHigh)) + " and " +
                  number(spacing_for(kNeighboursLow)) + " m");
}

// --- 6. viscous wall scale --------------------------------------------------------------------

void check_wall_viscosity(const Scene& scene, Report& report) {
  constexpr std::string_view kCheck = "wall_viscosity";
  constexpr std::string_view kTitle = "wall-viscosity";
  Inputs in(scene);
  const auto nu = in.sph("viscosity");
  const auto rho = in.density();
  const auto h = in.sph("smoothinglength");
  if (!in.complete()) return report.skip(kCheck, kTitle, in.missing());
  // The friction's range r_v: the fix's cutoff_visc (default its cutoff), else the thesis' 2h.
  double range = 2.0 * h->value;
  std::string range_source = "2h";
  if (const auto& fix = in.fix_line(); fix && fix->arguments) {
    range = fix->arguments->law.effective_viscous_cutoff();
    range_source = "the fix's cutoff_visc";
  }
  const double suggested = nu->value * rho->value / range;
  const auto t = in.wall("t", "SPH_wall_visc");
  if (!t) {
    std::vector<std::string> why = in.missing();
    why.back() += " (no slip at the wall needs t = rho0 nu / r_v = " + number(suggested) +
                  " N s/m^3, docs/theory.md \"Viscosity\")";
    return report.skip(kCheck, kTitle, why);
  }
  const double ratio = t->value / suggested;
  if (!above(ratio, kWallViscosityFactor) && !below(ratio, 1.0 / kWallViscosityFactor)) return;
  report.warn(kCheck, t->location,
              "wall viscosity t = " + number(t->value) + " N s/m^3 is " + number(ratio) +
                  "x the no-slip value t = rho0 nu / r_v = " + number(suggested) +
                  " N s/m^3 (nu = " + number(nu->value) + " m^2/s, rho0 = " + number(rho->value) +
                  " kg/m^3, r_v = " + number(range) + " m, " + range_source +
                  "; measured, docs/theory.md \"Viscosity\"), more than a factor 3 off",
              "set SPH_wall_visc = " + number(suggested) + " (SPHdensity*viscosity/r_v)");
}

// --- 7. fluid regions overlapping a mesh ------------------------------------------------------

// The surface the fluid sees at the start, one part per body (the ground's meshes together), as
// the run builds it: rigid meshes and the beams' outlines alike (a user's water drawn through an
// elastic baffle went unseen while this read the RigidBody2D and Ground blocks only).
struct WorldMesh {
  std::string owner;  // "body 'piston'", "the ground"
  std::vector<std::pair<Point, Point>> segments;
};

std::vector<WorldMesh> world_meshes(const Scene& scene) {
  const BoundaryMesh& boundary = scene.boundary;
  std::vector<WorldMesh> meshes;
  if (boundary.dimension != 2 || boundary.segments.empty()) return meshes;
  std::vector<double> positions, velocities;
  mbd::State start;
  try {
    start = scene.model.initial_configuration();
    boundary_state(boundary, scene.model, start, positions, velocities);
  } catch (const std::exception&) {
    return meshes;  // a model that cannot start is reported by the scene itself
  }
  auto vertex = [&](std::uint32_t k) { return Point(positions[2 * k], positions[2 * k + 1]); };
  for (const BodyElements& part : elements_by_body(boundary, scene.model)) {
    WorldMesh& mesh = meshes.emplace_back();
    mesh.owner = part.body == mbd::kGround ? std::string("the ground")
                                           : "body '" + scene.model.body_name(part.body) + "'";
    for (std::size_t e = 0; e + 1 < part.elements.size(); e += 2)
      mesh.segments.emplace_back(vertex(part.elements[e]), vertex(part.elements[e + 1]));
  }
  return meshes;
}

// The region the lattice fills as a polygon (a box is one with four corners), what to call it and
// where it is given; nullopt for an STL region.
struct FluidOutline {
  Polygon region;
  std::string kind;    // "fluid box"
  std::string extent;  // " (x, y)-(x, y)" for a box
  std::string keys;    // what to move
  SourceLocation where;
};

// Every box or polygon FluidRegion's outline (an STL region has none here).
std::vector<FluidOutline> fluid_outlines(const Scene& scene) {
  const std::vector<View> regions = View(scene.parameters, scene_schema()).blocks("FluidRegion");
  std::vector<FluidOutline> outlines;
  for (std::size_t n = 0; n < regions.size(); ++n) {
    const View& region = regions[n];
    const std::string which = regions.size() > 1 ? "[" + std::to_string(n) + "]" : "";
    const std::string shape = region.string("shape");
    if (shape == "box") {
      const auto lower = region.vector("lower");
      const auto upper = region.vector("upper");
      outlines.push_back({{{{lower.at(0), lower.at(1)},
                            {upper.at(0), lower.at(1)},
                            {upper.at(0), upper.at(1)},
                            {lower.at(0), upper.at(1)}},
                           {}},
                          "fluid box",
                          " " + readable_point(Point(lower.at(0), lower.at(1))) + "-" +
                              readable_point(Point(upper.at(0), upper.at(1))),
                          "FluidRegion" + which + ".lower/upper",
                          region.location("lower")});
      continue;
    }
    if (shape != "polygon") continue;
    FluidOutline outline{{},
                         "fluid polygon",
                         which.empty() ? "" : " FluidRegion" + which,
                         "FluidRegion" + which + ".points (or a Hole's points)",
                         region.location("points")};
    std::vector<NumberMatrix> holes;
    for (const View& hole : region.blocks("Hole"))
      holes.push_back(hole.matrix("points"));
    try {
      outline.region = rounded_polygon(region.matrix("points"), holes);
    } catch (const Error&) {
      continue;  // the scene builder reported it
    }
    outlines.push_back(std::move(outline));
  }
  return outlines;
}

// With the true-shape wall the region is the water itself and may touch the meshes; its lattice
// points sit at cell centres, d/2 from the region's edge. A particle closer than that to a mesh
// starts inside the structure or in its wall.
//
// A wall the lattice's outer particles stand more than 3/4 d off (d/2 on the lattice, the rest a
// gap the edge of the region left, e.g. a wall off the cell edges) under the water's top lets the
// water fall into the gap during the settling: the surface then starts with troughs beside the
// wall (a user's flap 0.9 d off its first columns: 7-8 mm troughs 0.3 m either side, 2026-12-06).
// Only walls along the lattice's axes that the water sees: the closest particle facing the wall
// and not behind another one (a thin wall's far face), at most 3/2 d away (beyond, the wall is
// not beside this water).
constexpr double kTrueShapeGapFraction = 0.75;
constexpr double kTrueShapeBesideFraction = 1.5;

// Does the segment r-s meet the path from p to q anywhere but at its ends (touching counts)?
bool blocks_path(const Point& p, const Point& q, const Point& r, const Point& s) {
  const Point path = q - p, wall = s - r;
  const double denominator = path.x() * wall.y() - path.y() * wall.x();
  if (std::abs(denominator) <= 1e-14 * path.norm() * wall.norm()) return false;  // parallel
  const Point pr = r - p;
  const double t = (pr.x() * wall.y() - pr.y() * wall.x()) / denominator;  // along the path
  const double u = (pr.x() * path.y() - pr.y() * path.x()) / denominator;  // along the wall
  constexpr double kEnds = 1e-9;
  return t > kEnds && t < 1.0 - kEnds && u >= -kEnds && u <= 1.0 + kEnds;
}

void check_true_shape_gaps(const Scene& scene, const Inputs& in,
                           const std::vector<WorldMesh>& meshes, Report& report) {
  constexpr std::string_view kCheck = "fluid_overlap";
  const double d = scene.fluid.spacing;
  const auto& xy = scene.fluid.positions;
  const Point up = -Point(scene.gravity[0], scene.gravity[1]);
  if (!(up.norm() > 0.0) || xy.size() < 2) return;  // no gravity: nothing falls into a gap
  const Point unit_up = up.normalized();
  double top = -std::numeric_limits<double>::infinity();
  for (std::size_t p = 0; p + 1 < xy.size(); p += 2)
    top = std::max(top, Point(xy[p], xy[p + 1]).dot(unit_up));
  for (const WorldMesh& mesh : meshes) {
    double widest = 0.0;
    Point widest_at = Point::Zero(), widest_particle = Point::Zero();
    for (const auto& [a, b] : mesh.segments) {
      if (std::min(a.dot(unit_up), b.dot(unit_up)) >= top) continue;  // above the water
      const Point ab = b - a;
      double closest = std::numeric_limits<double>::infinity();
      Point particle = Point::Zero(), foot = Point::Zero();
      // Along the lattice's rows or columns only: a slanted wall meets the lattice at every
      // distance up to d, which no drawing avoids (the close end is the check above's).
      const bool on_axis =
          std::abs(ab.x()) <= 1e-9 * ab.norm() || std::abs(ab.y()) <= 1e-9 * ab.norm();
      if (!(ab.squaredNorm() > 0.0) || !on_axis) continue;
      for (std::size_t p = 0; p + 1 < xy.size(); p += 2) {
        const Point x(xy[p], xy[p + 1]);
        // Particles facing the wall: a corner's diagonal neighbour is no gap.
        const double along = (x - a).dot(ab) / ab.squaredNorm();
        if (!(along > 0.0 && along < 1.0)) continue;
        const Point on = a + along * ab;
        const double distance = (x - on).norm();
        if (distance < closest) {
          closest = distance;
          particle = x;
          foot = on;
        }
      }
      if (!(closest > kTrueShapeGapFraction * d * (1.0 + 1e-9)) ||
          closest > kTrueShapeBesideFraction * d || closest <= widest)
        continue;
      bool behind = false;  // another wall between the particle and this one
      for (const WorldMesh& other : meshes) {
        for (const auto& [c, e] : other.segments) {
          if (&other == &mesh && c == a && e == b) continue;
          if (blocks_path(particle, foot, c, e)) behind = true;
        }
      }
      if (behind) continue;
      widest = closest;
      widest_at = foot;
      widest_particle = particle;
    }
    if (widest == 0.0) continue;
    // A note, not a warning: the water levels out during the settling, a trough of about the
    // gap's area spread along the surface (the sloshing and immersed-block examples validate
    // with gaps of 0.5 d).
    report.note(kCheck, in.where("FluidRegion.spacing"),
                "the water starts " + number(widest / d) + " d from the mesh of " + mesh.owner +
                    " at " + readable_point(widest_at) + " (the particle at " +
                    readable_point(widest_particle) +
                    "), below its top (true-shape wall: d/2 with the region's edge on the wall): "
                    "the gap of " +
                    number(widest - 0.5 * d) +
                    " m fills during the settling and the surface starts lower beside the wall "
                    "(a user's flap 0.9 d off: troughs of 0.3 d either side). To avoid it, put "
                    "the wall on a cell edge of the lattice (the region's lower corner, for a "
                    "polygon the least x and y of its points, plus whole spacings) and draw the "
                    "region's edge on it");
  }
}

// How far a point lies from the segment a-b.
double distance_to_segment(const Point& point, const Point& a, const Point& b) {
  const Point ab = b - a;
  const double along =
      ab.squaredNorm() > 0.0 ? std::clamp((point - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0) : 0.0;
  return (point - (a + along * ab)).norm();
}

// How far a point lies from a ring's edges (the ring closed).
double distance_to_ring(const std::vector<Point2>& ring, const Point& point) {
  double closest = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < ring.size(); ++i) {
    const Point2& a = ring[i];
    const Point2& b = ring[(i + 1) % ring.size()];
    closest = std::min(closest, distance_to_segment(point, Point(a[0], a[1]), Point(b[0], b[1])));
  }
  return closest;
}

// Does a fluid outline run along the segment a-b (its ends and its middle on one ring's edges)?
// Such a stretch of wall is the water's own edge: where it is slanted or curved (a rounded corner
// drawn with the same radius in the mesh and the water) the lattice meets it at every distance
// from 0 to d, and a particle close to it starts in the water, not in the structure.
bool water_follows(const std::vector<FluidOutline>& outlines, const Point& a, const Point& b,
                   double tolerance) {
  const auto on = [&](const std::vector<Point2>& ring) {
    return ring.size() > 1 && distance_to_ring(ring, a) <= tolerance &&
           distance_to_ring(ring, b) <= tolerance &&
           distance_to_ring(ring, 0.5 * (a + b)) <= tolerance;
  };
  for (const FluidOutline& outline : outlines) {
    if (on(outline.region.outer)) return true;
    for (const auto& hole : outline.region.holes) {
      if (on(hole)) return true;
    }
  }
  return false;
}

void check_true_shape_start(const Scene& scene, const Inputs& in, Report& report) {
  constexpr std::string_view kCheck = "fluid_overlap";
  const double d = scene.fluid.spacing;
  const auto& xy = scene.fluid.positions;
  const std::vector<WorldMesh> meshes = world_meshes(scene);
  check_true_shape_gaps(scene, in, meshes, report);
  const std::vector<FluidOutline> outlines = fluid_outlines(scene);
  for (const WorldMesh& mesh : meshes) {
    std::vector<bool> followed;
    for (const auto& [a, b] : mesh.segments)
      followed.push_back(water_follows(outlines, a, b, 1e-6 * d));
    double closest = std::numeric_limits<double>::infinity();
    Point closest_particle = Point::Zero();
    for (std::size_t p = 0; p + 1 < xy.size(); p += 2) {
      const Point particle(xy[p], xy[p + 1]);
      for (std::size_t s = 0; s < mesh.segments.size(); ++s) {
        if (followed[s]) continue;
        const double distance =
            distance_to_segment(particle, mesh.segments[s].first, mesh.segments[s].second);
        if (distance < closest) {
          closest = distance;
          closest_particle = particle;
        }
      }
    }
    if (!below(closest, kTrueShapeStartFraction * d)) continue;
    report.warn(kCheck, in.where("FluidRegion.spacing"),
                "a particle at " + readable_point(closest_particle) + " starts " +
                    number(closest / d) + " d from the mesh of " + mesh.owner +
                    " (true-shape wall: the lattice's cell centres lie d/2 inside the water's "
                    "outline): it starts inside the structure or its wall",
                "draw the FluidRegion (and its Hole blocks) along the water's true outline, so "
                "that it touches the meshes but does not cross them");
  }
}

void check_outline_against_meshes(const FluidOutline& outline, const std::vector<WorldMesh>& meshes,
                                  const std::optional<Quantity>& r0, Report& report) {
  constexpr std::string_view kCheck = "fluid_overlap";
  auto as_point2 = [](const Point& point) { return Point2{point.x(), point.y()}; };
  for (const WorldMesh& mesh : meshes) {
    double closest = std::numeric_limits<double>::infinity();
    std::size_t closest_segment = 0;
    for (std::size_t i = 0; i < mesh.segments.size(); ++i) {
      const auto& [a, b] = mesh.segments[i];
      const double distance = distance_to_region(outline.region, as_point2(a), as_point2(b));
      if (distance < closest) {
        closest = distance;
        closest_segment = i;
      }
    }
    if (mesh.segments.empty()) continue;
    const std::string segment = readable_point(mesh.segments[closest_segment].first) + "-" +
                                readable_point(mesh.segments[closest_segment].second);
    const std::string name = "the " + outline.kind + outline.extent;
    if (closest == 0.0) {
      report.warn(kCheck, outline.where,
                  name + " overlaps the mesh of " + mesh.owner + " (segment " + segment +
                      "): particles start on or inside the structure",
                  "move " + outline.keys + " clear of the mesh" +
                      (r0 ? ", by at least r0/2 = " + number(0.5 * r0->value) + " m" : ""));
    } else if (r0 && below(closest, 0.5 * r0->value)) {
      report.warn(kCheck, outline.where,
                  name + " comes within " + number(closest) + " m of the mesh of " + mesh.owner +
                      " (segment " + segment + "), closer than r0/2 = " + number(0.5 * r0->value) +
                      " m (r0 = SPH_wall_equilibriumdist): its outer "
                      "particles start deep in the wall repulsion (a wall keeps the fluid about h "
                      "= r0/2 away, thesis eq. 6.6 with r0 = r_c = 2h)",
                  "leave at least " + number(0.5 * r0->value) + " m between the " + outline.kind +
                      " and the mesh");
    }
  }
}

void check_fluid_overlap(const Scene& scene, Report& report) {
  constexpr std::string_view kCheck = "fluid_overlap";
  Inputs in(scene);
  if (!in.has_fluid_region()) {
    return report.skip(kCheck, "fluid-overlap",
                       {"no FluidRegion (particles made by the LIGGGHTS script)"});
  }
  if (scene.dimension == 3) {
    return report.skip(kCheck, "fluid-overlap",
                       {"a 3D scene (the fluid-to-mesh distance check is 2D only)"});
  }
  if (in.fix_line() && in.fix_line()->arguments && in.fix_line()->arguments->uses_true_shape) {
    return check_true_shape_start(scene, in, report);
  }
  const std::vector<FluidOutline> outlines = fluid_outlines(scene);
  if (outlines.empty()) return;
  const auto r0 = in.wall("r0", "SPH_wall_equilibriumdist");
  if (!r0) report.skip(kCheck, "fluid-to-mesh distance", in.missing());
  const std::vector<WorldMesh> meshes = world_meshes(scene);
  for (const FluidOutline& outline : outlines) {
    check_outline_against_meshes(outline, meshes, r0, report);
  }
}

// --- 8. the fluid's gravity against the structure's ------------------------------------------

std::string vector_text(const Eigen::Vector3d& vector) {
  return "(" + number(vector.x()) + ", " + number(vector.y()) + ", " + number(vector.z()) + ")";
}

// LIGGGHTS moves the fluid under its own `fix ... gravity`, the multibody system under the Gravity
// block: a scene that gives them different accelerations weighs a fluid the structure does not
// feel (thesis §6.3 measures the fluid weight through the structure). What counts is the gravity
// of the coupled run: the gravity fixes still defined after script 2 (a fix of the same ID
// replaces one, `unfix ID` removes it), so an equilibration may settle the fluid under another
// gravity on purpose (e.g. tilted, to start a U-tube's column displaced; examples/u_tube).
void check_gravity(const Scene& scene, Report& report) {
  constexpr std::string_view kCheck = "gravity";
  const LiggghtsSetup& liggghts = scene.liggghts;
  if (liggghts.script1_text.empty() && liggghts.script2_text.empty()) return;
  const Inputs in(scene);
  const Eigen::Vector3d structure(scene.gravity[0], scene.gravity[1], scene.gravity[2]);
  const SourceLocation block = in.where("Gravity.acceleration");
  const std::string structure_text =
      "the Gravity block gives the structure g = " + vector_text(structure) + " m/s^2";
  std::vector<std::string> unreadable;
  bool fluid_gravity = false;
  bool any_command = false;  // placeholder scripts (no fluid at all) have none
  struct FluidGravity {
    SourceLocation where;
    Eigen::Vector3d acceleration;
  };
  std::map<std::string, std::optional<FluidGravity>> active;  // by fix ID; nullopt: unreadable
  auto scan = [&](const std::string& script, const std::string& script_name) {
    for_each_command(script, [&](const std::vector<std::string>& tokens, int line) {
      any_command = true;
      if (tokens.size() >= 2 && tokens[0] == "unfix") {
        active.erase(tokens[1]);
        return;
      }
      if (tokens.size() < 4 || tokens[0] != "fix") return;
      if (tokens[3] != "gravity") {
        active.erase(tokens[1]);  // the ID now names another fix
        return;
      }
      fluid_gravity = true;
      const SourceLocation where{script_name, line, 1};
      const auto magnitude = tokens.size() > 4 ? script_number(tokens[4], liggghts) : std::nullopt;
      if (tokens.size() < 9 || tokens[5] != "vector" || !magnitude) {
        unreadable.push_back(where.text() +
                             " (only 'fix ID group gravity MAGNITUDE vector X Y Z' "
                             "with numbers or LIGGGHTS_SPH_parameters is read)");
        return;
      }
      Eigen::Vector3d direction;
      for (int k = 0; k < 3; ++k) {
        const auto component = script_number(tokens[6 + static_cast<std::size_t>(k)], liggghts);
        if (!component) {
          unreadable.push_back(where.text() + " (a direction component is not a number)");
          return;
        }
        direction[k] = *component;
      }
      if (!(direction.norm() > 0.0)) {  // LIGGGHTS refuses a zero direction itself
        active[tokens[1]] = std::nullopt;
        return;
      }
      active[tokens[1]] = FluidGravity{where, *magnitude * direction / direction.norm()};
    });
  };
  scan(liggghts.script1_text, liggghts.script1_name);
  scan(liggghts.script2_text, liggghts.script2_name);
  for (const auto& [id, gravity] : active) {
    if (!gravity) continue;
    const double size = std::max(gravity->acceleration.norm(), structure.norm());
    if ((gravity->acceleration - structure).norm() <= kTolerance * size) continue;
    report.warn(kCheck, gravity->where,
                "fix " + id + " gives the fluid g = " + vector_text(gravity->acceleration) +
                    " m/s^2 in the coupled run, but " + structure_text + " (" + block.text() +
                    "): fluid and structure must fall alike, or the structure does not carry "
                    "the fluid's weight (thesis §6.3)",
                "make Gravity.acceleration and the script's fix gravity the same vector");
  }
  if (!any_command && !in.has_fluid_region()) {
    report.skip(kCheck, "gravity",
                {"no FluidRegion and no command in the LIGGGHTS scripts (a scene without fluid, "
                 "e.g. for --mbd-only)"});
  } else if (!unreadable.empty()) {
    report.skip(kCheck, "gravity", {"cannot read the fluid's gravity at " + unreadable.front()});
  } else if (!fluid_gravity && structure.norm() > 0.0) {
    report.warn(kCheck, block,
                structure_text + ", but neither LIGGGHTS script has a 'fix ... gravity': the " +
                    "fluid does not fall",
                "add 'fix gravity all gravity " + number(structure.norm()) +
                    " vector X Y 0' to script 1, or remove the Gravity block");
  }
}

// fsi-client defines every LIGGGHTS_SPH_parameters entry as a LIGGGHTS variable, runs script 1,
// the equilibration, then script 2. LIGGGHTS stops the job at a ${name} it does not know, and
// without `fix ... fsi/sph` in script 1 the client has nothing to couple: both only showed at run
// time, after the set-up; here they are named at their script line before any run.
void check_liggghts_scripts(const Scene& scene, Report& report) {
  constexpr std::string_view kCheck = "liggghts_scripts";
  const LiggghtsSetup& liggghts = scene.liggghts;
  std::vector<std::string> defined;
  for (const auto& [name, value] : liggghts.variables)
    defined.push_back(name);
  auto is_defined = [&](const std::string& name) {
    return std::find(defined.begin(), defined.end(), name) != defined.end();
  };
  bool any_command = false;
  bool fsi_fix = false;
  std::optional<SourceLocation> unfollowed;  // include, jump: the check cannot follow them
  for (const auto& [name, text] : {std::pair{&liggghts.script1_name, &liggghts.script1_text},
                                   std::pair{&liggghts.script2_name, &liggghts.script2_text}}) {
    for (const contact::ScriptCommand& command : contact::script_commands(*text)) {
      any_command = true;
      const SourceLocation where{*name, command.line, 1};
      const std::string& verb = command.words.front();
      if (verb == "include" || verb == "jump" || verb == "label") {
        if (!unfollowed) unfollowed = where;
        continue;
      }
      if (name == &liggghts.script1_name && command.words.size() >= 4 && verb == "fix" &&
          command.words[3] == "fsi/sph")
        fsi_fix = true;
      if (unfollowed) continue;
      for (const std::string& variable : contact::referenced_variables(command.code)) {
        if (is_defined(variable)) continue;
        report.warn(kCheck, where,
                    "LIGGGHTS variable '" + variable +
                        "' is not defined when this line runs (fsi-client defines the " +
                        std::string(kSphBlock) +
                        " entries before script 1, then the scripts' own 'variable' lines in "
                        "order): LIGGGHTS would stop the run here",
                    "add '" + variable + " = ...' to " + std::string(kSphBlock) +
                        " in the scene, or a 'variable " + variable + " ...' line above this one");
        defined.push_back(variable);  // one warning per name
      }
      if (verb == "variable" && command.words.size() >= 2) defined.push_back(command.words[1]);
    }
  }
  if (!any_command) return;  // placeholder scripts of a scene without fluid (--mbd-only)
  if (unfollowed) {
    report.skip(kCheck, "LIGGGHTS script variables",
                {"the scripts use 'include', 'jump' or 'label' (" + unfollowed->text() +
                 "), which the check does not follow"});
  }
  if (!fsi_fix && !unfollowed) {
    report.warn(kCheck, SourceLocation{liggghts.script1_name, 1, 1},
                "script 1 has no 'fix ID group fsi/sph ...': the fluid would not feel the "
                "structure, and fsi-client stops after the set-up",
                "add e.g. 'fix fsi all fsi/sph t ${SPH_wall_visc} spacing ${particlespacing} "
                "pressure ${SPH_wall_pressure}' to script 1 (docs/fix_fsi_sph.md)");
  }
}
}  // namespace

std::string_view name(Severity severity) {
  return severity == Severity::Warning ? "warning" : "info";
}

// --- 10. damping zones ----------------------------------------------------------------------

// A DampingZone acts on whatever fluid is in its box: one that starts without water absorbs only
// what reaches it (a misplaced box, or a zone above the water), and one over a moving body slows
// the water that loads the body, whose fluid force is then partly the zone's. Both are judged
// where the scene starts; the kernel reaches about 2 d, so the box is widened by that.
void check_damping_zones(const Scene& scene, Report& report) {
  constexpr std::string_view kCheck = "damping_zones";
  if (scene.damping_zones.empty()) return;
  const auto dimension = static_cast<std::size_t>(scene.dimension);
  const double reach = 2.0 * scene.fluid.spacing;
  auto inside = [&](const DampingZone& zone, const double* point) {
    for (std::size_t k = 0; k < dimension; ++k) {
      if (point[k] < zone.lower[k] || point[k] > zone.upper[k]) return false;
    }
    return true;
  };
  const std::vector<WorldMesh> meshes = world_meshes(scene);  // 2D only
  for (const DampingZone& zone : scene.damping_zones) {
    const std::size_t count = scene.fluid.count();
    if (count > 0) {
      std::size_t in_zone = 0;
      for (std::size_t i = 0; i < count; ++i)
        in_zone += inside(zone, &scene.fluid.positions[i * dimension]) ? 1 : 0;
      if (in_zone == 0) {
        report.warn(kCheck, zone.location,
                    "no particle of the FluidRegions starts in this DampingZone: it absorbs only "
                    "the water that reaches it",
                    "draw the box over the water where the waves should end (a flume's far end, "
                    "from a little above the crests to the floor)");
      }
    }
    // Where a mesh first comes within reach of the zone: each segment clipped to the box grown by
    // the reach (Liang & Barsky), so a long segment crossing the box between its ends counts.
    auto reached = [&](const WorldMesh& mesh) -> std::optional<Point> {
      for (const auto& [a, b] : mesh.segments) {
        double enter = 0.0, leave = 1.0;
        for (int k = 0; k < 2 && enter <= leave; ++k) {
          const double lo = zone.lower[k] - reach, hi = zone.upper[k] + reach;
          const double delta = b[k] - a[k];
          if (delta == 0.0) {
            if (a[k] < lo || a[k] > hi) enter = 2.0;  // parallel and outside
            continue;
          }
          const double t_lo = (lo - a[k]) / delta, t_hi = (hi - a[k]) / delta;
          enter = std::max(enter, std::min(t_lo, t_hi));
          leave = std::min(leave, std::max(t_lo, t_hi));
        }
        if (enter <= leave) return Point(a + enter * (b - a));
      }
      return std::nullopt;
    };
    for (const WorldMesh& mesh : meshes) {
      if (mesh.owner == "the ground") continue;
      const std::optional<Point> where = reached(mesh);
      if (!where) continue;
      report.warn(kCheck, zone.location,
                  "this DampingZone reaches the mesh of " + mesh.owner + " (at " +
                      readable_point(*where) +
                      ", within 2 d of the box): its drag slows the water that loads the body, "
                      "whose fluid force is then partly the zone's",
                  "end the zone at least 2 d (the kernel's reach) before the body, or leave the "
                  "zone out where the body's loads are measured");
    }
  }
}

// --- 11. waves: particles per wave height ------------------------------------------------------

// SPH damps a wave as it travels, the more the fewer particles span its height: the wave-flap
// user's flume lost 27 % of the height over 0.9 wavelengths at H/d = 2.5 and 18 % at 3.75
// (docs/validation.md, "Users' unseen cases"). A note with the scene's H/d, since a structure
// down the flume then meets a smaller wave than the paddle makes.
void check_wave_resolution(const Scene& scene, Report& report) {
  constexpr std::string_view kCheck = "wave_resolution";
  if (scene.wavemakers.empty() || !(scene.fluid.spacing > 0.0)) return;
  for (const PlacedWavemaker& placed : scene.wavemakers) {
    const double per_height = placed.wave.height / scene.fluid.spacing;
    report.note(kCheck, placed.location,
                "the wave is H/d = " + number(per_height) +
                    " particle spacings high; SPH damps a travelling wave the more the fewer "
                    "spacings span it (measured: 27 % of the height lost over 0.9 wavelengths at "
                    "H/d = 2.5, 18 % at 3.75; docs/validation.md): a structure " +
                    number(placed.wave.wavelength) +
                    " m (a wavelength) down the flume meets a smaller wave than the paddle makes; "
                    "put a FreeSurfaceProbe in front of it to know the wave it meets, or refine "
                    "the spacing");
  }
}

std::string Diagnostic::text() const {
  return location.text() + ": " + std::string(name(severity)) + " (" + check + "): " + message +
         (fix.empty() ? "" : "; " + fix);
}

std::vector<Diagnostic> physics_checks(const Scene& scene) {
  Report report(scene);
  check_acoustic_time_step(scene, report);
  check_contact_time_step(scene, report);
  check_speed_of_sound(scene, report);
  check_wall_repulsion(scene, report);
  check_kernel_neighbours(scene, report);
  check_wall_viscosity(scene, report);
  check_fluid_overlap(scene, report);
  check_gravity(scene, report);
  check_liggghts_scripts(scene, report);
  check_damping_zones(scene, report);
  check_wave_resolution(scene, report);
  std::vector<Diagnostic> diagnostics = report.take();
  check_viscosity_match(scene, diagnostics);
  return diagnostics;
}

// The initial assembly gives every body the velocity its constraints need at the least change
// of kinetic energy. For a rigid body that is its motion; for a beam or cable it is a velocity
// field concentrated where the joints pull (the mass metric has no stiffness), not the body's
// rigid motion: the body starts deforming as if struck (a user's slider crank, its rod pulled at
// 22.5 m/s by the crank pin, rang at 12 mm instead of 1.6 mm).
void check_assembly_velocities(const Scene& scene, Report& report) {
  if (!scene.assembly || scene.parameters.child("Assembly") == nullptr) return;
  const View block = View(scene.parameters, scene_schema()).block("Assembly");
  for (const mbd::BodyCorrection& body : scene.assembly->bodies) {
    const bool flexible = scene.model.is_beam(body.body) || scene.model.is_cable(body.body);
    if (!flexible || !(body.largest_velocity_change > 1e-12)) continue;
    report.warn(
        "assembly_velocity", block.location(),
        std::string("the initial assembly gave ") +
            (scene.model.is_beam(body.body) ? "beam '" : "cable '") + body.name +
            "' the velocity its joints need at the least kinetic energy (a change of up to " +
            number(body.largest_velocity_change) + " in its " + body.velocity_coordinate +
            "): for a flexible body that velocity is concentrated where the joints pull, not the "
            "body's rigid motion, so it starts deforming as if struck and vibrates",
        std::string(scene.model.is_beam(body.body)
                        ? "give the beam the rigid motion its joints need (AncfBeam2D velocity "
                          "of its start and angular_velocity about it), so that the assembly "
                          "has nothing to add, or "
                        : "") +
            "start the mechanism at rest (each drive's rate 0 at t = 0) and bring the drive up "
            "smoothly, e.g. an angle driven to w over T: position = \"t < T ? w*(t - "
            "T/pi*sin(pi*t/T))/2 : w*(t - T/2)\" (docs/user-guide.md, \"Initial assembly\")");
  }
}

std::vector<Diagnostic> integrator_check(const Scene& scene) {
  Report report(scene);
  check_integrator_damping(scene, report);
  check_error_controlled_beams(scene, report);
  check_assembly_velocities(scene, report);
  return report.take();
}

std::vector<Diagnostic> end_time_check(const Scene& scene) {
  const double end_time = scene.solver.end_time;
  const double step = scene.solver.step_size;
  const double quotient = end_time / step;
  // What the session and --mbd-only do with it.
  const auto steps = static_cast<double>(scene.solver.step_count());
  if (std::abs(steps * step - end_time) <= kTolerance * end_time) return {};
  auto exact = [](double value) {
    char text[32];
    std::snprintf(text, sizeof text, "%.12g", value);
    return std::string(text);
  };
  auto steps_text = [&](double count) {
    return exact(count) + (count == 1.0 ? " step" : " steps");
  };
  const double fewer = std::floor(quotient);
  const double more = fewer + 1.0;
  const std::string end_text = exact(end_time);
  std::string fix = "use step_size = ";
  if (fewer >= 1.0) fix += end_text + "/" + exact(fewer) + " (" + steps_text(fewer) + ") or ";
  fix += end_text + "/" + exact(more) + " (" + steps_text(more) + "), or end_time = ";
  if (fewer >= 1.0) fix += exact(fewer * step) + " s (" + steps_text(fewer) + ") or ";
  fix += exact(more * step) + " s (" + steps_text(more) + ")";
  char ratio[32];
  std::snprintf(ratio, sizeof ratio, "%.2f", quotient);
  const View solver = View(scene.parameters, scene_schema()).block("SolverOptions");
  return {{Severity::Warning, "end_time", solver.location("end_time"),
           "end_time / step_size = " + end_text + " s / " + exact(step) + " s = " + ratio +
               " is not a whole number: the run takes " + steps_text(steps) +
               " and ends at t = " + exact(steps * step) + " s",
           fix}};
}

std::optional<double> speed_of_sound(const Scene& scene) {
  Inputs in(scene);
  const auto c = in.sph("cAB");
  if (!c) return std::nullopt;
  return c->value;
}

std::optional<double> smoothing_length(const Scene& scene) {
  Inputs in(scene);
  const auto h = in.sph("smoothinglength");
  if (!h) return std::nullopt;
  return h->value;
}

std::optional<double> true_shape_pressure(const Scene& scene) {
  Inputs in(scene);
  if (!in.fix_line() || !in.fix_line()->arguments || !in.fix_line()->arguments->uses_true_shape)
    return std::nullopt;
  return in.fix_line()->arguments->true_shape.pressure;
}

std::optional<double> wall_cutoff(const Scene& scene) {
  Inputs in(scene);
  if (in.fix_line() && in.fix_line()->arguments && in.fix_line()->arguments->uses_true_shape)
    return std::nullopt;
  const auto rc = in.wall("cutoff", "SPH_wall_cutoff");
  if (!rc) return std::nullopt;
  return rc->value;
}

}  // namespace fsi::scene
