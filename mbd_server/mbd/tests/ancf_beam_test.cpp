// The planar ANCF beam element (src/ancf_beam_2d.hpp) against finite differences: elastic
// forces as the gradient of the strain energy and their Jacobian, material points on the centre
// line and on both faces (position, velocity, Jacobians, load derivative), and point loads on
// such points as the gradient of their work (virtual work, thesis eq. 2.6-2.8). The beam
// acceptance tests (cantilever statics and frequencies) are in ancf_cantilever_test.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "ancf_beam_2d.hpp"
#include "error_message.hpp"
#include "fsi/common/error.hpp"
#include "fsi/mbd/integrator.hpp"
#include "fsi/mbd/model.hpp"
#include "fsi/mbd/readouts.hpp"
#include "radau_stage_equations.hpp"

namespace fsi::mbd {
namespace {

AncfBeamSpec beam_spec(int elements) {
  AncfBeamSpec spec;
  spec.name = "beam";
  spec.start = {0.3, -0.2};
  spec.end = {1.5, 0.4};
  spec.element_count = elements;
  spec.axial_stiffness = 3.0e4;
  spec.bending_stiffness = 25.0;
  spec.mass_per_length = 2.5;
  return spec;
}

// A smoothly and strongly deformed state: the reference coordinates plus random perturbations of
// positions (about 5 % of the length) and slopes (about 30 %).
Eigen::VectorXd deformed(const detail::AncfBeam2D& beam, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::VectorXd q = beam.reference_coordinates();
  for (int k = 0; k < q.size(); ++k)
    q(k) += ((k % 4) < 2 ? 0.05 * beam.length() : 0.3) * u(rng);
  return q;
}

Eigen::VectorXd random_vector(int size, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::VectorXd x(size);
  for (int k = 0; k < size; ++k)
    x(k) = u(rng);
  return x;
}

// Central differences of a vector function of q, column by column.
template <typename Function>
Eigen::MatrixXd differences(const Function& f, const Eigen::VectorXd& q, double step) {
  const Eigen::VectorXd f0 = f(q);
  Eigen::MatrixXd jacobian(f0.size(), q.size());
  for (int j = 0; j < q.size(); ++j) {
    Eigen::VectorXd plus = q, minus = q;
    plus(j) += step;
    minus(j) -= step;
    jacobian.col(j) = (f(plus) - f(minus)) / (2.0 * step);
  }
  return jacobian;
}

double relative_error(const Eigen::MatrixXd& value, const Eigen::MatrixXd& reference) {
  return (value - reference).cwiseAbs().maxCoeff() /
         std::max(reference.cwiseAbs().maxCoeff(), 1e-300);
}

// Material points on the centre line and on both faces, at element ends and inside elements.
std::vector<Eigen::Vector2d> material_points(const detail::AncfBeam2D& beam) {
  const double l = beam.element_length();
  return {{0.0, 0.0},     {0.37 * l, 0.04},  {l, -0.03},           {1.61 * l, 0.05},
          {2.0 * l, 0.0}, {2.93 * l, -0.05}, {beam.length(), 0.02}};
}

TEST(MbdAncfBeam, ElasticForceIsMinusTheGradientOfTheStrainEnergy) {
  std::mt19937 rng(3);
  const detail::AncfBeam2D beam(beam_spec(3));
  const int n = beam.coordinate_count();
  for (int trial = 0; trial < 5; ++trial) {
    const Eigen::VectorXd q = deformed(beam, rng);
    const Eigen::VectorXd v = Eigen::VectorXd::Zero(n);
    Eigen::VectorXd force = Eigen::VectorXd::Zero(n);
    beam.add_internal_force(q, v, force);
    const Eigen::MatrixXd gradient = differences(
        [&](const Eigen::VectorXd& x) {
          return Eigen::VectorXd::Constant(1, beam.strain_energy(x));
        },
        q, 1e-6);
    EXPECT_LT(relative_error(force.transpose(), -gradient), 1e-7) << "trial " << trial;
  }
}

TEST(MbdAncfBeam, ElasticStiffnessMatchesDifferencesOfTheForce) {
  std::mt19937 rng(4);
  const detail::AncfBeam2D beam(beam_spec(3));
  const int n = beam.coordinate_count();
  for (int trial = 0; trial < 5; ++trial) {
    const Eigen::VectorXd q = deformed(beam, rng);
    const Eigen::VectorXd v = random_vector(n, rng);
    Eigen::MatrixXd by_position = Eigen::MatrixXd::Zero(n, n);
    Eigen::MatrixXd by_velocity = Eigen::MatrixXd::Zero(n, n);
    beam.add_internal_force_derivatives(q, v, by_position, by_velocity);
    const Eigen::MatrixXd reference = differences(
        [&](const Eigen::VectorXd& x) {
          Eigen::VectorXd f = Eigen::VectorXd::Zero(n);
          beam.add_internal_force(x, v, f);
          return f;
        },
        q, 1e-6);
    EXPECT_LT(relative_error(by_position, reference), 1e-7) << "trial " << trial;
    EXPECT_EQ(by_velocity.cwiseAbs().maxCoeff(), 0.0) << "this beam has no damping";
    EXPECT_LT(relative_error(by_position, by_position.transpose()), 1e-12) << "conservative";
  }
}

TEST(MbdAncfBeam, DampedForceAndItsDerivativesMatchDifferences) {
  std::mt19937 rng(5);
  AncfBeamSpec spec = beam_spec(3);
  spec.axial_damping = 40.0;
  spec.bending_damping = 0.3;
  const detail::AncfBeam2D beam(spec);
  const detail::AncfBeam2D undamped(beam_spec(3));
  const int n = beam.coordinate_count();
  for (int trial = 0; trial < 5; ++trial) {
    const Eigen::VectorXd q = deformed(beam, rng);
    const Eigen::VectorXd v = 3.0 * random_vector(n, rng);
    auto force = [&](const detail::AncfBeam2D& b, const Eigen::VectorXd& x,
                     const Eigen::VectorXd& u) {
      Eigen::VectorXd f = Eigen::VectorXd::Zero(n);
      b.add_internal_force(x, u, f);
      return f;
    };
    Eigen::MatrixXd by_position = Eigen::MatrixXd::Zero(n, n);
    Eigen::MatrixXd by_velocity = Eigen::MatrixXd::Zero(n, n);
    beam.add_internal_force_derivatives(q, v, by_position, by_velocity);
    const Eigen::MatrixXd position_differences =
        differences([&](const Eigen::VectorXd& x) { return force(beam, x, v); }, q, 1e-6);
    const Eigen::MatrixXd velocity_differences =
        differences([&](const Eigen::VectorXd& u) { return force(beam, q, u); }, v, 1e-6);
    EXPECT_LT(relative_error(by_position, position_differences), 1e-7) << "trial " << trial;
    EXPECT_LT(relative_error(by_velocity, velocity_differences), 1e-7) << "trial " << trial;
    // Damping dissipates: the damping force does negative power.
    const Eigen::VectorXd damping_force = force(beam, q, v) - force(undamped, q, v);
    EXPECT_LT(damping_force.dot(v), 0.0);
    EXPECT_LT((force(beam, q, Eigen::VectorXd::Zero(n)) - force(undamped, q, v)).norm(),
              1e-12 * force(undamped, q, v).norm())
        << "at rest only the elastic force acts";
  }
}

TEST(MbdAncfBeam, RigidMotionOfTheReferenceLineIsStressFree) {
  const detail::AncfBeam2D beam(beam_spec(4));
  const int n = beam.coordinate_count();
  const double angle = 1.1;
  const Eigen::Rotation2Dd rotation(angle);
  Eigen::VectorXd q = beam.reference_coordinates();
  for (int node = 0; node < beam.node_count(); ++node) {
    q.segment<2>(4 * node) = rotation * q.segment<2>(4 * node) + Eigen::Vector2d(0.7, -2.0);
    q.segment<2>(4 * node + 2) = rotation * q.segment<2>(4 * node + 2);
  }
  Eigen::VectorXd force = Eigen::VectorXd::Zero(n);
  beam.add_internal_force(q, Eigen::VectorXd::Zero(n), force);
  EXPECT_LT(force.cwiseAbs().maxCoeff(), 1e-10 * beam.spec().axial_stiffness);
  EXPECT_LT(beam.strain_energy(q), 1e-20 * beam.spec().axial_stiffness);
}

TEST(MbdAncfBeam, CircularArcHasTheCurvatureOfTheCircle) {
  // Nodes on a circle of radius R with unit tangent slopes: kappa ~ 1/R, eps ~ 0, so the strain
  // energy is EI L / (2 R^2) up to the interpolation error of the cubic elements.
  const AncfBeamSpec spec = beam_spec(16);
  const detail::AncfBeam2D beam(spec);
  const double radius = beam.length() / 2.0;  // bent through 2 rad
  Eigen::VectorXd q(beam.coordinate_count());
  for (int node = 0; node < beam.node_count(); ++node) {
    const double phi = node * beam.element_length() / radius;
    q.segment<2>(4 * node) = radius * Eigen::Vector2d(std::sin(phi), 1.0 - std::cos(phi));
    q.segment<2>(4 * node + 2) = Eigen::Vector2d(std::cos(phi), std::sin(phi));
  }
  const double expected = 0.5 * spec.bending_stiffness * beam.length() / (radius * radius);
  EXPECT_NEAR(beam.strain_energy(q) / expected, 1.0, 1e-3);
}

TEST(MbdAncfBeam, TheCrossSectionsAngleAndItsRateFollowTheCentreLine) {
  // On the circular arc the tangent at s turns by s / R; spun rigidly at omega about a point
  // (v = omega z x (r - c), slope rates omega z x r'), every cross-section turns at omega. The
  // rate is the derivative of the angle: checked by a difference in time too.
  Model model;
  const AncfBeamSpec spec = beam_spec(16);
  const BodyId id = model.add_ancf_beam(spec);
  const detail::AncfBeam2D beam(spec);
  const double radius = beam.length() / 2.0;
  State state = model.initial_state();
  const Eigen::Vector2d centre(0.3, -0.2);
  const double omega = 0.7;
  const auto turn = [](const Eigen::Vector2d& r) { return Eigen::Vector2d(-r.y(), r.x()); };
  for (int node = 0; node < beam.node_count(); ++node) {
    const double phi = node * beam.element_length() / radius;
    state.q.segment<2>(4 * node) = radius * Eigen::Vector2d(std::sin(phi), 1.0 - std::cos(phi));
    state.q.segment<2>(4 * node + 2) = Eigen::Vector2d(std::cos(phi), std::sin(phi));
    state.v.segment<2>(4 * node) = omega * turn(state.q.segment<2>(4 * node) - centre);
    state.v.segment<2>(4 * node + 2) = omega * turn(state.q.segment<2>(4 * node + 2));
  }
  for (const double s : {0.0, 0.3 * beam.length(), beam.length()}) {
    EXPECT_NEAR(beam_tangent_angle(model, state, id, s), s / radius, 1e-4) << "s = " << s;
    EXPECT_NEAR(beam_tangent_rate(model, state, id, s), omega, 1e-12) << "s = " << s;
    State later = state;
    const double dt = 1e-7;
    later.q += dt * state.v;
    EXPECT_NEAR(
        (beam_tangent_angle(model, later, id, s) - beam_tangent_angle(model, state, id, s)) / dt,
        omega, 1e-5)
        << "s = " << s;
  }
  EXPECT_THROW(beam_tangent_angle(model, state, id, 1.01 * beam.length()), Error);
}

TEST(MbdAncfBeam, MassMatrixMovesRigidlyWithTheTotalMass) {
  const AncfBeamSpec spec = beam_spec(5);
  const detail::AncfBeam2D beam(spec);
  const int n = beam.coordinate_count();
  Eigen::MatrixXd mass(n, n);
  beam.mass_matrix(mass);
  // A uniform translation u: every node moves by u, the slopes stay.
  const Eigen::Vector2d u(0.3, -1.7);
  Eigen::VectorXd translation = Eigen::VectorXd::Zero(n);
  for (int node = 0; node < beam.node_count(); ++node)
    translation.segment<2>(4 * node) = u;
  const double total_mass = spec.mass_per_length * beam.length();
  EXPECT_NEAR(translation.dot(mass * translation), total_mass * u.squaredNorm(), 1e-12);
  // Gravity is the mass matrix times the uniform acceleration field.
  Eigen::VectorXd gravity = Eigen::VectorXd::Zero(n);
  beam.add_gravity_force(u, gravity);
  EXPECT_LT((gravity - mass * translation).cwiseAbs().maxCoeff(), 1e-13);
  EXPECT_LT(relative_error(mass, mass.transpose()), 1e-15);
  EXPECT_GT(Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(mass).eigenvalues().minCoeff(), 0.0);
  // The centre of mass of the reference line is its midpoint.
  const Eigen::VectorXd q = beam.reference_coordinates();
  EXPECT_LT((beam.reference_point(q) - 0.5 * (spec.start + spec.end)).norm(), 1e-14);
}

TEST(MbdAncfBeam, MaterialPointsAndTheirJacobiansMatchDifferences) {
  std::mt19937 rng(7);
  const detail::AncfBeam2D beam(beam_spec(3));
  const int n = beam.coordinate_count();
  for (int trial = 0; trial < 4; ++trial) {
    const Eigen::VectorXd q = deformed(beam, rng);
    const Eigen::VectorXd v = random_vector(n, rng);
    const Eigen::Vector2d load = Eigen::Vector2d(3.0, -2.0) * (trial + 1);
    for (const Eigen::Vector2d& local : material_points(beam)) {
      SCOPED_TRACE("trial " + std::to_string(trial) + ", s = " + std::to_string(local.x()) +
                   ", eta = " + std::to_string(local.y()));
      Eigen::MatrixXd jacobian(2, n);
      beam.position_jacobian(q, local, jacobian);
      const Eigen::MatrixXd position_differences = differences(
          [&](const Eigen::VectorXd& x) { return Eigen::VectorXd(beam.position(x, local)); }, q,
          1e-6);
      EXPECT_LT(relative_error(jacobian, position_differences), 1e-7);
      // The velocity is dr/dq v (ANCF: r is linear in q except for the face offset).
      EXPECT_LT((beam.velocity(q, v, local) - jacobian * v).norm(), 1e-14 * (1.0 + v.norm()));

      Eigen::MatrixXd velocity_jacobian(2, n);
      beam.velocity_jacobian(q, v, local, velocity_jacobian);
      const Eigen::MatrixXd velocity_differences = differences(
          [&](const Eigen::VectorXd& x) { return Eigen::VectorXd(beam.velocity(x, v, local)); }, q,
          1e-6);
      if (local.y() == 0.0) {
        EXPECT_EQ(velocity_jacobian.cwiseAbs().maxCoeff(), 0.0);
        EXPECT_LT(velocity_differences.cwiseAbs().maxCoeff(), 1e-8);
      } else {
        EXPECT_LT(relative_error(velocity_jacobian, velocity_differences), 1e-7);
      }

      Eigen::MatrixXd load_derivative = Eigen::MatrixXd::Zero(n, n);
      beam.add_point_load_derivative(q, local, load, load_derivative);
      const Eigen::MatrixXd load_differences = differences(
          [&](const Eigen::VectorXd& x) {
            Eigen::MatrixXd j(2, n);
            beam.position_jacobian(x, local, j);
            return Eigen::VectorXd(j.transpose() * load);
          },
          q, 1e-6);
      if (local.y() == 0.0) {
        EXPECT_EQ(load_derivative.cwiseAbs().maxCoeff(), 0.0);
      } else {
        EXPECT_LT(relative_error(load_derivative, load_differences), 1e-7);
      }
    }
  }
}

TEST(MbdAncfBeam, FacePointsStayAtTheirDistanceOnTheNormal) {
  std::mt19937 rng(8);
  const detail::AncfBeam2D beam(beam_spec(3));
  const Eigen::VectorXd q = deformed(beam, rng);
  const double s = 1.3 * beam.element_length();
  const Eigen::Vector2d centre = beam.position(q, {s, 0.0});
  const Eigen::Vector2d upper = beam.position(q, {s, 0.05});
  const Eigen::Vector2d lower = beam.position(q, {s, -0.05});
  EXPECT_NEAR((upper - centre).norm(), 0.05, 1e-15);
  EXPECT_LT((upper - centre + lower - centre).norm(), 1e-15);
  // Perpendicular to the tangent, on its left.
  const Eigen::Vector2d tangent =
      (beam.position(q, {s + 1e-6, 0.0}) - beam.position(q, {s - 1e-6, 0.0})).normalized();
  EXPECT_NEAR(tangent.dot(upper - centre), 0.0, 1e-10);
  EXPECT_GT(tangent.x() * (upper - centre).y() - tangent.y() * (upper - centre).x(), 0.0);
}

// The acceptance check 'fluid forces through virtual work' for beams: vertex forces on mesh
// points of both faces give the generalised force whose virtual work they do, and its derivative.
TEST(MbdAncfBeam, VertexForcesOnBothFacesGiveTheGeneralisedForceOfVirtualWork) {
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Model model;
  const BodyId beam_id = model.add_ancf_beam(beam_spec(3));
  const double length = (beam_spec(3).end - beam_spec(3).start).norm();
  std::vector<double> loads;
  for (int k = 0; k <= 12; ++k) {
    const double eta = (k % 2 == 0 ? 1.0 : -1.0) * 0.02;  // alternately upper and lower face
    model.add_marker(beam_id, {length * k / 12.0, eta});
    loads.push_back(40.0 * u(rng));
    loads.push_back(40.0 * u(rng));
  }
  model.set_point_loads(loads);
  const detail::AncfBeam2D element(beam_spec(3));
  State state = model.initial_state();
  state.q = deformed(element, rng);
  const int n = model.coordinate_count();

  // Work of the loads minus the strain energy: its gradient is F (gravity is zero here).
  auto point_load_force = [&](const Eigen::VectorXd& q) {
    Eigen::VectorXd force;
    model.applied_force(0.0, q, state.v, force);
    Eigen::VectorXd elastic = Eigen::VectorXd::Zero(n);
    element.add_internal_force(q, state.v, elastic);
    return Eigen::VectorXd(force - elastic);
  };
  auto work = [&](const Eigen::VectorXd& q) {
    State probe = state;
    probe.q = q;
    double sum = 0.0;
    for (int k = 0; k < model.marker_count(); ++k)
      sum += Eigen::Vector2d(loads[2 * k], loads[2 * k + 1])
                 .dot(marker_position(model, probe, k).head<2>());
    return Eigen::VectorXd::Constant(1, sum);
  };
  const Eigen::VectorXd force = point_load_force(state.q);
  EXPECT_LT(relative_error(force.transpose(), differences(work, state.q, 1e-6)), 1e-7);

  // dF/dq of the loads, analytic, against differences of sum_k (dr_k/dq)^T f_k (without the
  // much larger elastic force, whose rounding would swamp the differences).
  Eigen::MatrixXd by_position, by_velocity;
  model.applied_force_derivatives(0.0, state.q, state.v, by_position, by_velocity);
  Eigen::MatrixXd elastic_by_position = Eigen::MatrixXd::Zero(n, n);
  Eigen::MatrixXd elastic_by_velocity = Eigen::MatrixXd::Zero(n, n);
  element.add_internal_force_derivatives(state.q, state.v, elastic_by_position,
                                         elastic_by_velocity);
  auto virtual_work_force = [&](const Eigen::VectorXd& q) {
    Eigen::VectorXd sum = Eigen::VectorXd::Zero(n);
    for (int k = 0; k < model.marker_count(); ++k)
      sum +=
          model.marker_jacobian(q, k).transpose() * Eigen::Vector2d(loads[2 * k], loads[2 * k + 1]);
    return sum;
  };
  EXPECT_LT(relative_error(virtual_work_force(state.q).transpose(), force.transpose()), 1e-12);
  EXPECT_LT(relative_error(by_position - elastic_by_position,
                           differences(virtual_work_force, state.q, 1e-6)),
            1e-7);
  // Model::strain_energy is the beam's.
  EXPECT_DOUBLE_EQ(strain_energy(model, state), element.strain_energy(state.q));
}

TEST(MbdAncfBeam, NewtonMatrixWithABeamMatchesDifferencesOfTheResidual) {
  Model model;
  AncfBeamSpec spec = beam_spec(2);
  spec.axial_damping = 20.0;  // dF/dv of the beam in the matrix too
  spec.bending_damping = 0.2;
  const BodyId beam_id = model.add_ancf_beam(spec);
  model.set_gravity({0.0, -9.81});
  model.add_beam_clamp(beam_id, 0);
  model.add_marker(beam_id, {(spec.end - spec.start).norm(), 0.01});
  model.set_point_loads(std::vector<double>{0.5, -2.0});
  State start = model.initial_state();
  std::mt19937 rng(10);
  // A bent, stretched start (not consistent with the clamp, which the matrix does not need):
  // the elastic stiffness is then far from its value at the straight reference.
  start.q = deformed(detail::AncfBeam2D(spec), rng);
  const Eigen::VectorXd shift = random_vector(model.coordinate_count(), rng);
  const double h = 1e-3;
  detail::RadauStageEquations equations(radau_iia(3));
  equations.begin_step(model, start, h);
  Eigen::VectorXd unknowns;
  equations.predict(unknowns);
  for (int i = 0; i < unknowns.size(); ++i)
    unknowns(i) += 0.05 * std::sin(1.0 + i) + 0.01 * shift(i % shift.size());
  Eigen::MatrixXd jacobian;
  equations.jacobian(unknowns, jacobian);
  const Eigen::MatrixXd reference = differences(
      [&](const Eigen::VectorXd& x) {
        Eigen::VectorXd r;
        equations.residual(x, r);
        return r;
      },
      unknowns, 1e-6);
  EXPECT_LT(relative_error(jacobian, reference), 1e-7);
}

TEST(MbdAncfBeam, ModelApiChecksBeamsNodesAndMaterialPoints) {
  Model model;
  RigidBody2DSpec rigid;
  rigid.name = "block";
  rigid.mass = 1.0;
  rigid.inertia = 1.0;
  const BodyId block = model.add_rigid_body(rigid);
  const BodyId beam_id = model.add_ancf_beam(beam_spec(4));
  EXPECT_TRUE(model.is_beam(beam_id));
  EXPECT_FALSE(model.is_beam(block));
  EXPECT_EQ(model.beam_node_count(beam_id), 5);
  EXPECT_EQ(model.coordinate_count(), 3 + 20);
  EXPECT_EQ(model.beam_coordinate_index(beam_id, 2, BeamNodeCoordinate::SlopeY), 3 + 8 + 3);
  EXPECT_THROW(model.add_beam_clamp(block, 0), Error);
  EXPECT_THROW(model.add_beam_clamp(beam_id, 5), Error);
  EXPECT_THROW(model.add_marker(beam_id, {2.0, 0.0}), Error);  // beyond the end (L = 1.34)
  EXPECT_THROW(model.add_ancf_beam(beam_spec(2)), Error);      // the name is taken
  AncfBeamSpec bad = beam_spec(0);
  bad.name = "bad";
  bad.bending_stiffness = -1.0;
  const std::string message = testing::error_message([&] { model.add_ancf_beam(bad); });
  EXPECT_NE(message.find("element count"), std::string::npos) << message;
  EXPECT_NE(message.find("bending stiffness"), std::string::npos) << message;
  // A direction clamp holds x, y and the slope's direction; a full clamp both slope components.
  EXPECT_EQ(model.add_beam_clamp(beam_id, 0), 0);
  EXPECT_EQ(model.constraint_count(), 3);
  EXPECT_EQ(model.add_beam_clamp(beam_id, 4, BeamClamp::Full), 3);
  EXPECT_EQ(model.constraint_count(), 7);
  const State state = model.initial_state();  // consistent and not redundant
  EXPECT_EQ(position_constraint_drift(model, state), 0.0);
  EXPECT_NE(model.constraint_description(2).find("slope direction"), std::string::npos);
}

}  // namespace
}  // namespace fsi::mbd
