#include "fsi/scene/scene.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <tuple>

#include "fsi/common/error.hpp"
#include "scene_builder.hpp"

namespace fsi::scene {
namespace {

BlockSpec make_schema() {
  BlockSpec root;
  root.name = "";
  root.doc = "A scene file.";
  root.user_blocks_allowed = true;
  root.parameters = {
      integer("dimension",
              "2: planar scene (RigidBody2D, AncfBeam2D, polyline meshes); 3: spatial scene "
              "(RigidBody3D, PointMass, AncfCable3D, STL meshes, a 3D fluid)")
          .between(2, 3)
          .with_default(2)};
  for (const detail::ElementFamily& family : detail::element_families()) {
    for (BlockSpec& block : family.blocks())
      root.blocks.push_back(std::move(block));
  }
  return root;
}

// Marks the parameter at `where` as failed (a schema problem names it), so that the builder
// skips what needs it.
bool mark_failed(Block& block, const SourceLocation& where) {
  for (Parameter& parameter : block.parameters) {
    if (parameter.location == where) {
      parameter.failed = true;
      return true;
    }
  }
  for (Block& child : block.blocks) {
    if (mark_failed(child, where)) return true;
  }
  return false;
}

// The version statement: required, not defaulted, because a later language version may change
// what existing syntax means, and an unversioned file would then be read by the wrong rules
// without a word.
void check_language_version(const Block& parameters, const std::string& path,
                            std::vector<Problem>& problems) {
  if (!parameters.language_version) {
    Problem missing;
    missing.location.file = path;
    missing.location.line = 1;
    missing.location.column = 1;
    missing.message = "the scene does not state the scene language version it is written for";
    missing.fix = "add the line 'scene_language = " + std::to_string(kSceneLanguageVersion) +
                  "' at the top of the file (comments may stand above it)";
    problems.push_back(std::move(missing));
  }
  if (const Block* old = parameters.child("SceneFormat")) {
    problems.push_back({old->location, "SceneFormat { version = N } is no longer read",
                        "replace it by 'scene_language = N' as the first entry of the file"});
  }
}

// In the order of the scene file; problems in included files after it.
void sort_by_place(std::vector<Problem>& problems, const std::string& path) {
  std::stable_sort(problems.begin(), problems.end(), [&](const Problem& a, const Problem& b) {
    const auto key = [&](const Problem& p) {
      return std::make_tuple(p.location.file != path, p.location.file, p.location.line,
                             p.location.column);
    };
    return key(a) < key(b);
  });
}

// The schema of a run of the structure alone: the fluid's blocks are not required.
BlockSpec structure_only(BlockSpec schema) {
  for (BlockSpec& block : schema.blocks) {
    if (block.coupled_only) block.required = false;
  }
  return schema;
}

const BlockSpec& schema_for(SceneMode mode) {
  static const BlockSpec mbd_only = structure_only(scene_schema());
  return mode == SceneMode::Coupled ? scene_schema() : mbd_only;
}

std::string joined(const std::vector<std::string>& names) {
  std::string text;
  for (const std::string& name : names)
    text += (text.empty() ? "" : ", ") + name;
  return text;
}

// The model lists what is wrong with the initial state row by row ("\n  revolute joint 'hinge'
// (x): redundant ..."); each line becomes a problem at the block that added the row, so that a
// redundant or unsatisfied joint is found at its scene line.
std::vector<Problem> at_their_blocks(const Error& error, const mbd::Model& model,
                                     const detail::SceneBuilder& builder, const std::string& path) {
  const std::string separator = "\n  ";
  const std::string& text = error.fault();
  std::size_t start = text.find(separator);
  const std::string headline = text.substr(0, start == std::string::npos ? text.size() : start);
  std::vector<Problem> problems;
  while (start != std::string::npos) {
    const std::size_t end = text.find(separator, start + separator.size());
    const std::string line =
        text.substr(start + separator.size(),
                    end == std::string::npos ? std::string::npos : end - start - separator.size());
    SourceLocation where;
    where.file = path;
    for (int row = 0; row < model.constraint_count(); ++row) {
      const SourceLocation* owner = builder.owner_of_row(row);
      if (owner != nullptr && line.rfind(model.constraint_description(row) + ":", 0) == 0) {
        where = *owner;
        break;
      }
    }
    Problem found;
    found.location = where;
    found.message = headline + " " + line;
    found.fix = error.remedy();
    problems.push_back(std::move(found));
    start = end;
  }
  if (problems.empty()) {
    Problem whole;
    whole.location.file = path;
    whole.message = headline;
    whole.fix = error.remedy();
    problems.push_back(std::move(whole));
  }
  return problems;
}

}  // namespace

const BlockSpec& scene_schema() {
  static const BlockSpec schema = make_schema();
  return schema;
}

const Parameter* sph_parameter(const Scene& scene, std::string_view name) {
  if (const Block* block = scene.parameters.child("LIGGGHTS_SPH_parameters")) {
    if (const Parameter* parameter = block->find(name)) return parameter;
  }
  for (const Parameter& parameter : scene.fluid_variables) {
    if (parameter.key == name) return &parameter;
  }
  return nullptr;
}

std::string fluid_box_fill(const Scene& scene) {
  constexpr double kMissingFraction = 0.25;  // of d: 2 % of the depth at 12 rows
  const double d = scene.fluid.spacing;
  if (scene.parameters.child("FluidRegion") == nullptr || !(d > 0.0)) return "";
  const std::vector<View> regions = View(scene.parameters, scene_schema()).blocks("FluidRegion");
  const auto text = [](double value) {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.4g", value);
    return std::string(buffer);
  };
  std::string found;
  for (std::size_t n = 0; n < regions.size(); ++n) {
    const View& region = regions[n];
    if (region.string("shape") != "box") continue;
    const auto lower = region.vector("lower");
    const auto upper = region.vector("upper");
    constexpr std::array<const char*, 3> kAxes{"x", "y", "z"};
    std::string axes, drawn, cells, filled, short_by;
    for (std::size_t k = 0; k < std::min(lower.size(), upper.size()); ++k) {
      const double extent = upper[k] - lower[k];
      const double count = std::floor(extent / d + 1e-9);
      const double missing = extent - count * d;
      const std::string by = k == 0 ? "" : " x ";
      axes += std::string(k == 0 ? "" : ", ") + kAxes.at(k);
      drawn += by + text(extent);
      cells += by + text(count);
      filled += by + text(count * d);
      if (count >= 1.0 && missing > kMissingFraction * d * (1.0 + 1e-9)) {
        short_by += std::string(short_by.empty() ? "" : ", ") + kAxes.at(k) + " " +
                    text(100.0 * missing / extent) + " %";
      }
    }
    if (short_by.empty()) continue;
    const std::string which =
        regions.size() > 1 ? " of FluidRegion[" + std::to_string(n) + "]" : "";
    found += std::string(found.empty() ? "" : "; ") + "the fluid box" + which + " (" + axes + ") " +
             drawn + " m holds " + cells + " cells of " + text(d) + " m: the water fills " +
             filled + " m, " + short_by +
             " short at the upper side (whole cells from the lower corner; make each extent a "
             "whole number of spacings to fill the box)";
  }
  return found;
}

std::string blocks_needed(const Scene& scene, SceneMode mode) {
  const bool coupled = mode == SceneMode::Coupled;
  std::vector<std::string> needed;
  std::vector<std::string> unread;
  for (const BlockSpec& block : schema_for(mode).blocks) {
    if (block.required) needed.push_back(block.name);
    if (!coupled && block.coupled_only && scene.parameters.child(block.name) != nullptr) {
      // The Fluid block gives a dry run its step when the scene leaves it out.
      const bool gives_step = block.name == "Fluid" && scene.solver.step_size_derived;
      unread.push_back(block.name + (gives_step ? " (but for the step it derives)" : ""));
    }
  }
  std::string text =
      std::string(coupled ? "a coupled run" : "an --mbd-only run") + " needs: " + joined(needed) +
      (coupled ? ", and a surface mesh (Mesh blocks of bodies or Ground)" : "") + "\n";
  if (scene.model.coordinate_count() == 0) {
    text += "  no moving bodies: of SolverOptions only end_time and Timeint.step_size are used" +
            std::string(coupled ? "" : " (and --mbd-only needs a body)") + "\n";
  }
  if (!unread.empty())
    text += "  given but not read by an --mbd-only run: " + joined(unread) + "\n";
  return text;
}

Scene build_scene(const std::string& path, const std::vector<Override>& overrides, SceneMode mode) {
  Scene scene;
  scene.file = path;
  // Every problem is collected: evaluation, schema, then what the builder finds in the values
  // that are sound. Elements that need a value in error are skipped, not reported again.
  std::vector<Problem> problems;
  const BlockSpec& schema = schema_for(mode);
  scene.parameters = load_parameter_file(path, overrides, problems, declared_parameters(schema));
  for (Problem& problem : validate(scene.parameters, schema)) {
    mark_failed(scene.parameters, problem.location);
    problems.push_back(std::move(problem));
  }
  const bool input_sound = problems.empty();
  check_language_version(scene.parameters, path, problems);

  const View root(scene.parameters, schema);
  try {
    scene.dimension = static_cast<int>(root.integer("dimension"));
  } catch (const AlreadyReported&) {
    // Reported by the schema; the builder goes on as a planar scene.
  }
  scene.boundary.dimension = scene.dimension;
  scene.fluid.dimension = scene.dimension;
  detail::SceneBuilder builder(scene, root, mode, problems);
  builder.build();

  sort_by_place(problems, path);
  throw_if_any(problems, path);
  FSI_ASSERT(input_sound && !builder.skipped_any(),
             "a value in error was skipped without a problem");
  if (builder.assembly)
    scene.assembly = detail::assemble_initial_configuration(scene.model, *builder.assembly);
  try {
    (void)scene.model.initial_state();
  } catch (const Error& error) {
    std::vector<Problem> inconsistent = at_their_blocks(error, scene.model, builder, path);
    sort_by_place(inconsistent, path);
    throw_if_any(inconsistent, path);
  }
  return scene;
}

}  // namespace fsi::scene
