// The Fluid block: the fluid's parameters from a few physical inputs
// (fsi/scene/fluid_parameters.hpp holds the rules); every value becomes the LIGGGHTS variable the
// examples' hand-written LIGGGHTS_SPH_parameters used, so their scripts read it unchanged.

#include <cmath>
#include <optional>

#include "fsi/common/error.hpp"
#include "scene_builder.hpp"

namespace fsi::scene::detail {
namespace {

constexpr std::string_view kSphBlock = "LIGGGHTS_SPH_parameters";

// The block's keys, one per quantity of the table: inputs required (or with their default),
// derived values optional (given: it wins over the rule).
std::vector<BlockSpec> fluid_parameter_blocks() {
  std::vector<ParameterSpec> keys;
  for (const FluidQuantity& q : fluid_quantities()) {
    if (q.key.empty()) continue;  // g: the Gravity block's
    std::string doc = std::string(q.meaning);
    if (!q.is_input()) {
      const FluidRule& rule = q.rules.front();
      doc += "; absent: " + std::string(rule.text) + " (" + std::string(rule.source) + ")";
      if (q.has_choice()) doc += ", or the rule " + q.rule_key() + " names";
    }
    if (!q.variable.empty()) doc += "; LIGGGHTS ${" + std::string(q.variable) + "}";
    ParameterSpec spec = number(std::string(q.key), std::string(q.unit), doc);
    spec = q.may_be_zero ? spec.at_least(0.0) : spec.positive();
    if (q.input_default) {
      spec = spec.with_default(*q.input_default);
    } else if (!q.is_input()) {
      spec = spec.optional();
    }
    keys.push_back(spec);
    if (q.has_choice()) {
      std::vector<std::string> names;
      std::string doc_rules;
      for (const FluidRule& rule : q.rules) {
        names.emplace_back(rule.name);
        doc_rules += (doc_rules.empty() ? "" : "; ") + ("\"" + std::string(rule.name) + "\": ") +
                     std::string(rule.text) + " (" + std::string(rule.source) + ")";
      }
      keys.push_back(text(q.rule_key(), "the rule that derives " + std::string(q.key) +
                                            " when it is not given, absent: \"" + names[0] +
                                            "\"; " + doc_rules)
                         .one_of(names)
                         .optional());
    }
  }
  return {block_spec("Fluid",
                     "The fluid's parameters from a few physical inputs (docs/user-guide.md, \"The "
                     "Fluid block\"): each value not given is derived by its rule and defined as "
                     "a LIGGGHTS variable before script 1; fsi-server --check explains each.",
                     keys)
              .for_coupled_runs()};
}

// A LIGGGHTS_SPH_parameters entry that the Fluid block defines too: one place per value.
void refuse_duplicates(SceneBuilder& builder, const View& fluid) {
  const Block* sph = builder.scene.parameters.child(kSphBlock);
  if (sph == nullptr) return;
  for (const Parameter& p : sph->parameters) {
    for (const FluidQuantity& q : fluid_quantities()) {
      if (q.variable.empty() || q.variable != p.key) continue;
      const std::string owner =
          q.key.empty() ? std::string("the Gravity block") : "Fluid." + std::string(q.key);
      builder.problem(p.location,
                      "'" + p.key + "' is given both here and by the Fluid block at " +
                          fluid.location().text() + " (" + owner + ", " + std::string(q.symbol) +
                          (q.is_input() ? "" : " = " + std::string(q.rules.front().text)) + ")",
                      q.key.empty() ? "remove it here: the Fluid block defines ${gravity} as |g| "
                                      "of the Gravity block"
                                    : "remove it here; to set it yourself, write " +
                                          std::string(q.key) + " = ... in the Fluid block");
    }
  }
}

bool has_every_input(const View& fluid) {
  for (const FluidQuantity& q : fluid_quantities()) {
    if (q.is_input() && !q.key.empty() && !q.input_default && !fluid.has(q.key)) return false;
  }
  return true;
}

// The block's values by its rules (throws the rules' errors).
FluidDerivation derive_block(const SceneBuilder& builder, const View& fluid) {
  FluidValues given;
  FluidRuleChoices choices;
  for (const FluidQuantity& q : fluid_quantities()) {
    if (!q.key.empty() && fluid.has(q.key)) given[std::string(q.key)] = fluid.number(q.key);
    if (q.has_choice() && fluid.has(q.rule_key()))
      choices[std::string(q.key)] = fluid.string(q.rule_key());
  }
  const auto& g = builder.scene.gravity;
  given["g"] = std::sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
  return derive_fluid(given, builder.dimension, choices);
}

void derive_from_fluid_block(SceneBuilder& builder) {
  if (builder.mode != SceneMode::Coupled || !builder.root.has_block("Fluid")) return;
  const View fluid = builder.root.block("Fluid");
  refuse_duplicates(builder, fluid);
  // A missing input is the schema's problem, reported already.
  if (!has_every_input(fluid)) return;
  builder.guard(fluid.location(), [&] {
    FluidDerivation derivation;
    try {
      derivation = derive_block(builder, fluid);
    } catch (const AlreadyReported&) {
      throw;
    } catch (const Error& error) {
      const std::string& key = error.location();
      const bool is_key = key != "g" && fluid.spec().parameter(key) != nullptr;
      builder.problem(is_key ? fluid.location(key) : fluid.location(), error.fault(),
                      error.remedy());
      return;
    }
    for (const FluidValue& value : derivation.values) {
      const FluidQuantity& q = *value.quantity;
      if (q.variable.empty()) continue;
      Parameter parameter;
      parameter.key = std::string(q.variable);
      parameter.value.kind = ValueKind::Number;
      parameter.value.number = value.value;
      parameter.location =
          !q.key.empty() && fluid.has(q.key) ? fluid.location(q.key) : fluid.location();
      builder.scene.fluid_variables.push_back(parameter);
    }
    builder.scene.fluid_parameters = derivation;
  });
}

// An --mbd-only run of a coupled scene (the structure dry): the coupled run's step, from the
// Fluid block's rules, so that both runs step and write their rows alike. None when the block
// lacks an input or its rules fail (the coupled run reports those).
std::optional<FluidDerivation> dry_run_derivation(const SceneBuilder& builder) {
  const View fluid = builder.root.block("Fluid");
  if (!has_every_input(fluid)) return std::nullopt;
  try {
    return derive_block(builder, fluid);
  } catch (const Error&) {
    return std::nullopt;
  }
}

// SolverOptions.Timeint.step_size left out: a scene with a Fluid block steps at the largest step
// its rule allows that divides end_time into whole structure steps (a coupled run, and its
// structure alone with --mbd-only); anything else needs the step written.
void settle_step_size(SceneBuilder& builder) {
  SolverSettings& solver = builder.scene.solver;
  const View timeint = builder.root.block("SolverOptions").block("Timeint");
  if (timeint.has("step_size")) return;  // given (a bad value is the schema's problem)
  const bool coupled = builder.mode == SceneMode::Coupled;
  const bool has_fluid = builder.root.has_block("Fluid");
  if (coupled && has_fluid && !builder.scene.fluid_parameters) return;  // its problem is reported
  if (!(solver.end_time > 0.0)) return;                                 // so is end_time's
  std::optional<FluidDerivation> fluid = builder.scene.fluid_parameters;
  if (!coupled && has_fluid) fluid = dry_run_derivation(builder);
  if (!fluid) {
    builder.problem(
        timeint.location(),
        std::string("SolverOptions.Timeint.step_size is missing") +
            (!has_fluid ? ", and there is no Fluid block to derive it from"
                        : ", and the Fluid block cannot derive it (check the scene without "
                          "--mbd-only for its problems)"),
        "write step_size = ... in SolverOptions.Timeint" +
            std::string(!has_fluid ? ", or give the fluid's physical inputs in a Fluid block "
                                     "(docs/user-guide.md, \"The Fluid block\")"
                                   : ""));
    return;
  }
  solver.step_size = derived_time_step(*fluid, solver.end_time, solver.substeps);
  solver.step_size_derived = true;
  solver.step_size_location = builder.root.block("Fluid").location();
}

void build_fluid_parameters(SceneBuilder& builder) {
  derive_from_fluid_block(builder);
  builder.guard(builder.root.location(), [&] { settle_step_size(builder); });
}

}  // namespace

ElementFamily fluid_parameters_family() {
  return {"fluid parameters", fluid_parameter_blocks, {build_fluid_parameters}};
}

}  // namespace fsi::scene::detail
