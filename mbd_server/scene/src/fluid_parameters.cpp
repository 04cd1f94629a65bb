#include "fsi/scene/fluid_parameters.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "fsi/common/error.hpp"
#include "fsi/common/text.hpp"

namespace fsi::scene {
namespace {

double at(const FluidValues& values, std::string_view symbol) {
  const auto found = values.find(symbol);
  FSI_ASSERT(found != values.end(), "fluid rule reads '" + std::string(symbol) + "' before it");
  return found->second;
}

// The kernel ratio h/d: 1.9 in 2D (every 2D example, ~45 neighbours within 2h), 1.2 in 3D
// (examples/hydrostatic_box_3d, ~58 neighbours); both inside the 30-100 of kernel_neighbours.
double kernel_ratio(int dimension) {
  return dimension == 3 ? 1.2 : 1.9;
}

std::string number(double value) {
  return significant(value, 4);
}

std::vector<FluidQuantity> make_quantities() {
  std::vector<FluidQuantity> q;
  // What every quantity has, input or rule: its names, unit and meaning.
  auto described = [](std::string_view key, std::string_view variable, std::string_view symbol,
                      std::string_view unit, std::string_view meaning, bool may_be_zero) {
    FluidQuantity quantity;
    quantity.key = key;
    quantity.variable = variable;
    quantity.symbol = symbol;
    quantity.unit = unit;
    quantity.meaning = meaning;
    quantity.may_be_zero = may_be_zero;
    return quantity;
  };
  auto input = [&](std::string_view key, std::string_view variable, std::string_view symbol,
                   std::string_view unit, std::string_view meaning,
                   std::optional<double> fallback = std::nullopt, bool may_be_zero = false) {
    FluidQuantity quantity = described(key, variable, symbol, unit, meaning, may_be_zero);
    quantity.input_default = fallback;
    q.push_back(quantity);
  };
  // A quantity with one rule, or (`rules`) with named rules to choose from, the default first.
  auto rules = [&](std::string_view key, std::string_view variable, std::string_view symbol,
                   std::string_view unit, std::string_view meaning, std::vector<FluidRule> choices,
                   bool may_be_zero = false) {
    FluidQuantity quantity = described(key, variable, symbol, unit, meaning, may_be_zero);
    quantity.rules = std::move(choices);
    q.push_back(quantity);
  };
  auto rule = [&](std::string_view key, std::string_view variable, std::string_view symbol,
                  std::string_view unit, std::string_view meaning, std::string_view text,
                  std::string_view source, std::vector<std::string_view> uses,
                  double (*derive)(const FluidValues&, int), bool may_be_zero = false) {
    rules(key, variable, symbol, unit, meaning,
          {FluidRule{"default", text, source, std::move(uses), derive}}, may_be_zero);
  };
  // Inputs.
  input("density", "SPHdensity", "rho0", "kg/m^3", "rest density of the liquid");
  input("spacing", "particlespacing", "d", "m", "particle spacing (the FluidRegion's lattice)");
  input("viscosity", "viscosity", "nu", "m^2/s", "kinematic viscosity of the liquid (water 1e-6)",
        std::nullopt, true);
  input("height", "", "H", "m",
        "height of the liquid along gravity (a tank: the water depth; a column: its height)");
  input("speed", "", "U", "m/s",
        "largest flow speed expected besides free fall (a moving wall, an inflow, a paddle)", 0.0,
        true);
  input("", "gravity", "g", "m/s^2", "the magnitude of the Gravity block's acceleration", 0.0,
        true);
  // Rules, each after the values it uses.
  rule("smoothing_length", "smoothinglength", "h", "m", "SPH smoothing length (kernel support 2h)",
       "1.9 d (3D: 1.2 d)",
       "every 2D example (~45 neighbours), examples/hydrostatic_box_3d (~58); check "
       "kernel_neighbours: 30-100",
       {"d"}, [](const FluidValues& v, int dim) { return kernel_ratio(dim) * at(v, "d"); });
  rule("box_half_thickness", "zhalf", "z_half", "m",
       "2D: half the thickness of LIGGGHTS' periodic z-range around z = 0", "h / 2",
       "every 2D example", {"h"}, [](const FluidValues& v, int) { return 0.5 * at(v, "h"); });
  rule("particle_mass", "SPHparticlemass", "m", "kg/m (3D: kg)",
       "particle mass (2D: per unit depth)", "rho0 d^2 (3D: rho0 d^3)", "the lattice's cell",
       {"rho0", "d"},
       [](const FluidValues& v, int dim) { return at(v, "rho0") * std::pow(at(v, "d"), dim); });
  rule("speed_of_sound", "cAB", "c", "m/s", "speed of sound of the Tait equation",
       "10 max(sqrt(2 g H), U)",
       "thesis §6.2 (Mach <= 0.1: density within 1 %); check speed_of_sound", {"g", "H", "U"},
       [](const FluidValues& v, int) {
         return 10.0 * std::max(std::sqrt(2.0 * at(v, "g") * at(v, "H")), at(v, "U"));
       });
  rule(
      "artificial_alpha", "artificialalpha", "alpha", "",
      "LIGGGHTS artViscAlpha of the coupled run: numerical damping (a fluid of alpha c h / 16, "
      "3D: / 20)",
      "0.02", "examples dam_break, u_tube, floating_box (docs/theory.md, \"Viscosity\")", {},
      [](const FluidValues&, int) { return 0.02; }, true);
  rule(
      "equilibration_alpha", "equilibrationalpha", "alpha_eq", "",
      "LIGGGHTS artViscAlpha during the equilibration (with the settling drag)", "0.5",
      "examples dam_break, u_tube, floating_box", {}, [](const FluidValues&, int) { return 0.5; },
      true);
  rule("wall_pressure", "SPH_wall_pressure", "p_ref", "Pa",
       "reference pressure of the true-shape wall (fix fsi/sph pressure)", "rho0 g H / 2",
       "a tank's mean hydrostatic pressure (docs/theory.md, \"The true shape\"); check "
       "wall_repulsion: 0.05-1 rho0 g H",
       {"rho0", "g", "H"},
       [](const FluidValues& v, int) { return 0.5 * at(v, "rho0") * at(v, "g") * at(v, "H"); });
  rule("wall_friction_range", "SPH_wall_cutoff_visc", "r_v", "m",
       "range of the wall friction (fix fsi/sph cutoff_visc)", "2 h",
       "thesis eq. (4.7), every example", {"h"},
       [](const FluidValues& v, int) { return 2.0 * at(v, "h"); });
  rules("wall_friction", "SPH_wall_visc", "t", "N s/m^3 (3D: N s/m^4)",
        "wall friction scale (fix fsi/sph t)",
        {FluidRule{
             "thesis",
             "rho0 nu / r_v",
             "thesis eq. (6.4) with its h read as r_v: no slip about one spacing inside "
             "the drawn walls (docs/theory.md, \"Viscosity\"); checks wall_viscosity, "
             "viscosity_match",
             {"rho0", "nu", "r_v"},
             [](const FluidValues& v, int) { return at(v, "rho0") * at(v, "nu") / at(v, "r_v"); }},
         FluidRule{"moment",
                   "6 rho0 nu d^2 / r_v^3 (3D: 20 rho0 nu d^3 / (pi r_v^4))",
                   "the wall's friction moment equals the fluid's stress: no slip within 0.2 d "
                   "of the drawn walls, for flows driven by a flux (docs/theory.md, "
                   "\"Viscosity\"; examples/cylinder)",
                   {"rho0", "nu", "d", "r_v"},
                   [](const FluidValues& v, int dim) {
                     return moment_wall_friction(at(v, "rho0"), at(v, "nu"), at(v, "d"),
                                                 at(v, "r_v"), dim);
                   }}},
        true);
  rule("wall_cutoff", "SPH_wall_cutoff", "r_c", "m",
       "range of the thesis' wall law (fix fsi/sph cutoff)", "2 h", "thesis §6.2", {"h"},
       [](const FluidValues& v, int) { return 2.0 * at(v, "h"); });
  rule("wall_equilibrium_distance", "SPH_wall_equilibriumdist", "r0", "m",
       "rest distance of the thesis' wall law (fix fsi/sph r0)", "r_c", "thesis §6.2: no adhesion",
       {"r_c"}, [](const FluidValues& v, int) { return at(v, "r_c"); });
  rule("wall_stiffness", "SPH_wall_rep", "k", "Pa",
       "repulsion scale of the thesis' wall law (fix fsi/sph k)", "10 rho0 g H",
       "thesis §6.2: 2-20 rho0 g H; check wall_repulsion", {"rho0", "g", "H"},
       [](const FluidValues& v, int) { return 10.0 * at(v, "rho0") * at(v, "g") * at(v, "H"); });
  return q;
}

}  // namespace

const std::vector<FluidQuantity>& fluid_quantities() {
  static const std::vector<FluidQuantity> quantities = make_quantities();
  return quantities;
}

const FluidQuantity& fluid_quantity(std::string_view symbol) {
  for (const FluidQuantity& quantity : fluid_quantities()) {
    if (quantity.symbol == symbol) return quantity;
  }
  FSI_ASSERT(false, "no fluid quantity '" + std::string(symbol) + "'");
  return fluid_quantities().front();
}

double FluidDerivation::value(std::string_view symbol) const {
  for (const FluidValue& v : values) {
    if (v.quantity->symbol == symbol) return v.value;
  }
  FSI_ASSERT(false, "no fluid value '" + std::string(symbol) + "'");
  return 0.0;
}

std::vector<std::pair<std::string, double>> FluidDerivation::variables() const {
  std::vector<std::pair<std::string, double>> result;
  for (const FluidValue& v : values) {
    if (!v.quantity->variable.empty())
      result.emplace_back(std::string(v.quantity->variable), v.value);
  }
  return result;
}

const FluidRule* FluidQuantity::find_rule(std::string_view name) const {
  for (const FluidRule& rule : rules) {
    if (rule.name == name) return &rule;
  }
  return nullptr;
}

namespace {

std::string rule_names(const FluidQuantity& quantity) {
  std::string names;
  for (const FluidRule& rule : quantity.rules)
    names += (names.empty() ? "\"" : ", \"") + std::string(rule.name) + "\"";
  return names;
}

// The rule a quantity is derived by: the default, or the one `choices` names for its key.
const FluidRule& chosen_rule(const FluidQuantity& quantity, const FluidRuleChoices& choices,
                             bool given) {
  const auto choice = choices.find(quantity.key);
  if (choice == choices.end()) return quantity.rules.front();
  const std::string key = quantity.rule_key();
  if (!quantity.has_choice()) {
    throw Error(std::string(quantity.key) + " has one rule, " +
                    std::string(quantity.rules[0].text) + ", and no other to choose",
                key, "remove " + key);
  }
  const FluidRule* rule = quantity.find_rule(choice->second);
  if (rule == nullptr) {
    throw Error("no rule \"" + choice->second + "\" for " + std::string(quantity.key), key,
                "choose one of " + rule_names(quantity));
  }
  if (given) {
    throw Error(std::string(quantity.key) + " is given and its rule is chosen too (\"" +
                    choice->second + "\"): one place per value",
                key,
                "remove " + key + " to keep the given value, or remove " +
                    std::string(quantity.key) + " to derive it by the rule");
  }
  return *rule;
}

}  // namespace

FluidDerivation derive_fluid(const FluidValues& given, int dimension,
                             const FluidRuleChoices& choices) {
  for (const auto& choice : choices) {
    const std::string& key = choice.first;  // not a structured binding: clang's lambdas
    const bool known = std::any_of(fluid_quantities().begin(), fluid_quantities().end(),
                                   [&](const FluidQuantity& q) { return q.key == key; });
    FSI_ASSERT(known, "a rule chosen for '" + key + "', which is no quantity's key");
  }
  FluidDerivation derivation;
  derivation.dimension = dimension;
  FluidValues in_force;
  for (const FluidQuantity& quantity : fluid_quantities()) {
    const std::string_view name = quantity.key.empty() ? quantity.symbol : quantity.key;
    const auto user = given.find(name);
    FluidValue value;
    value.quantity = &quantity;
    value.given = user != given.end();
    if (quantity.is_input()) {
      if (!value.given && !quantity.input_default) {
        throw Error("the Fluid block needs its input '" + std::string(name) + "' (" +
                        std::string(quantity.meaning) + ")",
                    std::string(name),
                    "add " + std::string(name) + " = ... [" + std::string(quantity.unit) +
                        "] to the Fluid block");
      }
      value.value = value.given ? user->second : *quantity.input_default;
    } else {
      value.rule = &chosen_rule(quantity, choices, value.given);
      value.by_rule = value.rule->derive(in_force, dimension);
      value.value = value.given ? user->second : *value.by_rule;
    }
    const bool valid = std::isfinite(value.value) &&
                       (quantity.may_be_zero ? value.value >= 0.0 : value.value > 0.0);
    if (!valid) {
      std::string inputs;
      for (std::string_view used : value.rule->uses)
        inputs +=
            (inputs.empty() ? "" : ", ") + std::string(used) + " = " + number(at(in_force, used));
      throw Error(
          std::string(quantity.key) + " (" + std::string(quantity.symbol) +
              ") = " + number(value.value) +
              (value.given ? std::string(" as given")
                           : " by its rule " + std::string(value.rule->text) + " with " + inputs) +
              ": it must be " + (quantity.may_be_zero ? "at least 0" : "positive"),
          std::string(name),
          value.given
              ? "give a " + std::string(quantity.may_be_zero ? "non-negative" : "positive") +
                    " value"
              : "set " + std::string(quantity.key) +
                    " = ... in the Fluid block, or change the inputs of its rule");
    }
    in_force[std::string(quantity.symbol)] = value.value;
    derivation.values.push_back(value);
  }
  return derivation;
}

namespace {

// The unit of a scene of `dimension`: "kg/m (3D: kg)" is kg/m in 2D and kg in 3D.
std::string unit_in(std::string_view unit, int dimension) {
  constexpr std::string_view kSpatial = " (3D: ";
  const std::size_t split = unit.find(kSpatial);
  if (split == std::string_view::npos || unit.back() != ')') return std::string(unit);
  if (dimension != 3) return std::string(unit.substr(0, split));
  const std::size_t start = split + kSpatial.size();
  return std::string(unit.substr(start, unit.size() - 1 - start));
}

}  // namespace

std::string explain(const FluidDerivation& derivation, const FluidValue& value) {
  const FluidQuantity& q = *value.quantity;
  const std::string unit = q.unit.empty() ? "" : " " + unit_in(q.unit, derivation.dimension);
  std::string line = std::string(q.symbol);
  if (!q.variable.empty()) line += " (${" + std::string(q.variable) + "})";
  line += " = " + number(value.value) + unit;
  if (q.is_input()) {
    if (q.key.empty()) return line + ": from the Gravity block";
    return line + (value.given ? ": given" : ": default") + " (Fluid." + std::string(q.key) + ")";
  }
  const FluidRule& rule = *value.rule;
  const std::string named = q.has_choice()
                                ? " (rule \"" + std::string(rule.name) + "\"" +
                                      (&rule == &q.rules.front() ? std::string(", the default")
                                                                 : ", Fluid." + q.rule_key()) +
                                      ")"
                                : std::string();
  if (value.given) {
    return line + ": set by Fluid." + std::string(q.key) + ", which wins over the rule " +
           std::string(rule.text) + named + " = " + number(*value.by_rule) + unit;
  }
  line += ": " + std::string(rule.text) + named;
  std::string inputs;
  for (std::string_view used : rule.uses) {
    const FluidQuantity& input = fluid_quantity(used);
    inputs += (inputs.empty() ? "" : ", ") + std::string(used) + " = " +
              number(derivation.value(used)) +
              (input.unit.empty() ? "" : " " + unit_in(input.unit, derivation.dimension));
  }
  if (!inputs.empty()) line += " with " + inputs;
  return line + " (" + std::string(rule.source) + ")";
}

std::string fluid_rules_markdown() {
  std::string table =
      "| key in `Fluid` | LIGGGHTS variable | symbol | unit | rule (when not given) | source |\n"
      "|---|---|---|---|---|---|\n";
  for (const FluidQuantity& q : fluid_quantities()) {
    auto cell = [](std::string_view text, std::string_view wrap = "") {
      return text.empty() ? std::string("—")
                          : std::string(wrap) + std::string(text) + std::string(wrap);
    };
    std::string rule, source;
    if (q.is_input()) {
      rule = q.key.empty()     ? "input: \\|g\\| of the Gravity block (0 without one)"
             : q.input_default ? "input, default " + number(*q.input_default)
                               : std::string("input, required");
      source = q.meaning;
    } else if (!q.has_choice()) {
      rule = q.rules[0].text;
      source = q.rules[0].source;
    } else {
      // Each named rule, the default first: `<key>_rule = "name"` chooses.
      for (const FluidRule& r : q.rules) {
        const bool first = &r == &q.rules.front();
        rule += std::string(first ? "" : "; ") + "`" + q.rule_key() + " = \"" +
                std::string(r.name) + "\"`" + (first ? " (default)" : "") + ": " +
                std::string(r.text);
        source +=
            std::string(first ? "" : "; ") + std::string(r.name) + ": " + std::string(r.source);
      }
    }
    table += "| " + cell(q.key, "`") + " | " +
             cell(q.variable.empty() ? "" : "${" + std::string(q.variable) + "}", "`") + " | " +
             std::string(q.symbol) + " | " + cell(q.unit) + " | " + rule + " | " + source + " |\n";
  }
  return table;
}

namespace {

// The acoustic fraction of a step the run chooses itself: below the dam break's measured
// stability limit, which lies between dt c/h = 0.092 and 0.115 (docs/validation.md, "Stability
// maps"), where a fluid at rest holds to 0.25 and the check warns above 0.125.
constexpr double kDerivedAcousticFraction = 0.09;

struct TimeStepLimits {
  double acoustic = 0.0, viscous = 0.0, force = 0.0;
  double impact = 0.0;  // kDerivedAcousticFraction h / c
  double nu_max = 0.0;
};

TimeStepLimits time_step_limits(const FluidDerivation& d) {
  TimeStepLimits limits;
  const double h = d.value("h"), c = d.value("c"), g = d.value("g");
  limits.nu_max =
      std::max(d.value("nu"), d.value("alpha") * c * h / artificial_viscosity_divisor(d.dimension));
  limits.acoustic = 0.125 * h / c;
  limits.impact = kDerivedAcousticFraction * h / c;
  limits.viscous = limits.nu_max > 0.0 ? 0.125 * h * h / limits.nu_max : HUGE_VAL;
  limits.force = g > 0.0 ? 0.25 * std::sqrt(h / g) : HUGE_VAL;
  return limits;
}

}  // namespace

double artificial_viscosity_divisor(int dimension) {
  return dimension == 3 ? 20.0 : 16.0;
}

double moment_wall_friction(double density, double viscosity, double spacing, double range,
                            int dimension) {
  const double moment =
      dimension == 3 ? std::numbers::pi * std::pow(range, 4) / 20.0 : std::pow(range, 3) / 6.0;
  return density * viscosity * std::pow(spacing, dimension) / moment;
}

double recommended_time_step(const FluidDerivation& derivation) {
  const TimeStepLimits limits = time_step_limits(derivation);
  return std::min({limits.acoustic, limits.viscous, limits.force});
}

double derived_time_step(const FluidDerivation& derivation, double end_time, int substeps) {
  if (!(end_time > 0.0) || substeps < 1) {
    throw Error("a time step is derived for end_time > 0 and substeps >= 1, not end_time = " +
                    number(end_time) + " s, substeps = " + std::to_string(substeps),
                "SolverOptions", "give SolverOptions.end_time > 0 and Timeint.substeps >= 1");
  }
  const TimeStepLimits limits = time_step_limits(derivation);
  const double structure_limit = substeps * std::min({limits.impact, limits.viscous, limits.force});
  // A relative slack so that an end_time that is already a whole multiple stays one.
  const double structure_steps = std::ceil(end_time / structure_limit * (1.0 - 1e-12));
  return end_time / (std::max(structure_steps, 1.0) * substeps);
}

std::string explain_time_step(const FluidDerivation& derivation, double scene_step, bool derived,
                              double end_time) {
  const TimeStepLimits limits = time_step_limits(derivation);
  const double dt = recommended_time_step(derivation);
  // A limit in seconds, or "none" and why (an inviscid fluid, no gravity).
  auto limit = [](double value, std::string_view why_none = "") {
    return value == HUGE_VAL ? "none (" + std::string(why_none) + ")" : number(value) + " s";
  };
  std::string line = "dt <= " + number(dt) +
                     " s: the least of 0.125 h/c = " + limit(limits.acoustic) +
                     " (acoustic, check acoustic_time_step), " +
                     "0.125 h^2/nu_max = " + limit(limits.viscous, "nu_max = 0") +
                     " (viscous, nu_max = " + number(limits.nu_max) + " m^2/s: nu or alpha c h / " +
                     number(artificial_viscosity_divisor(derivation.dimension)) +
                     "), 0.25 sqrt(h/g) = " + limit(limits.force, "g = 0") +
                     " (body force); the contact's limit is check contact_time_step";
  if (derived && scene_step > 0.0) {
    char steps[32];
    std::snprintf(steps, sizeof steps, "%.0f", end_time / scene_step);
    line += "; SolverOptions.Timeint.step_size is not given: the run steps at " +
            number(scene_step) + " s, end_time / " + steps + " (the largest step within " +
            number(kDerivedAcousticFraction) + " h/c = " + limit(limits.impact) +
            ", below the dam break's measured stable 0.092 h/c, and the other limits that "
            "divides end_time = " +
            number(end_time) + " s into whole structure steps)";
  } else if (scene_step > 0.0) {
    line += "; SolverOptions.Timeint.step_size = " + number(scene_step) + " s" +
            (scene_step <= dt * (1.0 + 1e-9) ? " (within)" : " (ABOVE it)");
  }
  return line;
}

}  // namespace fsi::scene
