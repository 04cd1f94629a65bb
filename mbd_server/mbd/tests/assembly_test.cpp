// Initial assembly (fsi/mbd/assembly.hpp): closed loops given with every angle off by 1e-3 rad
// close to |C| <= 1e-12, keep the driving coordinate, project the velocities, run to the same
// motion as from the exact configuration, and an open loop is refused naming its joints.
#include "fsi/mbd/assembly.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "fsi/common/error.hpp"
#include "fsi/mbd/integrator.hpp"
#include "fsi/mbd/model.hpp"

namespace fsi::mbd {
namespace {

Eigen::Vector2d left_normal(const Eigen::Vector2d& direction) {
  return Eigen::Vector2d(-direction.y(), direction.x()).normalized();
}

// The intersection of two circles left of the line first -> second (the upper branch of the
// mechanisms below), from the exact triangle: the reference configuration to round-off.
Eigen::Vector2d circles_meet(const Eigen::Vector2d& first, double first_radius,
                             const Eigen::Vector2d& second, double second_radius) {
  const Eigen::Vector2d line = second - first;
  const double distance = line.norm();
  const double along =
      (first_radius * first_radius - second_radius * second_radius + distance * distance) /
      (2.0 * distance);
  const double across_squared = first_radius * first_radius - along * along;
  EXPECT_GT(across_squared, 0.0) << "the test mechanism cannot close";
  return first + along * line / distance + std::sqrt(across_squared) * left_normal(line);
}

// A rigid link through its joint points (world, exact): centre of mass at their mean, angle
// along the first two. `angle_error` turns the given angle, keeping the centre and the points'
// body coordinates: the user's approximate configuration.
struct Link {
  std::string name;
  std::vector<Eigen::Vector2d> points;
  double angle_error = 0.0;
};

struct Joint {
  std::string name;
  int link_a = 0;  // index into the links
  int point_a = 0;
  int link_b = -1;  // -1: the ground point `ground`
  int point_b = 0;
  Eigen::Vector2d ground = Eigen::Vector2d::Zero();
};

struct Mechanism {
  Model model;
  std::vector<BodyId> bodies;
};

Eigen::Vector2d centre_of(const Link& link) {
  Eigen::Vector2d sum = Eigen::Vector2d::Zero();
  for (const auto& point : link.points)
    sum += point;
  return sum / static_cast<double>(link.points.size());
}

double angle_of(const Link& link) {
  const Eigen::Vector2d along = link.points[1] - link.points[0];
  return std::atan2(along.y(), along.x());
}

Eigen::Vector2d local_of(const Link& link, int point) {
  return Eigen::Rotation2Dd(-angle_of(link)) * (link.points[point] - centre_of(link));
}

// Links of mass 1 kg/m per metre of their longest extent; the first link (the crank) turns at
// `crank_rate` about its first point, the others are at rest (consistent only for rate 0).
Mechanism build(const std::vector<Link>& links, const std::vector<Joint>& joints,
                double crank_rate = 0.0) {
  Mechanism mechanism;
  mechanism.model.set_gravity({0.0, -9.81});
  for (std::size_t k = 0; k < links.size(); ++k) {
    const Link& link = links[k];
    RigidBody2DSpec spec;
    spec.name = link.name;
    double extent = 0.0;
    for (const auto& point : link.points)
      extent = std::max(extent, (point - centre_of(link)).norm());
    spec.mass = 2.0 * extent;
    spec.inertia = spec.mass * extent * extent / 3.0;
    spec.position = centre_of(link);
    spec.angle = angle_of(link) + link.angle_error;
    if (k == 0) {
      spec.angular_velocity = crank_rate;
      spec.velocity = crank_rate * left_normal(centre_of(link) - link.points[0]) *
                      (centre_of(link) - link.points[0]).norm();
    }
    mechanism.bodies.push_back(mechanism.model.add_rigid_body(spec));
  }
  for (const Joint& joint : joints) {
    const BodyPointSpec a{mechanism.bodies[joint.link_a],
                          local_of(links[joint.link_a], joint.point_a)};
    const BodyPointSpec b = joint.link_b < 0
                                ? BodyPointSpec{kGround, joint.ground}
                                : BodyPointSpec{mechanism.bodies[joint.link_b],
                                                local_of(links[joint.link_b], joint.point_b)};
    mechanism.model.add_revolute_joint(a, b, joint.name);
  }
  return mechanism;
}

// Crank-rocker four-bar: ground pivots O1 = 0 and O2 = (0.4, 0), crank 0.1 m at `crank`,
// coupler 0.35 m, rocker 0.3 m.
struct FourBar {
  std::vector<Link> links;
  std::vector<Joint> joints;
};

FourBar four_bar(double crank, double coupler_length = 0.35, double rocker_length = 0.3) {
  const Eigen::Vector2d o1(0.0, 0.0), o2(0.4, 0.0);
  const Eigen::Vector2d a = o1 + 0.1 * Eigen::Vector2d(std::cos(crank), std::sin(crank));
  FourBar mechanism;
  if (coupler_length + rocker_length > (o2 - a).norm()) {
    const Eigen::Vector2d b = circles_meet(o2, rocker_length, a, coupler_length);
    mechanism.links = {{"crank", {o1, a}}, {"coupler", {a, b}}, {"rocker", {o2, b}}};
  } else {
    // Links that cannot reach: laid out towards each other, the gap left at B.
    const Eigen::Vector2d towards = (o2 - a).normalized();
    mechanism.links = {{"crank", {o1, a}},
                       {"coupler", {a, a + coupler_length * towards}},
                       {"rocker", {o2, o2 - rocker_length * towards}}};
  }
  mechanism.joints = {
      {"O1", 0, 0, -1, 0, o1}, {"A", 0, 1, 1, 0}, {"B", 1, 1, 2, 1}, {"O2", 2, 0, -1, 0, o2}};
  return mechanism;
}

// Watt six-bar (five moving links, seven revolute joints, one degree of freedom): the four-bar
// above with a ternary coupler (A, B, E) and a ternary rocker (O2, B, F), and the dyad E-G-F.
FourBar watt_six_bar(double crank) {
  FourBar base = four_bar(crank);
  const Eigen::Vector2d a = base.links[1].points[0], b = base.links[1].points[1];
  const Eigen::Vector2d o2 = base.links[2].points[0];
  const Eigen::Vector2d e = a + 0.5 * (b - a) + 0.15 * left_normal(b - a);
  const Eigen::Vector2d f = o2 + 1.3 * (b - o2) + 0.05 * left_normal(b - o2);
  const Eigen::Vector2d g = circles_meet(f, 0.25, e, 0.3);
  base.links[1].points.push_back(e);
  base.links[2].points.push_back(f);
  base.links.push_back({"link_eg", {e, g}});
  base.links.push_back({"link_fg", {f, g}});
  base.joints.push_back({"E", 1, 2, 3, 0});
  base.joints.push_back({"F", 2, 2, 4, 0});
  base.joints.push_back({"G", 3, 1, 4, 1});
  return base;
}

// Every link's angle off by 1e-3 rad (alternating signs) except the crank's, which is driving.
std::vector<Link> off_by_a_milliradian(std::vector<Link> links) {
  for (std::size_t k = 1; k < links.size(); ++k)
    links[k].angle_error = (k % 2 == 1 ? 1.0 : -1.0) * 1e-3;
  return links;
}

double position_residual(const Model& model, const State& state) {
  Eigen::VectorXd residual;
  model.constraint_residual(state.time, state.q, state.v, residual);
  return residual.lpNorm<Eigen::Infinity>();
}

State run(const Model& model, State state, int steps, double step_size) {
  RadauIIA integrator(3);
  for (int n = 0; n < steps; ++n)
    integrator.step(model, state, step_size);
  return state;
}

// Assembles the approximate mechanism with the crank angle driving, checks the acceptance
// numbers, and returns the largest difference of q after 0.3 s against the exact start.
void expect_assembles_and_runs_like_exact(const FourBar& exact_geometry, const char* label) {
  Mechanism exact = build(exact_geometry.links, exact_geometry.joints);
  Mechanism approximate = build(off_by_a_milliradian(exact_geometry.links), exact_geometry.joints);
  Model& model = approximate.model;
  EXPECT_THROW((void)model.initial_state(), Error) << "the perturbed start must be inconsistent";

  const State given = model.initial_configuration();
  AssemblyOptions options;
  options.driving_coordinates = {model.coordinate_index(approximate.bodies[0], Coordinate::Angle)};
  const AssemblyReport report = assemble(model, given, options);
  const int crank_angle = options.driving_coordinates[0];

  EXPECT_LE(report.position_residual, 1e-12) << label;
  EXPECT_LE(position_residual(model, report.state), 1e-12) << label;
  EXPECT_EQ(report.state.q(crank_angle), given.q(crank_angle)) << label << ": driving moved";
  const State exact_start = exact.model.initial_state();
  const double configuration_error = (report.state.q - exact_start.q).lpNorm<Eigen::Infinity>();
  EXPECT_LE(configuration_error, 1e-12) << label;
  ASSERT_EQ(report.bodies.size(), exact_geometry.links.size());
  EXPECT_EQ(report.bodies[0].largest_position_change, 0.0) << label << ": the crank is driving";
  for (std::size_t k = 1; k < report.bodies.size(); ++k) {
    // Each link turned back by its 1e-3 rad; its centre moves less than that times its size.
    EXPECT_NEAR(report.bodies[k].largest_position_change, 1e-3, 1e-6)
        << label << " " << report.bodies[k].name;
    EXPECT_EQ(report.bodies[k].position_coordinate, "coordinate angle");
  }

  model.set_initial_configuration(report.state.q, report.state.v);
  const State assembled_start = model.initial_state();  // checked and multipliers made consistent
  const State from_assembled = run(model, assembled_start, 300, 1e-3);
  const State from_exact = run(exact.model, exact_start, 300, 1e-3);
  const double q_difference = (from_assembled.q - from_exact.q).lpNorm<Eigen::Infinity>();
  const double v_difference = (from_assembled.v - from_exact.v).lpNorm<Eigen::Infinity>();
  std::printf(
      "%s: %d Gauss-Newton steps, |C| = %.3g, start off exact by %.3g, after 0.3 s "
      "|dq| = %.3g, |dv| = %.3g, crank turned %.6f rad\n",
      label, report.iterations, report.position_residual, configuration_error, q_difference,
      v_difference, from_exact.q(crank_angle) - exact_start.q(crank_angle));
  EXPECT_LE(q_difference, 1e-10) << label;
  EXPECT_LE(v_difference, 1e-9) << label;
  EXPECT_GT(std::abs(from_exact.q(crank_angle) - exact_start.q(crank_angle)), 0.05)
      << label << ": the mechanism must move for the comparison to mean anything";
}

TEST(MbdAssembly, FourBarOffByAMilliradianClosesAndRunsLikeTheExactOne) {
  expect_assembles_and_runs_like_exact(four_bar(0.7), "four-bar");
}

TEST(MbdAssembly, WattSixBarOfFiveLinksClosesAndRunsLikeTheExactOne) {
  expect_assembles_and_runs_like_exact(watt_six_bar(0.7), "Watt six-bar");
}

// The velocities of the driven crank's mechanism: given the crank rate only, the assembly
// projects the others onto G v = 0; they match the derivative of the exact construction.
TEST(MbdAssembly, VelocitiesAreProjectedKeepingTheDrivingRate) {
  const double crank = 0.7, rate = 2.0;
  const FourBar geometry = watt_six_bar(crank);
  Mechanism mechanism = build(off_by_a_milliradian(geometry.links), geometry.joints, rate);
  Model& model = mechanism.model;
  AssemblyOptions options;
  const int crank_angle = model.coordinate_index(mechanism.bodies[0], Coordinate::Angle);
  options.driving_coordinates = {crank_angle};
  const State given = model.initial_configuration();
  const AssemblyReport report = assemble(model, given, options);
  EXPECT_EQ(report.state.v(crank_angle), rate);
  EXPECT_LE(report.velocity_residual, 1e-12);
  EXPECT_GT(report.bodies[1].largest_velocity_change, 0.1) << "the coupler was at rest";

  // Central differences of the exact construction along the crank angle.
  const double step = 1e-6;
  const Mechanism ahead = build(watt_six_bar(crank + step).links, geometry.joints);
  const Mechanism behind = build(watt_six_bar(crank - step).links, geometry.joints);
  const Eigen::VectorXd derivative =
      (ahead.model.initial_configuration().q - behind.model.initial_configuration().q) /
      (2.0 * step);
  EXPECT_LE((report.state.v - rate * derivative).lpNorm<Eigen::Infinity>(), 1e-8);
  model.set_initial_configuration(report.state.q, report.state.v);
  EXPECT_NO_THROW((void)model.initial_state());
}

TEST(MbdAssembly, AnOpenLoopIsRefusedNamingItsJointsAndTheMiss) {
  // Coupler and rocker 0.1 m each cannot bridge the >= 0.3 m from the crank to O2: at best
  // the loop misses by 0.4 - 0.1 - 0.1 - 0.1 = 0.1 m (all links in a line).
  const FourBar geometry = four_bar(0.0, 0.1, 0.1);
  Mechanism mechanism = build(off_by_a_milliradian(geometry.links), geometry.joints);
  try {
    (void)assemble(mechanism.model, mechanism.model.initial_configuration());
    FAIL() << "an open loop was assembled";
  } catch (const Error& error) {
    const std::string message = error.what();
    std::printf("%s\n", message.c_str());
    EXPECT_NE(message.find("cannot be closed"), std::string::npos) << message;
    for (const char* joint : {"'O1'", "'A'", "'B'", "'O2'"})
      EXPECT_NE(message.find(std::string("revolute joint ") + joint), std::string::npos)
          << joint << " not named in: " << message;
    const auto miss = message.find("the loop misses by ");
    ASSERT_NE(miss, std::string::npos) << message;
    EXPECT_NEAR(std::stod(message.substr(miss + 19)), 0.1, 1e-6) << message;
    EXPECT_NE(error.remedy().find("lengths"), std::string::npos);
  }
}

TEST(MbdAssembly, ADrivingCoordinateAConstraintFixesIsNamed) {
  // The crank angle is driving at 0.7 rad but a coordinate constraint holds it at 0.8.
  const FourBar geometry = four_bar(0.7);
  Mechanism mechanism = build(geometry.links, geometry.joints);
  Model& model = mechanism.model;
  const int crank_angle = model.coordinate_index(mechanism.bodies[0], Coordinate::Angle);
  model.add_coordinate_constraint(mechanism.bodies[0], Coordinate::Angle, 0.8);
  AssemblyOptions options;
  options.driving_coordinates = {crank_angle};
  try {
    (void)assemble(model, model.initial_configuration(), options);
    FAIL() << "a contradicting driving coordinate was accepted";
  } catch (const Error& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find(model.constraint_description(model.constraint_count() - 1)),
              std::string::npos)
        << message;
    EXPECT_EQ(message.find("revolute joint 'A'"), std::string::npos)
        << "the joints close; only the contradicted row stays: " << message;
  }
}

// In space: two rigid bodies in natural coordinates closing a loop through three spherical
// joints, the second body's centre given 1e-3 m off. The assembly closes the joints and keeps
// the orthonormality rows of both bodies (they are constraint rows like the joints).
TEST(MbdAssembly, SpatialLoopOfRigidBodiesCloses) {
  Model model;
  RigidBody3DSpec spec;
  spec.mass = 1.0;
  spec.inertia = Eigen::Vector3d(0.02, 0.03, 0.04).asDiagonal();
  spec.name = "first";
  spec.position = Eigen::Vector3d(0.5, 0.0, 0.0);
  const BodyId first = model.add_rigid_body_3d(spec);
  spec.name = "second";
  spec.position = Eigen::Vector3d(1.0, 0.5, 1e-3);
  spec.orientation = Eigen::AngleAxisd(0.5 * M_PI, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const BodyId second = model.add_rigid_body_3d(spec);
  model.add_spherical_joint({first, {-0.5, 0.0, 0.0}}, {kGround, Eigen::Vector3d::Zero()}, "root");
  model.add_spherical_joint({first, {0.5, 0.0, 0.0}}, {second, {-0.5, 0.0, 0.0}}, "knee");
  model.add_spherical_joint({second, {0.5, 0.0, 0.0}}, {kGround, {1.0, 1.0, 0.0}}, "tip");
  EXPECT_THROW((void)model.initial_state(), Error);

  AssemblyOptions options;
  options.driving_coordinates = {model.first_coordinate(first) + 2};  // first's z
  const State given = model.initial_configuration();
  const AssemblyReport report = assemble(model, given, options);
  EXPECT_LE(report.position_residual, 1e-12);
  EXPECT_EQ(report.state.q(options.driving_coordinates[0]), 0.0);
  EXPECT_GT(report.bodies[1].largest_position_change, 1e-4);
  EXPECT_LE(report.bodies[1].largest_position_change, 2e-3);
  model.set_initial_configuration(report.state.q, report.state.v);
  EXPECT_NO_THROW((void)model.initial_state());
}

TEST(MbdAssembly, RefusesBadDrivingIndicesAndReportsEveryBody) {
  const FourBar geometry = four_bar(0.7);
  Mechanism mechanism = build(geometry.links, geometry.joints);
  const Model& model = mechanism.model;
  AssemblyOptions options;
  options.driving_coordinates = {2, 2};
  EXPECT_THROW((void)assemble(model, model.initial_configuration(), options), Error);
  options.driving_coordinates = {model.coordinate_count()};
  EXPECT_THROW((void)assemble(model, model.initial_configuration(), options), Error);

  // An exact configuration stays as it is, to round-off.
  const AssemblyReport report = assemble(model, model.initial_configuration());
  EXPECT_LE((report.state.q - model.initial_configuration().q).lpNorm<Eigen::Infinity>(), 1e-15);
  const std::vector<std::string> lines = report.lines();
  ASSERT_EQ(lines.size(), 4u);
  EXPECT_NE(lines[0].find("initial assembly"), std::string::npos);
  EXPECT_NE(lines[2].find("body 'coupler'"), std::string::npos) << lines[2];
}

}  // namespace
}  // namespace fsi::mbd
