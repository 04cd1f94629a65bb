#pragma once
// Scene blocks of the spatial (3D) multibody model (internal to the scene builder):
// RigidBody3D (with STL meshes in its body frame), PointMass, AncfCable3D (with a tube mesh),
// CableClamp, SphericalJoint, RevoluteJoint3D, FixedJoint3D, DistanceConstraint3D. Their
// declarations and how they become model elements, markers and boundary triangles.

#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "fsi/scene/fluid_region.hpp"
#include "fsi/scene/scene.hpp"
#include "fsi/scene/schema.hpp"
#include "scene_elements.hpp"

namespace fsi::scene::detail {

// The spatial blocks, in the order they appear in docs/parameters.md.
std::vector<BlockSpec> spatial_block_specs();
// Their names: a planar scene refuses them at their place.
std::vector<std::string> spatial_block_names();

struct SpatialBodyBuilder {
  mbd::Model& model;
  BoundaryMesh& boundary;
  std::function<void(const SourceLocation&, const std::function<void()>&)> guard;
  std::function<void(const SourceLocation&, const std::string&, const std::string&)> problem;
  // The STL file named by a key, relative to the scene; a problem at the key when unreadable.
  std::function<std::optional<TriangleMesh>(const View&, std::string_view)> read_stl;
  std::vector<std::string>& skipped_bodies;  // bodies not built for a value in error
  bool& unnamed_body_skipped;
};

// The bodies of a 3D scene with their meshes: model markers (dynamic boundary vertices) and
// triangles. Runs before the ground meshes, whose vertices follow the dynamic ones.
void build_spatial_bodies(const View& root, SpatialBodyBuilder& builder);
// The spatial connectors (after every body exists).
void build_spatial_connectors(const View& root, ElementBuilder& builder);

}  // namespace fsi::scene::detail
