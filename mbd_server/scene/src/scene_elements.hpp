#pragma once
// Scene blocks of the 2D connectors, force elements and time-dependent loads beyond the
// revolute joint, rod and linear spring (internal to the scene builder): their declarations and
// how they become model elements. Named elements are recorded for the sensors.

#include <functional>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "fsi/mbd/model.hpp"
#include "fsi/scene/schema.hpp"

namespace fsi::scene::detail {

// A joint's rows and the body its reaction is measured on (a joint_force sensor).
struct NamedJoint {
  int first_row = 0;
  int rows = 0;
  mbd::BodyId body = mbd::kGround;
  std::string kind;  // "prismatic joint", for units and messages
};

struct NamedElements {
  std::map<std::string, NamedJoint> joints;
  std::map<std::string, int> force_elements;  // index among the model's force elements
  std::map<std::string, bool> rotational;     // force element measures a torque
};

// What the builders need from build_scene.
struct ElementBuilder {
  mbd::Model& model;
  NamedElements& names;
  // Runs one element's construction: a value in error skips it, an fsi::Error becomes a problem
  // at the element.
  std::function<void(const SourceLocation&, const std::function<void()>&)> guard;
  std::function<mbd::BodyId(const View&, std::string_view)> find_body;
  // point_a / point_b of a two-point element (side "a" or "b"; no body_b: the ground).
  std::function<mbd::BodyPointSpec(const View&, const std::string&)> point;
  // The model's messages get the element's place.
  std::function<void(const View&, const std::function<void()>&)> placed;
  // Records a problem at a place.
  std::function<void(const SourceLocation&, const std::string&, const std::string&)> problem;
  // SolverOptions.end_time: prescribed motions are checked over [0, end_time].
  double end_time = 0.0;
};

class RuntimeExpression;

// The coordinate a scene names: "x", "y", or the angle ("angle", or "torque" for forces).
mbd::Coordinate coordinate_of(const std::string& text);
// An expression of the scene compiled for the model in the named variables; a mistake becomes a
// problem at its key.
RuntimeExpression expression(const View& element, std::string_view key,
                             const std::vector<std::string>& variables);

// The new blocks, in the order they appear in docs/parameters.md.
std::vector<BlockSpec> element_block_specs();
// The optional `name` of an element block, the same declaration everywhere.
ParameterSpec element_name_spec();

// Builds every new block of the scene root into the model.
void build_elements(const View& root, ElementBuilder& builder);

// Registers a named element: a second use of the name is a problem at `where`.
void register_joint(ElementBuilder& builder, const View& element, NamedJoint joint);
void register_force_element(ElementBuilder& builder, const View& element, int index,
                            bool rotational);

}  // namespace fsi::scene::detail
