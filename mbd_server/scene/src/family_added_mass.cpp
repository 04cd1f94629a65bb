// AddedMass: artificial added mass on a light body in the fluid (docs/theory.md, "Artificial added
// mass"), the cure for the added-mass instability of the staggered coupling. Coupled runs only:
// without fluid there is no instability to damp, and --mbd-only integrates the body's own mass.

#include <cstdio>
#include <string>

#include "scene_builder.hpp"

namespace fsi::scene::detail {
namespace {

std::vector<BlockSpec> added_mass_blocks() {
  return {
      block_spec(
          "AddedMass",
          "Artificial added mass on a body that is light against the water it moves (docs/"
          "theory.md, \"Artificial added mass\"): the body is integrated with its mass matrix "
          "times 1 + ratio, and ratio times its own mass matrix times its mean acceleration over "
          "the last coupled step is applied back as a load over the next, so a steady motion is "
          "the body's own while the extra inertia damps the added-mass instability of the "
          "staggered scheme (the energy audit's `coupling_energy` stop). Gravity keeps the "
          "body's own mass. A ratio of about the water's added mass over the body's own mass, or "
          "more, is stable. The compensation acts one step late, which undamps every stiffness k "
          "acting on the body: pay it with a damping of at least ratio dt k (dt the structure's "
          "step; required of a beam's own axial and bending damping, ratio dt EA and ratio dt "
          "EI; advised for springs and stops on the body).",
          {element_name_spec(), text("body", "name of the body (any kind)"),
           number("ratio", "", "artificial mass as a multiple of the body's own mass")
               .at_least(0.0)})
          .as_list()
          .for_coupled_runs(),
  };
}

std::string number_text(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.4g", value);
  return text;
}

// The lag of the compensation feeds the stiffnesses acting on the body (docs/theory.md): a
// flexible body needs its own stiffness-proportional damping of at least ratio dt (EA, EI), dt
// the structure's step. Refused with the values it needs otherwise.
template <typename BeamSpec>
void check_beam_damping(SceneBuilder& builder, const View& element, const BeamSpec& beam,
                        double ratio, double step) {
  const double axial = ratio * step * beam.axial_stiffness;
  const double bending = ratio * step * beam.bending_stiffness;
  if (beam.axial_damping >= axial && beam.bending_damping >= bending) return;
  builder.problem(
      element.location("ratio"),
      "the AddedMass of '" + beam.name + "' (ratio " + number_text(ratio) +
          ") needs axial_damping >= ratio dt EA = " + number_text(axial) +
          " and bending_damping >= ratio dt EI = " + number_text(bending) +
          " (dt = " + number_text(step) + " s, the structure's step), but the beam has " +
          number_text(beam.axial_damping) + " and " + number_text(beam.bending_damping) +
          ": the compensation acts one step late, which undamps the beam's own modes "
          "(docs/theory.md, \"Artificial added mass\")",
      "give the beam at least that damping, or a smaller ratio");
}

void build_added_mass(SceneBuilder& builder) {
  if (builder.mode != SceneMode::Coupled) return;
  const double step = builder.scene.solver.step_size * builder.scene.solver.substeps;
  builder.each("AddedMass", [&](const View& element) {
    const mbd::BodyId body = builder.find_body(element, "body");
    const double ratio = element.number("ratio");
    if (builder.model.is_beam(body)) {
      check_beam_damping(builder, element, builder.model.beam(body), ratio, step);
    } else if (builder.model.is_cable(body)) {
      check_beam_damping(builder, element, builder.model.cable(body), ratio, step);
    }
    builder.placed(element, [&] { builder.model.set_added_mass_ratio(body, ratio); });
  });
}

}  // namespace

ElementFamily added_mass_family() {
  return {"added mass", added_mass_blocks, {build_added_mass}};
}

}  // namespace fsi::scene::detail
