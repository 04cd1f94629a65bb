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

// One quantity of the fluid: an input (no rule) or a value derived from earlier ones by its rule.
struct FluidQuantity {
  std::string_view key;       // of the Fluid block ("" for g, which the Gravity block gives)
  std::string_view variable;  // the LIGGGHTS variable it becomes ("": none)
  std::string_view symbol;    // in the rules and in --check
  std::string_view unit;      // "" dimensionless
  std::string_view meaning;   // one line of doc
  std::string_view rule;      // the formula in words, "" for an input
  std::string_view source;    // where the rule comes from
  std::vector<std::string_view> uses;  // the symbols the rule reads
  // The rule (nullptr: an input). `dimension` 2 or 3.
  double (*derive)(const FluidValues& values, int dimension) = nullptr;
  bool may_be_zero = false;             // 0 is a valid value (an inviscid fluid, no speed)
  std::optional<double> input_default;  // inputs only: absent means required

  bool is_input() const { return derive == nullptr; }
};

// Every quantity in derivation order: inputs first, then each rule after the values it uses.
const std::vector<FluidQuantity>& fluid_quantities();
const FluidQuantity& fluid_quantity(std::string_view symbol);  // asserts that it exists

// A value of the derivation: what the rule gives and, when the user set it, what the user gave.
struct FluidValue {
  const FluidQuantity* quantity = nullptr;
  double value = 0.0;             // in force: the user's when given, else the rule's
  std::optional<double> by_rule;  // what the rule gives (from the values in force before it)
  bool given = false;             // set by the user (an input is always given, or defaulted)
};

struct FluidDerivation {
  int dimension = 2;
  std::vector<FluidValue> values;  // in the order of fluid_quantities()
  double value(std::string_view symbol) const;
  // The LIGGGHTS variables: (name, value) of every quantity that has a variable.
  std::vector<std::pair<std::string, double>> variables() const;
};

// Derives every quantity from `given` (by key; g by its symbol "g"); a derived quantity given
// there wins over its rule, and the rules after it use the given value. Throws fsi::Error for a
// missing input or a value that comes out non-positive (naming the inputs to change).
FluidDerivation derive_fluid(const FluidValues& given, int dimension);

// One line for --check: "c = cAB = 14.0 m/s: 10 max(sqrt(2 g H), U) with g = 9.81 m/s^2,
// H = 0.1 m, U = 0 m/s (thesis §6.2 ...)", or for a value the user set, the rule's value it
// replaces.
std::string explain(const FluidDerivation& derivation, const FluidValue& value);

// The table of docs/user-guide.md, "The Fluid block": one row per quantity (key, LIGGGHTS
// variable, symbol, unit, rule or "input", source); a unit test keeps the guide's copy equal.
std::string fluid_rules_markdown();

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
