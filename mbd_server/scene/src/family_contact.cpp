// Contact between structures: penalty contact (mbd::Model::add_contact) between the surface
// meshes of two bodies, or of a body and the ground, or of every pair ("*"). Built after the
// meshes, joints, springs and loads, so that the contact's force elements follow theirs. The
// pairs with contact are remembered in Scene::contact_pairs: the run's crossing check watches
// the others (mesh_crossing.hpp).

#include <algorithm>
#include <cmath>
#include <map>

#include "fsi/common/error.hpp"
#include "scene_builder.hpp"

namespace fsi::scene::detail {
namespace {

std::vector<BlockSpec> contact_blocks() {
  return {
      block_spec(
          "Contact",
          "Penalty contact between the surface meshes of body_a and body_b (docs/theory.md, "
          "\"Contact between structures\"): every vertex of either mesh behind an element of the "
          "other feels k delta + c d(delta)/dt along the element's outward normal (never "
          "pulling), and optional regularised Coulomb friction. k = (the heavier body's weight) "
          "/ penetration_tolerance: the whole weight on one vertex sinks it by the tolerance.",
          {element_name_spec(),
           text("body_a", "a body with a mesh, or \"*\": every pair of meshes (ground included)"),
           text("body_b", "a body with a mesh, or \"ground\"").with_default("ground"),
           number("penetration_tolerance", "m",
                  "depth at which one vertex carries the heavier body's weight (default: 1 % "
                  "of the smaller mesh's smallest extent)")
               .positive()
               .optional(),
           number("stiffness", "N/m",
                  "per vertex (2D: per unit depth); given, it replaces weight / tolerance")
               .positive()
               .optional(),
           number("damping_ratio", "",
                  "c = ratio 2 sqrt(k m), m the lighter body's mass (ramped in over the first "
                  "10 % of the tolerance)")
               .at_least(0.0)
               .with_default(0.5),
           number("friction", "", "Coulomb coefficient mu").at_least(0.0).with_default(0.0),
           number("regularisation_speed", "m/s",
                  "v_reg of f_t = -mu f_n tanh(|v_t| / v_reg); much smaller values make Newton "
                  "fail at impacts")
               .positive()
               .with_default(0.03),
           number("depth_limit", "m",
                  "a vertex deeper than this behind an element has passed it and feels nothing "
                  "(default: min(10 tolerances, a quarter of the smaller mesh's smallest extent))")
               .positive()
               .optional()})
          .as_list(),
  };
}

// One body's (or the ground's) part of the boundary mesh, as the contact's surface.
struct BodySurface {
  mbd::ContactSurfaceSpec spec;
  double smallest_extent = 0.0;  // of its bounding box; 0 for the ground
};

std::map<mbd::BodyId, BodySurface> surfaces_by_body(const Scene& scene) {
  const BoundaryMesh& boundary = scene.boundary;
  const mbd::Model& model = scene.model;
  const int corners = boundary.dimension;
  std::map<mbd::BodyId, BodySurface> surfaces;
  std::map<std::uint32_t, int> local_index;  // mesh vertex -> index in its body's surface
  auto body_of = [&](std::uint32_t vertex) {
    return vertex < boundary.dynamic_vertex_count ? model.marker_body(static_cast<int>(vertex))
                                                  : mbd::kGround;
  };
  auto place_of = [&](std::uint32_t vertex) -> Eigen::Vector3d {
    // 2D: every vertex is a marker (the ground's hold world positions); 3D: the ground's
    // vertices are static positions after the markers.
    if (boundary.dimension == 2 || vertex < boundary.dynamic_vertex_count)
      return model.marker_local_coordinates(static_cast<int>(vertex));
    const std::size_t k = 3 * (vertex - boundary.dynamic_vertex_count);
    return {boundary.static_positions[k], boundary.static_positions[k + 1],
            boundary.static_positions[k + 2]};
  };
  const auto& elements = boundary.elements();
  for (std::size_t e = 0; e + corners <= elements.size(); e += corners) {
    const mbd::BodyId body = body_of(elements[e]);
    BodySurface& surface = surfaces[body];
    surface.spec.body = body;
    surface.spec.name = body == mbd::kGround ? "ground" : model.body_name(body);
    for (int k = 0; k < corners; ++k) {
      const std::uint32_t vertex = elements[e + k];
      auto [found, added] =
          local_index.emplace(vertex, static_cast<int>(surface.spec.vertices.size()));
      if (added) surface.spec.vertices.push_back(place_of(vertex));
      surface.spec.elements.push_back(found->second);
    }
  }
  for (auto& [body, surface] : surfaces) {
    if (body == mbd::kGround) continue;
    Eigen::Vector3d low = surface.spec.vertices.front(), high = low;
    for (const Eigen::Vector3d& vertex : surface.spec.vertices) {
      low = low.cwiseMin(vertex);
      high = high.cwiseMax(vertex);
    }
    const Eigen::Vector3d extent = high - low;
    surface.smallest_extent = corners == 2 ? std::min(extent.x(), extent.y()) : extent.minCoeff();
  }
  return surfaces;
}

void add_contact(SceneBuilder& builder, const View& block, const BodySurface& a,
                 const BodySurface& b) {
  const mbd::Model& model = builder.model;
  auto mass_of = [&](const BodySurface& s) {
    return s.spec.body == mbd::kGround ? 0.0 : model.body_mass(s.spec.body);
  };
  const double heavier = std::max(mass_of(a), mass_of(b));
  double lighter = std::min(mass_of(a), mass_of(b));
  if (lighter == 0.0) lighter = heavier;
  double smallest = 0.0;
  for (const BodySurface* s : {&a, &b}) {
    if (s->smallest_extent > 0.0)
      smallest = smallest == 0.0 ? s->smallest_extent : std::min(smallest, s->smallest_extent);
  }
  const double tolerance =
      block.has("penetration_tolerance") ? block.number("penetration_tolerance") : 0.01 * smallest;
  if (!(tolerance > 0.0)) {
    throw Error("the meshes of '" + a.spec.name + "' and '" + b.spec.name +
                    "' have no extent to derive a penetration tolerance from",
                block.location().text(), "give penetration_tolerance = ... [m]");
  }
  const double weight = heavier * std::hypot(builder.scene.gravity[0], builder.scene.gravity[1],
                                             builder.scene.gravity[2]);
  if (!block.has("stiffness") && !(weight > 0.0)) {
    throw Error("without gravity the stiffness cannot follow from the weight",
                block.location().text(), "give stiffness = ... [N/m]");
  }
  mbd::ContactSpec spec;
  spec.name = name_of(block);
  if (spec.name.empty()) spec.name = a.spec.name + " on " + b.spec.name;
  spec.first = a.spec;
  spec.second = b.spec;
  spec.stiffness = block.has("stiffness") ? block.number("stiffness") : weight / tolerance;
  spec.damping = block.number("damping_ratio") * 2.0 * std::sqrt(spec.stiffness * lighter);
  spec.friction_coefficient = block.number("friction");
  spec.regularisation_speed = block.number("regularisation_speed");
  spec.depth_limit = block.has("depth_limit")
                         ? block.number("depth_limit")
                         : std::min(10.0 * tolerance, smallest > 0.0 ? 0.25 * smallest : 1e300);
  spec.damping_onset_depth = std::min(0.1 * tolerance, 0.5 * spec.depth_limit);
  builder.placed(block, [&] { builder.model.add_contact(spec); });
  builder.scene.contact_pairs.emplace_back(a.spec.body, b.spec.body);
}

void build_contacts(SceneBuilder& builder) {
  const auto blocks = builder.blocks("Contact");
  if (blocks.empty()) return;
  const std::map<mbd::BodyId, BodySurface> surfaces = surfaces_by_body(builder.scene);
  auto surface_of = [&](const View& block, std::string_view key) -> const BodySurface& {
    const std::string& name = block.string(key);
    const mbd::BodyId body = name == "ground" ? mbd::kGround : builder.find_body(block, key);
    const auto found = surfaces.find(body);
    if (found == surfaces.end()) {
      throw Error(
          (body == mbd::kGround ? std::string("the ground") : "body '" + name + "'") +
              " has no surface mesh to touch with",
          block.location(key).text(),
          body == mbd::kGround ? "add Ground { Mesh { ... } }" : "add a Mesh block to the body");
    }
    return found->second;
  };
  builder.each("Contact", [&](const View& block) {
    if (block.string("body_a") == "*") {
      for (auto a = surfaces.begin(); a != surfaces.end(); ++a) {
        for (auto b = std::next(a); b != surfaces.end(); ++b)
          add_contact(builder, block, a->second, b->second);
      }
      return;
    }
    const BodySurface& a = surface_of(block, "body_a");
    const BodySurface& b = surface_of(block, "body_b");
    add_contact(builder, block, a, b);
  });
}

}  // namespace

ElementFamily contact_family() {
  return {"contact", contact_blocks, {build_contacts}};
}

}  // namespace fsi::scene::detail
