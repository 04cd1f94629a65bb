#pragma once
// The scene builder and its unit of extension (internal to fsi::scene).
//
// An element family is one file (family_*.cpp) that declares its blocks once (BlockSpec, with
// the dimension each block belongs to) and builds them into the scene through a SceneBuilder.
// The registry (family_registry.cpp) lists the families, one line each, in the order they are
// built and documented: bodies before the meshes on them, every body before the joints and
// springs that name it, joints and springs before the sensors that read them.

#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Dense>

#include "family_assembly.hpp"
#include "fsi/mbd/model.hpp"
#include "fsi/scene/fluid_region.hpp"
#include "fsi/scene/scene.hpp"
#include "fsi/scene/schema.hpp"

namespace fsi::scene::detail {

// A joint's rows and the body its reaction is measured on (a joint_force sensor).
struct NamedJoint {
  int first_row = 0;
  int rows = 0;
  mbd::BodyId body = mbd::kGround;
  std::string kind;    // "prismatic joint", for units and messages
  bool drive = false;  // a driven RevoluteJoint3D: its last row is the drive (component torque)
  // body is an AncfBeam2D: the beam point [s, eta] the joint acts at (a BeamClamp's node, a
  // pin's point_a); joint_force reads the torque about it.
  std::optional<std::array<double, 2>> beam_point = std::nullopt;
};

struct NamedElements {
  std::map<std::string, NamedJoint> joints;
  std::map<std::string, int> force_elements;  // index among the model's force elements
  std::map<std::string, bool> rotational;     // force element measures a torque
  // A named Ground block: its meshes' elements, as [first, end) ranges of the boundary mesh's
  // elements (a WallPressureProbe's `mesh` may name it).
  std::map<std::string, std::vector<std::pair<std::uint32_t, std::uint32_t>>> ground_meshes;
};

class SceneBuilder;
class RuntimeExpression;

struct ElementFamily {
  std::string_view name;  // "planar joints", for the README and messages of the registry
  std::vector<BlockSpec> (*blocks)();
  // Run in this order: the order of the model's rows and force elements, which sensors read by
  // index.
  std::vector<void (*)(SceneBuilder& builder)> build_steps;
};

// Every family, in build and documentation order.
const std::vector<ElementFamily>& element_families();

// What a family needs while it builds: the scene, the problem list, and the look-ups that turn a
// name in the file into a model element. Problems are collected, never thrown: a scene reports
// all of them at once.
class SceneBuilder {
 public:
  SceneBuilder(Scene& scene, const View& root, SceneMode mode, std::vector<Problem>& problems);

  // Runs the families of the registry; afterwards `problems` holds everything found.
  void build();

  Scene& scene;
  mbd::Model& model;
  const View& root;
  const SceneMode mode;
  const int dimension;
  const std::filesystem::path scene_dir;
  NamedElements names;
  double end_time = 0.0;  // SolverOptions.end_time: prescribed motions are checked over it

  bool spatial() const { return dimension == 3; }
  // The blocks of that name that belong to this scene's dimension (the others are refused at
  // their place by the builder).
  std::vector<View> blocks(std::string_view name) const;
  // Builds every block of that name (of this scene's dimension) by `build`, each inside guard();
  // a block's `release_time` (releasable()) then releases the constraint rows it added.
  void each(std::string_view name, const std::function<void(const View&)>& build);
  // Runs one element's construction: a value in error skips it, an fsi::Error becomes a problem
  // at the element (or at the error's own place). False when it did either.
  bool guard(const SourceLocation& element, const std::function<void()>& step);
  // Was the element of this name (a joint, spring, ...) skipped by each() for a reported problem?
  // A sensor naming it is then skipped too, not told the name does not exist.
  bool element_skipped(const std::string& name) const;
  void problem(const SourceLocation& where, const std::string& message, const std::string& fix);
  void problem(Problem found);
  // The block whose element added constraint row `row` (the innermost guarded step that did), or
  // nullptr: the model's messages about a row can then point at the scene's line.
  const SourceLocation* owner_of_row(int row) const;
  // The Assembly block's request (family_assembly.hpp), taken after every element is built.
  std::optional<AssemblyRequest> assembly;
  // Has an element been skipped for a value in error (reported already)?
  bool skipped_any() const { return skipped_any_; }

  // A body, added by `add` (the model's fsi::Error becomes a problem at its name; nullopt: `add`
  // reported its own problem): a body that fails is remembered by name, so that the elements
  // naming it are skipped instead of reported again.
  std::optional<mbd::BodyId> add_body(const View& element,
                                      const std::function<std::optional<mbd::BodyId>()>& add);
  // The body an element names at `key`; a skipped body skips the element too.
  mbd::BodyId find_body(const View& element, std::string_view key);
  // point_a / point_b of a planar two-point element (no body_b: a point of the world).
  mbd::BodyPointSpec point(const View& element, const std::string& side);
  // The same for a spatial two-point element.
  mbd::SpatialPointSpec point3(const View& element, const std::string& side);
  // The model's messages name no place: runs `add` and gives its errors the element's.
  void placed(const View& element, const std::function<void()>& add);
  // A joint or force element a sensor may name; a second use of the name is a problem.
  void register_joint(const View& element, NamedJoint joint);
  void register_force_element(const View& element, int index, bool rotational);
  // placed(add) and register what it added: `add` returns the first row of the joint (the
  // joint's first_row is filled in) or the index of the force element.
  void add_joint(const View& element, const std::function<int()>& add, NamedJoint joint);
  void add_force_element(const View& element, const std::function<int()>& add, bool rotational);

  // A file named at `where`: relative to the folder of the scene file that names it (an
  // included file's own), or to the top-level scene's for a --set; unless absolute.
  std::filesystem::path scene_relative(const SourceLocation& where, const std::string& name) const;
  // The STL file named at `key` (scene_relative); a problem at the key when unreadable.
  std::optional<TriangleMesh> read_stl(const View& block, std::string_view key);
  // The expression at `key` compiled for the model in the named variables; its other names are
  // the scene's numbers by their path from the top (scene_number). A mistake is an fsi::Error at
  // the key.
  RuntimeExpression expression(const View& element, std::string_view key,
                               const std::vector<std::string>& variables) const;
  // A vector of `components` values (the scene's dimension); absent: zeros.
  std::optional<std::vector<double>> dimension_vector(const View& block, std::string_view key,
                                                      int components);

 private:
  // Is the element named, with a name no other joint or spring has? A taken name is a problem.
  bool name_is_free(const View& element);

  struct RowOwner {
    SourceLocation where;
    int first_row = 0, rows = 0;
  };

  std::vector<Problem>& problems_;
  std::vector<RowOwner> row_owners_;
  bool skipped_any_ = false;
  std::vector<std::string> skipped_bodies_;    // bodies not built for a value in error
  std::vector<std::string> skipped_elements_;  // named elements each() skipped (reported)
  bool unnamed_body_skipped_ = false;          // a body whose name is in error: its name is unknown
};

// Helpers the families share.
// The optional `name` of an element block, the same declaration everywhere.
ParameterSpec element_name_spec();
// A constraint block with the key `release_time`, declared once for every constraint family:
// its rows hold until then and are removed from then on (mbd::Model::set_release_time).
BlockSpec releasable(BlockSpec constraint_block);
std::vector<BlockSpec> releasable(std::vector<BlockSpec> constraint_blocks);
std::string name_of(const View& element);  // "" when unnamed
std::optional<double> optional_number(const View& element, std::string_view key);
// The coordinate a scene names: "x", "y", or the angle ("angle", or "torque" for forces).
mbd::Coordinate coordinate_of(const std::string& text);
// The doc of a block holding runtime expressions (SceneBuilder::expression): `text` and what
// else its expressions may name.
std::string with_scene_numbers(std::string text);

// When a prescribed motion's rate is checked against its position (mbd::PrescribedMotionSpec::
// check_times): t = 0 and 200 times across [0, end_time], off the round fractions of end_time
// where a drive's pieces tend to meet (a user's rate wrong for 0.5 < t < 2.5 s of a 30 s spin-up
// passed the 11 samples once taken every 3 s, and its index-2 run went wrong unseen).
std::vector<double> prescribed_motion_check_times(double end_time);

// A vector of the scene's dimension (2 or 3 components): the builder checks its length.
ParameterSpec per_dimension(ParameterSpec spec);
// body_a/point_a and body_b/point_b of a planar two-point element (body_b absent: point_b is a
// point of the world), then `more`. `on_beams`: the bodies may be AncfBeam2D ([s, eta] points).
std::vector<ParameterSpec> planar_two_points(std::vector<ParameterSpec> more, bool on_beams);
// The same for spatial bodies; `spatial_point` declares one point key ("point" for side "").
ParameterSpec spatial_point(const std::string& side, const std::string& doc);
std::vector<ParameterSpec> spatial_two_points(std::vector<ParameterSpec> more);
Eigen::Vector3d vector3(const View& element, std::string_view key);
// A 2D polyline mesh on a body (or the ground): model markers and boundary segments.
void add_polyline_mesh(SceneBuilder& builder, const View& mesh, mbd::BodyId body);

}  // namespace fsi::scene::detail
