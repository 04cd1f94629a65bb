// PointOnLine: a planar slider. Point b (on a RigidBody2D or the ground) stays on the line through
// point a along `axis` (fixed in a's body; in the world when a is the ground). One row,
//   C = (u x (r_b - r_a)) / |axis|,  u = R(phi_a) axis,
// the distance of b from the line; lambda is the normal force. Unlike PrismaticJoint the relative
// rotation stays free. The row is written here on the public model (coordinate indices), as any
// new family may write its own element.

#include <Eigen/Dense>

#include <cmath>
#include <memory>
#include <vector>

#include "fsi/common/error.hpp"
#include "fsi/mbd/constraint_element.hpp"
#include "scene_builder.hpp"

namespace fsi::scene::detail {
namespace {

// The planar cross product a_x b_y - a_y b_x and the quarter turn S a = dR/dphi R^T a.
double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}
Eigen::Vector2d quarter_turn(const Eigen::Vector2d& a) {
  return {-a.y(), a.x()};
}
Eigen::Vector2d rotated(double angle, const Eigen::Vector2d& a) {
  return Eigen::Rotation2Dd(angle) * a;
}

// A point of a planar rigid body, r = (x, y) + R(phi) local, or of the world (indices -1).
struct RigidPoint {
  int x = -1, y = -1, angle = -1;
  Eigen::Vector2d local = Eigen::Vector2d::Zero();

  bool on_ground() const { return angle < 0; }
  // R(phi) local: the point's offset from the centre of mass in the world.
  Eigen::Vector2d arm(const Eigen::VectorXd& q) const {
    return on_ground() ? Eigen::Vector2d::Zero() : rotated(q(angle), local);
  }
  Eigen::Vector2d position(const Eigen::VectorXd& q) const {
    return on_ground() ? local : Eigen::Vector2d(q(x), q(y)) + arm(q);
  }
};

struct Entry {
  int row, column;
  double value;
};

class PointOnLineRow final : public mbd::ConstraintElement {
 public:
  PointOnLineRow(std::string description, RigidPoint a, RigidPoint b, Eigen::Vector2d axis)
      : description_(std::move(description)), a_(a), b_(b), axis_(axis), length_(axis.norm()) {}

  std::string description() const override { return description_; }
  mbd::ConstraintLevel level() const override { return mbd::ConstraintLevel::Position; }
  double residual(double, const Eigen::VectorXd& q, const Eigen::VectorXd&) const override {
    return cross(direction(q), b_.position(q) - a_.position(q)) / length_;
  }
  void jacobian_row(double, const Eigen::VectorXd& q, mbd::RowRef row) const override {
    for (const Entry& entry : gradient(q))
      row(entry.column) += entry.value;
  }
  double explicit_time_derivative(double, const Eigen::VectorXd&) const override { return 0.0; }
  double acceleration_remainder(double, const Eigen::VectorXd& q,
                                const Eigen::VectorXd& v) const override {
    double remainder = 0.0;
    for (const Entry& entry : hessian(q))
      remainder += entry.value * v(entry.row) * v(entry.column);
    return remainder;
  }
  void add_force_derivative(double, const Eigen::VectorXd& q, double multiplier,
                            Eigen::MatrixXd& derivative) const override {
    for (const Entry& entry : hessian(q))
      derivative(entry.row, entry.column) += multiplier * entry.value;
  }

 private:
  // u = R(phi_a) axis: the line's direction in the world.
  Eigen::Vector2d direction(const Eigen::VectorXd& q) const {
    return a_.on_ground() ? axis_ : rotated(q(a_.angle), axis_);
  }

  // dC/dq: the translations of b and a move the point across the line, the angle of b turns its
  // arm, the angle of a turns the line and its point.
  std::vector<Entry> gradient(const Eigen::VectorXd& q) const {
    const Eigen::Vector2d u = direction(q);
    const Eigen::Vector2d d = b_.position(q) - a_.position(q);
    std::vector<Entry> entries;
    if (!b_.on_ground()) {
      entries.push_back({0, b_.x, -u.y() / length_});
      entries.push_back({0, b_.y, u.x() / length_});
      entries.push_back({0, b_.angle, cross(u, quarter_turn(b_.arm(q))) / length_});
    }
    if (!a_.on_ground()) {
      entries.push_back({0, a_.x, u.y() / length_});
      entries.push_back({0, a_.y, -u.x() / length_});
      entries.push_back(
          {0, a_.angle, (cross(quarter_turn(u), d) - cross(u, quarter_turn(a_.arm(q)))) / length_});
    }
    return entries;
  }

  // d^2C/dq^2, both triangles: u'' = -u, d r'' = -R p at each body's own angle; the only mixed
  // terms pair the angle of a (it turns u) with every coordinate of d.
  std::vector<Entry> hessian(const Eigen::VectorXd& q) const {
    const Eigen::Vector2d u = direction(q);
    const Eigen::Vector2d d = b_.position(q) - a_.position(q);
    std::vector<Entry> entries;
    auto symmetric = [&](int i, int j, double value) {
      entries.push_back({i, j, value / length_});
      if (i != j) entries.push_back({j, i, value / length_});
    };
    if (!b_.on_ground()) symmetric(b_.angle, b_.angle, -cross(u, b_.arm(q)));
    if (a_.on_ground()) return entries;
    const Eigen::Vector2d turned = quarter_turn(u);
    const Eigen::Vector2d arm_a = a_.arm(q);
    symmetric(a_.angle, a_.angle,
              -cross(u, d) - 2.0 * cross(turned, quarter_turn(arm_a)) + cross(u, arm_a));
    symmetric(a_.angle, a_.x, turned.y());
    symmetric(a_.angle, a_.y, -turned.x());
    if (b_.on_ground()) return entries;
    symmetric(a_.angle, b_.x, -turned.y());
    symmetric(a_.angle, b_.y, turned.x());
    symmetric(a_.angle, b_.angle, cross(turned, quarter_turn(b_.arm(q))));
    return entries;
  }

  std::string description_;
  RigidPoint a_, b_;
  Eigen::Vector2d axis_;
  double length_;
};

std::vector<BlockSpec> point_on_line_blocks() {
  return {releasable(
      block_spec("PointOnLine",
                 "A slider: point_b stays on the line through point_a along axis (body_a's "
                 "frame; the world's when body_a is absent), rotation free. 1 row, lambda the "
                 "normal force; a joint_force sensor reads the force on body_b (on body_a "
                 "when body_b is the ground).",
                 {element_name_spec(),
                  text("body_a", "name of a RigidBody2D; absent: the ground").optional(),
                  vector("point_a", 2, "m", "point on the line: body_a coordinates or world")
                      .with_default({0.0, 0.0}),
                  text("body_b", "name of a RigidBody2D; absent: the ground").optional(),
                  vector("point_b", 2, "m", "the sliding point: body_b coordinates or world")
                      .with_default({0.0, 0.0}),
                  vector("axis", 2, "", "line direction, body_a's frame (world without body_a)")
                      .with_default({1.0, 0.0})})
          .as_list()
          .planar())};
}

RigidPoint rigid_point(SceneBuilder& builder, const View& element, const std::string& side) {
  RigidPoint point;
  const auto local = element.vector("point_" + side);
  point.local = {local[0], local[1]};
  if (!element.has("body_" + side)) return point;
  const mbd::BodyId body = builder.find_body(element, "body_" + side);
  if (builder.model.is_beam(body)) {
    throw Error("body_" + side + " '" + element.string("body_" + side) + "' is an AncfBeam2D",
                element.location("body_" + side).text(),
                "connect RigidBody2D bodies (or the ground) with a PointOnLine");
  }
  point.x = builder.model.coordinate_index(body, mbd::Coordinate::X);
  point.y = builder.model.coordinate_index(body, mbd::Coordinate::Y);
  point.angle = builder.model.coordinate_index(body, mbd::Coordinate::Angle);
  return point;
}

void build_point_on_line(SceneBuilder& builder, const View& slider) {
  const RigidPoint a = rigid_point(builder, slider, "a");
  const RigidPoint b = rigid_point(builder, slider, "b");
  if (a.on_ground() && b.on_ground()) {
    throw Error("both points of the PointOnLine are on the ground", slider.location().text(),
                "give body_a or body_b");
  }
  if (!a.on_ground() && a.angle == b.angle) {
    throw Error("both points of the PointOnLine are on the same body",
                slider.location("body_b").text(), "connect two different bodies");
  }
  const auto axis = slider.vector("axis");
  const Eigen::Vector2d direction(axis[0], axis[1]);
  if (!(direction.norm() > 0.0) || !std::isfinite(direction.norm())) {
    throw Error("the axis must be a finite, non-zero vector", slider.location("axis").text(),
                "give e.g. axis = [1, 0]");
  }
  const std::string name = name_of(slider);
  const int row = builder.model.add_constraint_element(std::make_unique<PointOnLineRow>(
      "point on line" + (name.empty() ? "" : " '" + name + "'"), a, b, direction));
  const mbd::BodyId measured =
      builder.model.find_body(slider.string(b.on_ground() ? "body_a" : "body_b"));
  builder.register_joint(slider, {row, 1, measured, "point on line"});
}

void build_points_on_lines(SceneBuilder& builder) {
  builder.each("PointOnLine", [&](const View& slider) { build_point_on_line(builder, slider); });
}

}  // namespace

ElementFamily point_on_line_family() {
  return {"point on line (slider)", point_on_line_blocks, {build_points_on_lines}};
}

}  // namespace fsi::scene::detail
