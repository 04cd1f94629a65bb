// Where the probes that move with a body are (docs/user-guide.md, "Probes that move with a
// body"): a rigid body's motion from its initial configuration, applied to the probe's
// declaration in the initial configuration.

#include <cmath>

#include "fsi/mbd/readouts.hpp"
#include "fsi/scene/scene.hpp"

namespace fsi::scene {
namespace {

// The placement of `body` in `state` relative to `initial`, the model's initial configuration
// (copied once per placed_probes call, not once per probe).
probes::RigidPlacement placement_since(const mbd::Model& model, const mbd::State& initial,
                                       const mbd::State& state, mbd::BodyId body) {
  Eigen::Matrix3d turn = Eigen::Matrix3d::Identity();
  Eigen::Vector3d origin_then, origin_now;
  if (model.dimension() == 2) {
    // The body frame's origin and x axis, then and now.
    const mbd::BodyPointSpec origin{body, Eigen::Vector2d::Zero()};
    const mbd::BodyPointSpec unit_x{body, Eigen::Vector2d::UnitX()};
    origin_then = mbd::point_position(model, initial, origin);
    origin_now = mbd::point_position(model, state, origin);
    const Eigen::Vector3d axis_then = mbd::point_position(model, initial, unit_x) - origin_then;
    const Eigen::Vector3d axis_now = mbd::point_position(model, state, unit_x) - origin_now;
    const double angle =
        std::atan2(axis_now.y(), axis_now.x()) - std::atan2(axis_then.y(), axis_then.x());
    turn.topLeftCorner<2, 2>() << std::cos(angle), -std::sin(angle), std::sin(angle),
        std::cos(angle);
  } else {
    const mbd::SpatialPointSpec origin{body, Eigen::Vector3d::Zero()};
    origin_then = mbd::point_position(model, initial, origin);
    origin_now = mbd::point_position(model, state, origin);
    turn =
        mbd::orientation(model, state, body) * mbd::orientation(model, initial, body).transpose();
  }
  const Eigen::Vector3d shift = origin_now - turn * origin_then;
  probes::RigidPlacement placement;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j)
      placement.rotation[static_cast<std::size_t>(3 * i + j)] = turn(i, j);
    placement.translation[static_cast<std::size_t>(i)] = shift(i);
  }
  return placement;
}

}  // namespace

probes::RigidPlacement rigid_placement(const mbd::Model& model, const mbd::State& state,
                                       mbd::BodyId body) {
  return placement_since(model, model.initial_configuration(), state, body);
}

std::vector<probes::ProbeDefinition> placed_probes(const Scene& scene, const mbd::State& state) {
  std::vector<probes::ProbeDefinition> placed;
  placed.reserve(scene.attached_probes.size());
  if (scene.attached_probes.empty()) return placed;
  const mbd::State initial = scene.model.initial_configuration();
  for (const AttachedProbe& attached : scene.attached_probes) {
    placed.push_back(probes::placed(scene.probes[attached.probe],
                                    placement_since(scene.model, initial, state, attached.body)));
  }
  return placed;
}

}  // namespace fsi::scene
