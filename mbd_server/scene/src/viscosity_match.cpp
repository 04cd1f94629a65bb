#include "viscosity_match.hpp"

#include <muParser.h>

#include <cctype>
#include <cmath>
#include <map>
#include <optional>
#include <string>

#include "fsi/common/text.hpp"
#include "fsi/contact/fix_arguments.hpp"
#include "fsi/contact/script_text.hpp"
#include "fsi/scene/fluid_parameters.hpp"

namespace fsi::scene {
namespace {

constexpr std::string_view kCheck = "viscosity_match";
// Warn when the wall's friction and the fluid's viscosity are more than this factor apart.
constexpr double kFactor = 2.0;
// A t within this fraction of the moment rule's (moment_wall_friction) is that rule.
constexpr double kMomentRuleTolerance = 0.05;

std::string number(double value) {
  return significant(value, 3);
}

// A value set by the scripts, with where it was set.
struct Setting {
  double value = 0.0;
  SourceLocation location;
};

// The scripts read as fsi-client runs them: the LIGGGHTS_SPH_parameters as string variables,
// then script 1 and script 2 command by command. Keeps the numeric value of every variable it can
// evaluate (`equal` variables through muParser, ${name}, $x and v_name substituted) and the
// settings the check needs, the last one of each in force.
class ScriptReader {
 public:
  explicit ScriptReader(const LiggghtsSetup& liggghts) {
    for (const auto& [name, value] : liggghts.variables)
      variables_[name] = value;
    read(liggghts.script1_name, liggghts.script1_text);
    read(liggghts.script2_name, liggghts.script2_text);
  }

  std::optional<Setting> alpha, sound_speed, smoothing_length, pair_h;
  bool pair_has_artificial_viscosity = false;
  std::optional<SourceLocation> pair_location;
  std::vector<std::string> fix_words;  // of the last `fix ... fsi/sph`, substituted
  std::optional<SourceLocation> fix_location;
  std::string unreadable;  // the first fix fsi/sph word that could not be substituted

  std::optional<std::string> substitute(const std::string& word) const {
    return contact::substitute_variables(word, [&](const std::string& name) {
      const auto found = variables_.find(name);
      return found == variables_.end() ? std::nullopt : std::optional<std::string>(found->second);
    });
  }

  // A word (or an equal-style expression) as a number: ${name} and v_name replaced, then
  // evaluated by muParser (LIGGGHTS' + - * / ^ and parentheses read the same).
  std::optional<double> evaluate(const std::string& expression) const {
    auto text = substitute(expression);
    if (!text) return std::nullopt;
    std::string replaced;
    for (std::size_t i = 0; i < text->size(); ++i) {
      const bool starts_name =
          i == 0 ||
          !(std::isalnum(static_cast<unsigned char>((*text)[i - 1])) || (*text)[i - 1] == '_');
      if (starts_name && text->compare(i, 2, "v_") == 0) {
        std::size_t end = i + 2;
        while (end < text->size() &&
               (std::isalnum(static_cast<unsigned char>((*text)[end])) || (*text)[end] == '_'))
          ++end;
        const auto found = variables_.find(text->substr(i + 2, end - i - 2));
        if (found == variables_.end()) return std::nullopt;
        replaced += "(" + found->second + ")";
        i = end - 1;
        continue;
      }
      replaced += (*text)[i];
    }
    try {
      mu::Parser parser;
      parser.SetExpr(replaced);
      const double value = parser.Eval();
      if (!std::isfinite(value)) return std::nullopt;
      return value;
    } catch (const mu::Parser::exception_type&) {
      return std::nullopt;
    }
  }

 private:
  void read(const std::string& file, const std::string& text) {
    for (const contact::ScriptCommand& command : contact::script_commands(text)) {
      const auto& w = command.words;
      const SourceLocation at{file, command.line, 1};
      if (w[0] == "variable" && w.size() >= 4) {
        if (w[2] == "equal") {
          std::string expression;
          for (std::size_t i = 3; i < w.size(); ++i)
            expression += w[i];
          if (const auto value = evaluate(expression)) {
            variables_[w[1]] = significant(*value, 17);
          } else {
            variables_.erase(w[1]);
          }
        } else if (w[2] == "index" || w[2] == "string") {
          if (const auto value = substitute(w[3])) variables_[w[1]] = *value;
        }
      } else if (w[0] == "fix" && w.size() >= 7 && w[3] == "property/global") {
        std::optional<Setting>* target = w[4] == "artViscAlpha"   ? &alpha
                                         : w[4] == "speedOfSound" ? &sound_speed
                                         : w[4] == "sl"           ? &smoothing_length
                                                                  : nullptr;
        if (target == nullptr) continue;
        const auto value = evaluate(w[6]);
        *target = value ? std::optional<Setting>(Setting{*value, at}) : std::nullopt;
      } else if (w[0] == "fix" && w.size() >= 4 && w[3] == "fsi/sph") {
        fix_location = at;
        fix_words.clear();
        unreadable.clear();
        for (std::size_t i = 4; i < w.size(); ++i) {
          const auto word = substitute(w[i]);
          if (!word && unreadable.empty()) unreadable = w[i];
          fix_words.push_back(word.value_or(w[i]));
        }
      } else if (w[0] == "pair_style" && w.size() >= 2) {
        pair_location = at;
        pair_has_artificial_viscosity = false;
        pair_h.reset();
        if (w[1].starts_with("sph/artVisc")) {
          if (w.size() >= 4) {
            if (const auto h = evaluate(w[3])) pair_h = Setting{*h, at};
          }
          for (std::size_t i = 4; i < w.size(); ++i)
            pair_has_artificial_viscosity = pair_has_artificial_viscosity || w[i] == "artVisc";
        }
      }
    }
  }

  std::map<std::string, std::string> variables_;
};

std::optional<double> sph_number(const Scene& scene, std::string_view key) {
  const Parameter* parameter = sph_parameter(scene, key);
  if (parameter == nullptr || parameter->value.kind != ValueKind::Number ||
      !(parameter->value.number > 0.0))
    return std::nullopt;
  return parameter->value.number;
}

void skip(const Scene& scene, std::vector<Diagnostic>& diagnostics, const std::string& why) {
  diagnostics.push_back({Severity::Info, std::string(kCheck), SourceLocation{scene.file, 0, 0},
                         why + ": wall-friction against fluid-viscosity check skipped", ""});
}

}  // namespace

double wall_viscosity(const contact::ForceLaw& law, double density) {
  return law.viscous_scale * law.effective_viscous_cutoff() / density;
}

void check_viscosity_match(const Scene& scene, std::vector<Diagnostic>& diagnostics) {
  const LiggghtsSetup& liggghts = scene.liggghts;
  if (contact::script_commands(liggghts.script1_text).empty()) return;  // no fluid (--mbd-only)
  const ScriptReader scripts(liggghts);
  if (!scripts.fix_location) return skip(scene, diagnostics, "the scripts have no fix fsi/sph");
  if (!scripts.unreadable.empty())
    return skip(scene, diagnostics,
                "fix fsi/sph word '" + scripts.unreadable + "' at " + scripts.fix_location->text() +
                    " is not a known variable");
  contact::FixFsiSphArguments fix;
  try {
    fix = contact::parse_fix_fsi_sph_arguments(scripts.fix_words, scene.dimension);
  } catch (const std::invalid_argument&) {
    return skip(scene, diagnostics,
                "fix fsi/sph at " + scripts.fix_location->text() + " is refused by the fix");
  }
  if (!scripts.pair_location || !scripts.pair_has_artificial_viscosity)
    return skip(scene, diagnostics, "no 'pair_style sph/artVisc/... artVisc' in the scripts");
  if (!scripts.alpha || !scripts.sound_speed)
    return skip(scene, diagnostics,
                "no 'fix ... property/global artViscAlpha' or 'speedOfSound' with a value the "
                "check can evaluate");
  const std::optional<Setting> h =
      scripts.smoothing_length ? scripts.smoothing_length : scripts.pair_h;
  if (!h) return skip(scene, diagnostics, "no smoothing length (fix property/global sl)");
  const bool has_region = scene.parameters.child("FluidRegion") != nullptr;
  const std::optional<double> density =
      has_region ? std::optional<double>(scene.fluid.density) : sph_number(scene, "SPHdensity");
  if (!density) return skip(scene, diagnostics, "no FluidRegion and no 'SPHdensity'");

  const int dim = scene.dimension;
  const double divisor = artificial_viscosity_divisor(dim);
  const double t = fix.law.viscous_scale;
  const double range = fix.law.effective_viscous_cutoff();
  const double nu_fluid = scripts.alpha->value * scripts.sound_speed->value * h->value / divisor;
  if (!(nu_fluid > 0.0)) return;  // an inviscid fluid: nothing to match
  const double nu_wall = wall_viscosity(fix.law, *density);
  const double ratio = nu_wall / nu_fluid;
  if (ratio <= kFactor * (1.0 + 1e-9) && ratio >= (1.0 - 1e-9) / kFactor) return;
  // The moment rule for this fluid (to 5 %) is the other no-slip rule: matched, not slipping.
  if (fix.uses_true_shape &&
      std::abs(t / moment_wall_friction(*density, nu_fluid, fix.true_shape.spacing, range, dim) -
               1.0) < kMomentRuleTolerance)
    return;
  const double t_for_fluid = *density * nu_fluid / range;
  const double alpha_for_wall = nu_wall * divisor / (scripts.sound_speed->value * h->value);
  // A wall stickier than the fluid (ratio > 2) holds a fluid more viscous than the one that flows:
  // a free-surface flow stalls (issue 13: the dam break's front 29-42 % short) — a warning. A
  // wall that slips (ratio < 1/2) is a legitimate choice where alpha is numerical damping, not
  // the fluid's physics (examples/dam_break, examples/floating_box): an info that says so.
  const bool sticky = ratio > 1.0;
  diagnostics.push_back(
      {sticky ? Severity::Warning : Severity::Info, std::string(kCheck), *scripts.fix_location,
       "the wall friction t = " + number(t) +
           " N s/m^3 holds without slip a fluid of nu = t r_v / rho0 = " + number(nu_wall) +
           " m^2/s (r_v = " + number(range) + " m, rho0 = " + number(*density) +
           " kg/m^3), but the fluid's artificial viscosity alpha = " +
           number(scripts.alpha->value) + " (" + scripts.alpha->location.text() +
           ") gives nu = alpha c h / " + number(divisor) + " = " + number(nu_fluid) +
           " m^2/s (c = " + number(scripts.sound_speed->value) + " m/s, h = " + number(h->value) +
           " m): " + number(ratio) +
           "x, more than a factor 2 apart (docs/theory.md, \"Viscosity\")" +
           (sticky ? std::string(": the wall is stickier than the fluid, which slows a flow "
                                 "along it (a dam break's front stalls)")
                   : std::string(": the wall slips, fine where alpha is numerical damping "
                                 "rather than the fluid's viscosity (e.g. examples/dam_break)")) +
           (dim == 3 ? "; the wall's rule is measured in 2D" : ""),
       "set t = " + number(t_for_fluid) + " (rho0 nu / r_v) for this fluid, or alpha = " +
           number(alpha_for_wall) + " for the fluid this wall holds"});
}

}  // namespace fsi::scene
