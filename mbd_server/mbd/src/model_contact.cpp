// Model::add_contact: checks a ContactSpec and builds the planar or spatial mesh contact
// (src/mesh_contact.hpp).

#include <cmath>
#include <memory>
#include <string>

#include "ancf_cable_3d.hpp"
#include "fsi/common/error.hpp"
#include "fsi/mbd/model.hpp"
#include "mesh_contact.hpp"
#include "model_data.hpp"

namespace fsi::mbd {
namespace {

void check_law(const ContactSpec& spec, const std::string& user) {
  std::string problems;
  auto finite = [](double x) { return std::isfinite(x); };
  if (!(spec.stiffness > 0.0) || !finite(spec.stiffness)) problems += " stiffness <= 0;";
  if (!(spec.damping >= 0.0) || !finite(spec.damping)) problems += " damping < 0;";
  if (!(spec.friction_coefficient >= 0.0) || !finite(spec.friction_coefficient))
    problems += " friction coefficient < 0;";
  if (spec.friction_coefficient > 0.0 &&
      (!(spec.regularisation_speed > 0.0) || !finite(spec.regularisation_speed)))
    problems += " regularisation speed <= 0;";
  if (!(spec.depth_limit > 0.0) || !finite(spec.depth_limit)) problems += " depth limit <= 0;";
  if (!(spec.damping_onset_depth >= 0.0) || !(spec.damping_onset_depth < spec.depth_limit))
    problems += " damping onset depth outside [0, depth limit);";
  if (problems.empty()) return;
  problems.pop_back();
  throw Error("invalid parameters:" + problems, user,
              "give a finite positive stiffness and depth limit, non-negative damping and "
              "friction coefficient, and a positive regularisation speed with friction");
}

// The element indices of a surface, D per element, in range and not degenerate.
template <int D>
std::vector<std::array<int, D>> surface_elements(const ContactSurfaceSpec& surface,
                                                 const std::string& user) {
  const std::string which = "surface '" + surface.name + "'";
  if (surface.vertices.empty() || surface.elements.empty()) {
    throw Error(which + " has no " + (D == 2 ? "segments" : "triangles"), user,
                "give each side of a contact a mesh");
  }
  if (surface.elements.size() % D != 0) {
    throw Error(which + ": " + std::to_string(surface.elements.size()) +
                    " element indices are not a multiple of " + std::to_string(D),
                user, "give " + std::to_string(D) + " vertex indices per element");
  }
  for (const Eigen::Vector3d& vertex : surface.vertices) {
    if (!vertex.allFinite())
      throw Error(which + " has a vertex that is not finite", user, "give finite coordinates");
  }
  std::vector<std::array<int, D>> elements(surface.elements.size() / D);
  const int count = static_cast<int>(surface.vertices.size());
  for (std::size_t e = 0; e < elements.size(); ++e) {
    for (int k = 0; k < D; ++k) {
      const int index = surface.elements[e * D + k];
      if (index < 0 || index >= count) {
        throw Error(which + ": element " + std::to_string(e) + " refers to vertex " +
                        std::to_string(index) + " of " + std::to_string(count),
                    user, "refer to vertices 0.." + std::to_string(count - 1));
      }
      elements[e][k] = index;
    }
    const Eigen::Vector3d& a = surface.vertices[elements[e][0]];
    const Eigen::Vector3d& b = surface.vertices[elements[e][1]];
    const double size = D == 2 ? (b - a).head<2>().norm()
                               : (b - a).cross(surface.vertices[elements[e][D - 1]] - a).norm();
    if (!(size > 0.0)) {
      throw Error(which + ": element " + std::to_string(e) + " is degenerate (" +
                      (D == 2 ? "zero length" : "zero area") + ")",
                  user, "remove repeated points from the mesh");
    }
  }
  return elements;
}

}  // namespace

int Model::add_contact(const ContactSpec& spec) {
  const int index = force_element_count();
  const std::string user = detail::element_name("contact", spec.name, index);
  check_law(spec, user);
  if (spec.first.body == spec.second.body) {
    throw Error(spec.first.body == kGround ? "both surfaces are on the ground"
                                           : "both surfaces are on the same body",
                user, "let a contact act between two bodies, or a body and the ground");
  }
  const detail::ContactLaw law{spec.stiffness,
                               spec.damping,
                               spec.friction_coefficient,
                               spec.regularisation_speed,
                               spec.depth_limit,
                               spec.damping_onset_depth};
  if (dimension() == 3) {
    auto build = [&](const ContactSurfaceSpec& given) {
      detail::ContactSurface<detail::SpatialPoint, 3> surface;
      surface.name = given.name;
      surface.elements = surface_elements<3>(given, user);
      if (given.body != kGround && is_cable(given.body)) {
        throw Error("surface '" + given.name +
                        "' is on a cable, whose tube vertices are not "
                        "material points",
                    user, "let contact act on rigid bodies and the ground");
      }
      for (const Eigen::Vector3d& vertex : given.vertices)
        surface.vertices.push_back(data_->spatial_point({given.body, vertex}, user));
      surface.normal_signs.assign(surface.elements.size(),
                                  detail::spatial_outward_sign(given.vertices, surface.elements));
      return surface;
    };
    add_force_element(std::make_unique<detail::SpatialMeshContact>(user, build(spec.first),
                                                                   build(spec.second), law));
    return index;
  }
  auto build = [&](const ContactSurfaceSpec& given) {
    detail::ContactSurface<detail::BodyPoint, 2> surface;
    surface.name = given.name;
    surface.elements = surface_elements<2>(given, user);
    for (const Eigen::Vector3d& vertex : given.vertices)
      surface.vertices.push_back(data_->point({given.body, vertex.head<2>()}, user));
    surface.normal_signs = detail::planar_outward_signs(given.vertices, surface.elements);
    return surface;
  };
  add_force_element(std::make_unique<detail::PlanarMeshContact>(user, build(spec.first),
                                                                build(spec.second), law));
  return index;
}

}  // namespace fsi::mbd
