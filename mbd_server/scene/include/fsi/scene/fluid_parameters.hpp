#pragma once
// The fluid's parameters from a few physical inputs (issue 13, item 4): the rules of thumb the
// examples used for the smoothing length, speed of sound, artificial viscosity, wall law and time
// step, declared once here as a table of quantities. The scene's `Fluid` block
// (src/family_fluid_parameters.cpp) declares its keys from this table, hands every value to the
// LIGGGHTS scripts under the variable name the examples' LIGGGHTS_SPH_parameters used, and
// `fsi-server --check` prints `explain` for each; docs/user-guide.md ("The Fluid block") gives
// the same table. Pure: numbers in, numbers and text out.

#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace fsi::scene {

// Values by the symbol their rules use ("rho0", "d", "h", ...).
using FluidValues = std::map<std::string, double, std::less<>>;

// One rule of a derived quantity: its name (a quantity with several is chosen in the Fluid block by
// `<key>_rule = "name"`), the formula in words, where it comes from, the symbols it reads, and the
// function itself (`dimension` 2 or 3).
struct FluidRule {
  std::string_view name;
  std::string_view text;
  std::string_view source;
  std::vector<std::string_view> uses;
  double (*derive)(const FluidValues& values, int dimension) = nullptr;
};

// One quantity of the fluid: an input (no rule) or a value derived from earlier ones by its rule.
struct FluidQuantity {
  std::string_view key;          // of the Fluid block ("" for g, which the Gravity block gives)
  std::string_view variable;     // the LIGGGHTS variable it becomes ("": none)
  std::string_view symbol;       // in the rules and in --check
  std::string_view unit;         // "" dimensionless
  std::string_view meaning;      // one line of doc
  std::vector<FluidRule> rules;  // none for an input; the first is the default
  bool may_be_zero = false;      // 0 is a valid value (an inviscid fluid, no speed)
  std::optional<double> input_default;  // inputs only: absent means required

  bool is_input() const { return rules.empty(); }
  bool has_choice() const { return rules.size() > 1; }
  // The Fluid block's key that chooses among the rules: "<key>_rule".
  std::string rule_key() const { return std::string(key) + "_rule"; }
  const FluidRule* find_rule(std::string_view name) const;  // nullptr: no rule of that name
};

// Every quantity in derivation order: inputs first, then each rule after the values it uses.
const std::vector<FluidQuantity>& fluid_quantities();
const FluidQuantity& fluid_quantity(std::string_view symbol);  // asserts that it exists

// A value of the derivation: what the rule gives and, when the user set it, what the user gave.
struct FluidValue {
  const FluidQuantity* quantity = nullptr;
  const FluidRule* rule = nullptr;  // derived quantities: the rule chosen (the default, or named)
  double value = 0.0;               // in force: the user's when given, else the rule's
  std::optional<double> by_rule;    // what the rule gives (from the values in force before it)
  bool given = false;               // set by the user (an input is always given, or defaulted)
};

struct FluidDerivation {
  int dimension = 2;
  std::vector<FluidValue> values;  // in the order of fluid_quantities()
  double value(std::string_view symbol) const;
  // The LIGGGHTS variables: (name, value) of every quantity that has a variable.
  std::vector<std::pair<std::string, double>> variables() const;
};

// The rule chosen for a quantity, by its key ("wall_friction" -> "moment"); absent: the default.
using FluidRuleChoices = std::map<std::string, std::string, std::less<>>;

// Derives every quantity from `given` (by key; g by its symbol "g"); a derived quantity given
// there wins over its rule, and the rules after it use the given value; `choices` picks a rule
// other than the default. Throws fsi::Error for a missing input, a value that comes out
// non-positive (naming the inputs to change), an unknown rule name, or a rule chosen for a value
// that is given as well.
FluidDerivation derive_fluid(const FluidValues& given, int dimension,
                             const FluidRuleChoices& choices = {});

// One line for --check: "c = cAB = 14.0 m/s: 10 max(sqrt(2 g H), U) with g = 9.81 m/s^2,
// H = 0.1 m, U = 0 m/s (thesis §6.2 ...)", or for a value the user set, the rule's value it
// replaces.
std::string explain(const FluidDerivation& derivation, const FluidValue& value);

// The table of docs/user-guide.md, "The Fluid block": one row per quantity (key, LIGGGHTS
// variable, symbol, unit, rule or "input", source); a unit test keeps the guide's copy equal.
std::string fluid_rules_markdown();

// LIGGGHTS' sph/artVisc acts on approaching pairs only; in a shear flow that is half of the pairs,
// and the fluid's kinematic viscosity is nu = alpha c h / divisor (2D: 16, 3D: 20; docs/theory.md,
// "Viscosity").
double artificial_viscosity_divisor(int dimension);

// The moment rule's wall friction (`wall_friction_rule = "moment"`) for a fluid of nu:
// t = rho0 nu d^D / M, M the friction's second moment over its range (2D: r_v^3 / 6, 3D:
// pi r_v^4 / 20), d the particle spacing: the wall's total friction in a linear shear flow equals
// the fluid's own stress (docs/theory.md, "Viscosity"). Measured in 2D: the channel flows meet it
// within 0.2 d of the drawn walls, where the default rho0 nu / r_v holds about one spacing of fluid
// on them; the rule for flows driven by a flux (examples/cylinder).
double moment_wall_friction(double density, double viscosity, double spacing, double range,
                            int dimension);

// The largest stable time step of the rules of thumb, min(0.125 h/c, 0.125 h^2/nu_max,
// 0.25 sqrt(h/g)), nu_max the larger of nu and the artificial viscosity's alpha c h / 16 (3D: 20);
// `explain_time_step` names each limit and the scene's step.
double recommended_time_step(const FluidDerivation& derivation);

// The step a coupled scene takes when it leaves SolverOptions.Timeint.step_size out: the largest
// step within dt_max = min(0.09 h/c, the viscous and the body-force limits) -- the acoustic
// fraction below the 0.092 h/c a dam break measured stable, not the 0.125 of a fluid at rest --
// that divides `end_time` into a whole number of structure steps of `substeps` fluid steps:
// end_time / N, N = substeps ceil(end_time / (substeps dt_max)). Throws fsi::Error when end_time
// or substeps is not positive.
double derived_time_step(const FluidDerivation& derivation, double end_time, int substeps);

// One line for --check: the limits, and the scene's step against them; `derived`: the step was
// left out and came from `derived_time_step` (the line says how).
std::string explain_time_step(const FluidDerivation& derivation, double scene_step,
                              bool derived = false, double end_time = 0.0);

}  // namespace fsi::scene
