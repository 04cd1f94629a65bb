#include "scene_builder.hpp"

#include <algorithm>
#include <charconv>
#include <cstdio>
#include <utility>

#include "fsi/common/error.hpp"
#include "raw_tree.hpp"
#include "runtime_expression.hpp"

namespace fsi::scene::detail {
namespace {

namespace fs = std::filesystem;

// What a scene of the other dimension suggests instead of a refused block: for a planar block,
// the spatial blocks there are (from their specs).
std::string counterpart_hint(int block_dimension, const std::vector<BlockSpec>& blocks) {
  if (block_dimension != 2)
    return "set dimension = 3 at the top of the scene, or use a planar element";
  std::string spatial;
  for (const BlockSpec& spec : blocks) {
    if (spec.dimension == 3) spatial += (spatial.empty() ? "" : ", ") + spec.name;
  }
  return "set dimension = 2, or use its spatial counterpart among " + spatial;
}

// The number at `path` ("Geometry.T", "RigidBody2D[1].mass": blocks down from `root`, then the
// key; its last assignment) for a runtime expression, or why not when the path names something
// else. An element list needs its index, as in --set.
RuntimeExpression::Found scene_number(const Block& root, const std::string& path) {
  const auto unknown = [&]() -> RuntimeExpression::Found {
    std::vector<std::string> paths;
    for (const auto& [number_path, value] : flatten_numbers(root))
      paths.push_back(number_path);
    const std::string suggestion = nearest(path, paths);
    if (suggestion.empty()) return {};
    return {std::nullopt, "'" + path +
                              "' is neither one of its variables nor a number of the scene (did "
                              "you mean '" +
                              suggestion + "'?)"};
  };
  std::vector<PathPart> parts;
  if (!parse_path(path, parts) || parts.back().index >= 0) return unknown();
  const Block* block = &root;
  for (std::size_t i = 0; i + 1 < parts.size(); ++i) {
    const std::vector<const Block*> candidates = block->children(parts[i].name);
    if (parts[i].index < 0 && candidates.size() > 1)
      return {std::nullopt, "'" + parts[i].name + "' in '" + path + "' is a list of " +
                                std::to_string(candidates.size()) + " blocks: pick one, " +
                                parts[i].name + "[0] ... " + parts[i].name + "[" +
                                std::to_string(candidates.size() - 1) + "]"};
    const std::size_t index = parts[i].index < 0 ? 0 : static_cast<std::size_t>(parts[i].index);
    if (index >= candidates.size()) return unknown();
    block = candidates[index];
  }
  const Parameter* parameter = block->find(parts.back().name);
  if (!parameter) return unknown();
  if (parameter->value.kind != ValueKind::Number)
    return {std::nullopt, "'" + path + "' is a " + std::string(name(parameter->value.kind)) +
                              ": arithmetic needs numbers"};
  return {parameter->value.number, ""};
}

}  // namespace

SceneBuilder::SceneBuilder(Scene& scene_, const View& root_, SceneMode mode_,
                           std::vector<Problem>& problems)
    : scene(scene_),
      model(scene_.model),
      root(root_),
      mode(mode_),
      dimension(scene_.dimension),
      scene_dir(fs::path(scene_.file).parent_path()),
      problems_(problems) {}

void SceneBuilder::build() {
  // A block of the other dimension is refused where it stands; blocks() then skips it.
  for (const BlockSpec& spec : root.spec().blocks) {
    if (spec.dimension == 0 || spec.dimension == dimension) continue;
    for (const View& element : root.blocks(spec.name)) {
      problem(element.location(),
              spec.dimension == 2
                  ? spec.name +
                        " is a planar (2D) element: planar bodies and their "
                        "joints need dimension = 2"
                  : spec.name + " is a spatial (3D) element: it needs dimension = 3",
              counterpart_hint(spec.dimension, root.spec().blocks));
    }
  }
  for (const ElementFamily& family : element_families()) {
    for (const auto build_step : family.build_steps)
      build_step(*this);
  }
}

std::vector<View> SceneBuilder::blocks(std::string_view name) const {
  const BlockSpec* spec = root.spec().block(name);
  if (spec != nullptr && spec->dimension != 0 && spec->dimension != dimension) return {};
  return root.blocks(name);
}

void SceneBuilder::each(std::string_view name, const std::function<void(const View&)>& build) {
  for (const View& element : blocks(name)) {
    const bool built = guard(element.location(), [&] {
      const int first_row = model.constraint_count();
      build(element);
      // Only constraint blocks declare it (releasable); in another block the schema has
      // reported it as unknown already.
      if (element.spec().parameter("release_time") == nullptr || !element.has("release_time"))
        return;
      const double release = element.number("release_time");
      placed(element, [&] {
        for (int row = first_row; row < model.constraint_count(); ++row)
          model.set_release_time(row, release);
      });
    });
    // A named element that failed (reported) is remembered, so that a sensor naming it is
    // skipped rather than told the name does not exist.
    const ParameterSpec* named = element.spec().parameter("name");
    if (!built && named != nullptr && named->kind == Kind::String && element.has("name")) {
      try {
        skipped_elements_.push_back(element.string("name"));
      } catch (const AlreadyReported&) {  // the name itself is in error: nothing can name it
      }
    }
  }
}

bool SceneBuilder::element_skipped(const std::string& name) const {
  return std::find(skipped_elements_.begin(), skipped_elements_.end(), name) !=
         skipped_elements_.end();
}

bool SceneBuilder::guard(const SourceLocation& element, const std::function<void()>& step) {
  const int first_row = model.constraint_count();
  try {
    step();
    const int rows = model.constraint_count() - first_row;
    if (rows > 0) row_owners_.push_back({element, first_row, rows});
    return true;
  } catch (const AlreadyReported&) {
    skipped_any_ = true;
  } catch (const Error& error) {
    const SourceLocation where =
        error.location().empty() ? element : SourceLocation{error.location()};
    problems_.push_back({where, error.fault(), error.remedy()});
  }
  return false;
}

void SceneBuilder::problem(const SourceLocation& where, const std::string& message,
                           const std::string& fix) {
  problems_.push_back({where, message, fix});
}

const SourceLocation* SceneBuilder::owner_of_row(int row) const {
  const RowOwner* owner = nullptr;
  for (const RowOwner& candidate : row_owners_) {
    const bool holds = row >= candidate.first_row && row < candidate.first_row + candidate.rows;
    if (holds && (owner == nullptr || candidate.rows < owner->rows)) owner = &candidate;
  }
  return owner == nullptr ? nullptr : &owner->where;
}

void SceneBuilder::problem(Problem found) {
  problems_.push_back(std::move(found));
}

std::optional<mbd::BodyId> SceneBuilder::add_body(
    const View& element, const std::function<std::optional<mbd::BodyId>()>& add) {
  // The name goes on the skipped list as soon as it is read, and off it once the body exists:
  // a body that fails on any value skips the elements that name it.
  const Parameter* name_given = element.raw().find("name");
  if (name_given && name_given->failed) unnamed_body_skipped_ = true;
  std::optional<mbd::BodyId> id;
  guard(element.location(), [&] {
    skipped_bodies_.push_back(element.string("name"));
    try {
      id = add();
    } catch (const AlreadyReported&) {
      throw;
    } catch (const Error& error) {
      problem(element.location("name"), error.fault(), error.remedy());
      return;
    }
    if (id) skipped_bodies_.pop_back();
  });
  return id;
}

mbd::BodyId SceneBuilder::find_body(const View& element, std::string_view key) {
  const std::string& name = element.string(key);
  if (std::find(skipped_bodies_.begin(), skipped_bodies_.end(), name) != skipped_bodies_.end()) {
    throw AlreadyReported(element.location(key));
  }
  try {
    return model.find_body(name);
  } catch (const Error& error) {
    if (unnamed_body_skipped_) throw AlreadyReported(element.location(key));  // perhaps it
    throw Error(error.fault(), element.location(key).text(), error.remedy());
  }
}

mbd::BodyPointSpec SceneBuilder::point(const View& element, const std::string& side) {
  mbd::BodyPointSpec point;
  if (side == "a" || element.has("body_b")) point.body = find_body(element, "body_" + side);
  const auto local = element.vector("point_" + side);
  point.local = {local[0], local[1]};
  return point;
}

mbd::SpatialPointSpec SceneBuilder::point3(const View& element, const std::string& side) {
  mbd::SpatialPointSpec point;
  if (side == "a" || element.has("body_b")) point.body = find_body(element, "body_" + side);
  point.local = vector3(element, "point_" + side);
  return point;
}

void SceneBuilder::placed(const View& element, const std::function<void()>& add) {
  try {
    add();
  } catch (const AlreadyReported&) {
    throw;
  } catch (const Error& error) {
    throw Error(error.fault(), element.location().text(), error.remedy());
  }
}

bool SceneBuilder::name_is_free(const View& element) {
  if (!element.has("name")) return false;
  const std::string& name = element.string("name");
  if (names.joints.count(name) == 0 && names.force_elements.count(name) == 0) return true;
  problem(element.location("name"), "a second element is named '" + name + "'",
          "give every joint and force element its own name");
  return false;
}

void SceneBuilder::add_joint(const View& element, const std::function<int()>& add,
                             NamedJoint joint) {
  placed(element, [&] { joint.first_row = add(); });
  register_joint(element, std::move(joint));
}

void SceneBuilder::add_force_element(const View& element, const std::function<int()>& add,
                                     bool rotational) {
  int index = 0;
  placed(element, [&] { index = add(); });
  register_force_element(element, index, rotational);
}

void SceneBuilder::register_joint(const View& element, NamedJoint joint) {
  if (name_is_free(element)) names.joints.emplace(element.string("name"), std::move(joint));
}

void SceneBuilder::register_force_element(const View& element, int index, bool rotational) {
  if (!name_is_free(element)) return;
  names.force_elements.emplace(element.string("name"), index);
  names.rotational.emplace(element.string("name"), rotational);
}

// Relative to the folder of the scene file that names it (an included file's own folder), or to
// the top-level scene's for a --set (no line); unless absolute.
fs::path SceneBuilder::scene_relative(const SourceLocation& where, const std::string& name) const {
  if (fs::path(name).is_absolute()) return name;
  const bool in_a_file = where.line > 0;
  return (in_a_file ? fs::path(where.file).parent_path() : scene_dir) / name;
}

std::optional<TriangleMesh> SceneBuilder::read_stl(const View& block, std::string_view key) {
  const std::string& name = block.string(key);
  const fs::path file = scene_relative(block.location(key), name);
  std::error_code error;
  if (!fs::is_regular_file(file, error)) {
    problem(block.location(key), "STL file '" + file.string() + "' does not exist",
            "give the path relative to the scene file that names it");
    return std::nullopt;
  }
  try {
    return scene::read_stl(file.string());
  } catch (const Error& failure) {
    const std::string where = failure.location().empty() ? "" : " (" + failure.location() + ")";
    problem(block.location(key), failure.fault() + where, failure.remedy());
    return std::nullopt;
  }
}

std::optional<std::vector<double>> SceneBuilder::dimension_vector(const View& block,
                                                                  std::string_view key,
                                                                  int components) {
  const auto size = static_cast<std::size_t>(components);
  if (!block.has(key)) return std::vector<double>(size, 0.0);
  std::vector<double> value = block.vector(key);
  if (value.size() == size) return value;
  problem(block.location(key),
          "'" + std::string(key) + "' has " + std::to_string(value.size()) +
              " components, the scene has dimension = " + std::to_string(components),
          components == 3 ? "write " + std::string(key) + " = [x, y, z]"
                          : "write " + std::string(key) +
                                " = [x, y], or set dimension = 3 at the top of the scene");
  return std::nullopt;
}

ParameterSpec per_dimension(ParameterSpec spec) {
  spec.length.reset();
  return spec;
}

std::vector<ParameterSpec> planar_two_points(std::vector<ParameterSpec> more, bool on_beams) {
  std::vector<ParameterSpec> parameters =
      on_beams
          ? std::vector<ParameterSpec>{element_name_spec(),
                                       text("body_a", "name of a RigidBody2D or AncfBeam2D"),
                                       vector("point_a", 2, "m",
                                              "point on body_a: body coordinates, [s, eta] on a "
                                              "beam")
                                           .with_default({0.0, 0.0}),
                                       text("body_b",
                                            "name of a RigidBody2D or AncfBeam2D; absent: the "
                                            "ground")
                                           .optional(),
                                       vector("point_b", 2, "m",
                                              "point on body_b (body coordinates, [s, eta] on a "
                                              "beam) or in the world")
                                           .with_default({0.0, 0.0})}
          : std::vector<ParameterSpec>{
                element_name_spec(), text("body_a", "name of a RigidBody2D"),
                vector("point_a", 2, "m", "point on body_a, body coordinates")
                    .with_default({0.0, 0.0}),
                text("body_b", "name of a RigidBody2D; absent: the ground").optional(),
                vector("point_b", 2, "m", "point on body_b (body coordinates) or in the world")
                    .with_default({0.0, 0.0})};
  parameters.insert(parameters.end(), more.begin(), more.end());
  return parameters;
}

ParameterSpec spatial_point(const std::string& side, const std::string& doc) {
  return vector(side.empty() ? std::string("point") : "point_" + side, 3, "m", doc)
      .with_default({0.0, 0.0, 0.0});
}

std::vector<ParameterSpec> spatial_two_points(std::vector<ParameterSpec> more) {
  std::vector<ParameterSpec> parameters = {
      element_name_spec(), text("body_a", "name of a RigidBody3D, PointMass or AncfCable3D"),
      spatial_point("a",
                    "point on body_a: body axes from the centre of mass; [s, 0, 0] on a cable; "
                    "[0, 0, 0] on a point mass"),
      text("body_b", "name of a spatial body; absent: the ground").optional(),
      spatial_point("b", "point on body_b (as point_a) or in the world")};
  parameters.insert(parameters.end(), more.begin(), more.end());
  return parameters;
}

Eigen::Vector3d vector3(const View& element, std::string_view key) {
  const auto v = element.vector(key);
  return {v[0], v[1], v[2]};
}

BlockSpec releasable(BlockSpec constraint_block) {
  constraint_block.parameters.push_back(
      number("release_time", "s",
             "the constraint holds until this time and is removed from then on: its multipliers "
             "are zero, its joint_force and constraint_force sensors read 0 (absent: never)")
          .at_least(0.0)
          .optional());
  return constraint_block;
}

std::vector<BlockSpec> releasable(std::vector<BlockSpec> constraint_blocks) {
  for (BlockSpec& block : constraint_blocks)
    block = releasable(std::move(block));
  return constraint_blocks;
}

ParameterSpec element_name_spec() {
  return text("name", "unique name for sensors and messages (default: kind and index)").optional();
}

std::string name_of(const View& element) {
  return element.has("name") ? element.string("name") : std::string();
}

std::optional<double> optional_number(const View& element, std::string_view key) {
  if (!element.has(key)) return std::nullopt;
  return element.number(key);
}

mbd::Coordinate coordinate_of(const std::string& text) {
  if (text == "x") return mbd::Coordinate::X;
  if (text == "y") return mbd::Coordinate::Y;
  return mbd::Coordinate::Angle;  // "angle" or "torque"
}

std::vector<double> prescribed_motion_check_times(double end_time) {
  constexpr int kChecks = 200;
  std::vector<double> times(1, 0.0);
  for (int k = 1; k <= kChecks; ++k)
    times.push_back(end_time * (k - 0.381966) / kChecks);
  return times;
}

std::string with_scene_numbers(std::string text) {
  return text +
         " Other names in the expressions are the scene's numbers by their path from the "
         "top, as --set names them (Geometry.T, RigidBody2D[1].mass).";
}

RuntimeExpression SceneBuilder::expression(const View& element, std::string_view key,
                                           const std::vector<std::string>& variables) const {
  const Block& top = root.raw();
  try {
    return RuntimeExpression(element.string(key), variables,
                             [&top](const std::string& path) { return scene_number(top, path); });
  } catch (const Error& error) {
    throw Error(error.fault(), element.location(key).text(), error.remedy());
  }
}

}  // namespace fsi::scene::detail
