#include "family_assembly.hpp"

#include <algorithm>
#include <sstream>
#include <string>

#include "fsi/common/error.hpp"
#include "scene_builder.hpp"

namespace fsi::scene::detail {
namespace {

// "crank.angle" -> the index of that coordinate in q; a problem at `where` otherwise. Planar
// rigid bodies have x, y, angle; spatial rigid bodies and point masses x, y, z of the centre of
// mass (their axes are coordinates no user drives).
std::optional<int> driving_index(const mbd::Model& model, const std::string& item,
                                 const SourceLocation& where, std::vector<Problem>& problems) {
  const auto dot = item.rfind('.');
  if (dot == std::string::npos || dot == 0 || dot + 1 == item.size()) {
    problems.push_back({where,
                        "driving coordinate '" + item + "' is not of the form body.coordinate",
                        "write e.g. driving = \"crank.angle\" (2D: x, y, angle; 3D: x, y, z)"});
    return std::nullopt;
  }
  const std::string body_name = item.substr(0, dot);
  const std::string coordinate = item.substr(dot + 1);
  mbd::BodyId body = mbd::kGround;
  try {
    body = model.find_body(body_name);
  } catch (const Error& error) {
    problems.push_back(
        {where, "driving coordinate '" + item + "': " + error.fault(), error.remedy()});
    return std::nullopt;
  }
  const std::string kind = model.body_kind(body);
  const std::vector<std::string> names =
      kind == "rigid_body_2d" ? std::vector<std::string>{"x", "y", "angle"}
      : kind == "rigid_body_3d" || kind == "point_mass" ? std::vector<std::string>{"x", "y", "z"}
                                                        : std::vector<std::string>{};
  if (names.empty()) {
    problems.push_back({where,
                        "driving coordinate '" + item + "': '" + body_name + "' is a " + kind +
                            ", whose coordinates cannot be marked as driving",
                        "mark a coordinate of a rigid body or point mass"});
    return std::nullopt;
  }
  for (std::size_t k = 0; k < names.size(); ++k) {
    if (names[k] == coordinate) return model.first_coordinate(body) + static_cast<int>(k);
  }
  std::string known;
  for (const std::string& name : names)
    known += (known.empty() ? "" : ", ") + name;
  problems.push_back(
      {where,
       "driving coordinate '" + item + "': a " + kind + " has no coordinate '" + coordinate + "'",
       "use one of " + known});
  return std::nullopt;
}

}  // namespace

BlockSpec assembly_block_spec() {
  return block_spec(
      "Assembly",
      "Initial assembly before step 0 (docs/user-guide.md, \"Initial assembly\"): the bodies' "
      "positions and velocities as given are corrected by the smallest change (mass metric) "
      "that satisfies every joint; the log says how far each body moved. Without this block the "
      "initial state must satisfy the constraints to 1e-12 as given.",
      {integer("enabled", "1: assemble (the block's presence means 1); 0: check only")
           .between(0, 1)
           .with_default(1.0),
       number("tolerance", "m, rad", "largest constraint residual accepted, times (1 + |q|)")
           .positive()
           .at_most(1e-6)
           .with_default(1e-12),
       integer("max_iterations", "Gauss-Newton steps before the loop counts as open")
           .at_least(1)
           .with_default(50.0),
       text("driving",
            "coordinates kept exactly as given, comma-separated body.coordinate (2D: x, y, "
            "angle; 3D: x, y, z), e.g. \"crank.angle\"")
           .with_default("")});
}

std::optional<AssemblyRequest> assembly_request(const View& root, const mbd::Model& model,
                                                std::vector<Problem>& problems) {
  if (!root.has_block("Assembly")) return std::nullopt;
  const View block = root.block("Assembly");
  AssemblyRequest request;
  request.block = block.location();
  try {
    if (block.integer("enabled") == 0) return std::nullopt;
    request.options.tolerance = block.number("tolerance");
    request.options.max_iterations = static_cast<int>(block.integer("max_iterations"));
    std::string driving = block.string("driving");
    for (char& c : driving) {
      if (c == ',') c = ' ';
    }
    std::istringstream items(driving);
    std::string item;
    while (items >> item) {
      const auto index = driving_index(model, item, block.location("driving"), problems);
      if (!index) continue;
      auto& driving_coordinates = request.options.driving_coordinates;
      if (std::find(driving_coordinates.begin(), driving_coordinates.end(), *index) !=
          driving_coordinates.end()) {
        problems.push_back({block.location("driving"),
                            "driving coordinate '" + item + "' is named twice",
                            "name each driving coordinate once"});
        continue;
      }
      driving_coordinates.push_back(*index);
    }
  } catch (const AlreadyReported&) {
    return std::nullopt;
  }
  return request;
}

namespace {

void request_assembly(SceneBuilder& builder) {
  std::vector<Problem> found;
  builder.assembly = assembly_request(builder.root, builder.model, found);
  for (Problem& problem : found)
    builder.problem(std::move(problem));
}

}  // namespace

ElementFamily assembly_family() {
  return {"initial assembly",
          [] { return std::vector<BlockSpec>{assembly_block_spec()}; },
          {request_assembly}};
}

mbd::AssemblyReport assemble_initial_configuration(mbd::Model& model,
                                                   const AssemblyRequest& request) {
  try {
    mbd::AssemblyReport report =
        mbd::assemble(model, model.initial_configuration(), request.options);
    model.set_initial_configuration(report.state.q, report.state.v);
    return report;
  } catch (const Error& error) {
    throw Error(error.fault(), request.block.text() + " (Assembly)", error.remedy());
  }
}

}  // namespace fsi::scene::detail
