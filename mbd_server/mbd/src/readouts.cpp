#include "fsi/mbd/readouts.hpp"

#include <Eigen/SparseCore>

#include <algorithm>
#include <cmath>
#include <string>

#include "ancf_beam_2d.hpp"
#include "ancf_cable_3d.hpp"
#include "fsi/common/error.hpp"
#include "measured_force.hpp"
#include "model_data.hpp"
#include "rigid_body_3d.hpp"

namespace fsi::mbd {
namespace {

using Data = detail::ModelAccess::Data;

const Data& data_of(const Model& model) {
  return detail::ModelAccess::data(model);
}

// The generalised force -G^T lambda of the rows first_row .. first_row + rows - 1 alone. Sparse
// G: a sensor per output step must not cost O(m n).
Eigen::VectorXd joint_generalised_force(const Model& model, const State& state, int first_row,
                                        int rows) {
  FSI_ASSERT(first_row >= 0 && rows >= 0 && first_row + rows <= model.constraint_count(),
             "joint rows out of range");
  Eigen::SparseMatrix<double> jacobian;
  model.constraint_jacobian(state.time, state.q, jacobian);
  Eigen::VectorXd multipliers = Eigen::VectorXd::Zero(model.constraint_count());
  multipliers.segment(first_row, rows) = state.lambda.segment(first_row, rows);
  return -(jacobian.transpose() * multipliers);
}

Wrench planar_joint_reaction(const Model& model, const State& state, int first_row, int rows,
                             BodyId body) {
  const Eigen::VectorXd force = joint_generalised_force(model, state, first_row, rows);
  Wrench reaction;
  if (body == kGround) return reaction;
  reaction.force.x() = force(model.coordinate_index(body, Coordinate::X));
  reaction.force.y() = force(model.coordinate_index(body, Coordinate::Y));
  reaction.torque.z() = force(model.coordinate_index(body, Coordinate::Angle));
  return reaction;
}

Wrench spatial_joint_reaction(const Model& model, const State& state, int first_row, int rows,
                              BodyId body) {
  const Data& data = data_of(model);
  const auto& spatial = data.spatial_body(body, "a joint reaction");
  const bool rigid = dynamic_cast<const detail::RigidBody3D*>(&spatial) != nullptr;
  if (!rigid && dynamic_cast<const detail::PointMass3D*>(&spatial) == nullptr) {
    throw Error("'" + spatial.name() + "' is neither a spatial rigid body nor a point mass",
                "a joint reaction", "measure a RigidBody3D or a PointMass");
  }
  const Eigen::VectorXd generalised = joint_generalised_force(model, state, first_row, rows);
  const auto own = data.segment(generalised, body);
  const auto q = data.segment(state.q, body);
  Wrench reaction;
  reaction.force = own.head<3>();
  if (rigid) {
    for (int k = 0; k < 3; ++k) {
      reaction.torque += Eigen::Vector3d(q.segment<3>(3 + 3 * k))
                             .cross(Eigen::Vector3d(own.segment<3>(3 + 3 * k)));
    }
  }
  return reaction;
}

Eigen::Vector3d planar(const Eigen::Vector2d& value) {
  return {value.x(), value.y(), 0.0};
}

Eigen::Vector3d spatial_marker_position(const Data& data, const State& state, int marker) {
  const detail::Marker& m = data.markers[marker];
  if (m.body == kGround) return m.spatial_local;
  const auto& body = *data.as_spatial(m.body);
  const auto q = data.segment(state.q, m.body);
  const Eigen::Vector3d centre = body.spatial_position(q, m.spatial_local);
  if (m.tube_radius == 0.0) return centre;
  // The initial normals turned by the rotation that takes the initial tangent t0 to the current
  // t: R v = c v + w x v + w (w . v) / (1 + c), w = t0 x t, c = t0 . t (regular unless t = -t0).
  const auto& cable = dynamic_cast<const detail::AncfCable3D&>(body);
  const Eigen::Vector3d t0 = (cable.spec().end - cable.spec().start).normalized();
  const Eigen::Vector3d t = cable.tangent(q, m.spatial_local.x());
  const Eigen::Vector3d& offset = m.tube_offset;
  const Eigen::Vector3d w = t0.cross(t);
  const double c = t0.dot(t);
  const Eigen::Vector3d turned = c * offset + w.cross(offset) + w * w.dot(offset) / (1.0 + c);
  return centre + m.tube_radius * turned;
}

Eigen::Vector2d planar_marker_position(const Data& data, const State& state, int marker) {
  const detail::Marker& m = data.markers[marker];
  if (m.body == kGround) return m.local;
  return data.bodies[m.body]->position(data.segment(state.q, m.body), m.local);
}

Eigen::Vector3d spatial_marker_velocity(const Data& data, const State& state, int marker) {
  const detail::Marker& m = data.markers[marker];
  if (m.body == kGround) return Eigen::Vector3d::Zero();
  return data.as_spatial(m.body)->spatial_velocity(data.segment(state.q, m.body),
                                                   data.segment(state.v, m.body), m.spatial_local);
}

Eigen::Vector2d planar_marker_velocity(const Data& data, const State& state, int marker) {
  const detail::Marker& m = data.markers[marker];
  if (m.body == kGround) return Eigen::Vector2d::Zero();
  return data.bodies[m.body]->velocity(data.segment(state.q, m.body), data.segment(state.v, m.body),
                                       m.local);
}

// Writes `readout(model, state, k)` of every marker k into `values`, as many components a marker
// as the model has dimensions.
template <typename Readout>
void copy_per_marker(const Model& model, const State& state, std::span<double> values,
                     const char* too_small, Readout readout) {
  const Data& data = data_of(model);
  const std::size_t dimension = data.dimension == 3 ? 3 : 2;
  FSI_ASSERT(values.size() >= dimension * data.markers.size(), too_small);
  for (int k = 0; k < model.marker_count(); ++k) {
    const Eigen::Vector3d value = readout(model, state, k);
    std::copy(value.data(), value.data() + dimension, values.begin() + dimension * k);
  }
}

}  // namespace

double kinetic_energy(const ConstrainedSystem& system, const State& state) {
  return 0.5 * state.v.dot(system.sparse_mass_matrix() * state.v);
}

Eigen::VectorXd generalised_constraint_force(const ConstrainedSystem& system, const State& state) {
  Eigen::SparseMatrix<double> jacobian;
  system.constraint_jacobian(state.time, state.q, jacobian);
  return -jacobian.transpose() * state.lambda;
}

double position_constraint_drift(const ConstrainedSystem& system, const State& state) {
  Eigen::VectorXd residual;
  system.constraint_residual(state.time, state.q, state.v, residual);
  double drift = 0.0;
  for (int k = 0; k < system.constraint_count(); ++k) {
    if (system.constraint_level(k) == ConstraintLevel::Position && system.holds_at(k, state.time))
      drift = std::max(drift, std::abs(residual(k)));
  }
  return drift;
}

double velocity_constraint_drift(const ConstrainedSystem& system, const State& state) {
  Eigen::VectorXd rate;
  system.constraint_rate(state.time, state.q, state.v, rate);
  double drift = 0.0;
  for (int k = 0; k < system.constraint_count(); ++k) {
    if (system.holds_at(k, state.time)) drift = std::max(drift, std::abs(rate(k)));
  }
  return drift;
}

double potential_energy(const Model& model, const State& state) {
  const Data& data = data_of(model);
  double energy = 0.0;
  for (int b = 0; b < model.body_count(); ++b) {
    const auto q = data.segment(state.q, b);
    if (const auto* spatial = data.as_spatial(b)) {
      energy += spatial->spatial_gravity_potential(q, data.spatial_gravity);
    } else {
      energy += data.bodies[b]->gravity_potential(q, data.gravity);
    }
  }
  for (const auto& element : data.force_elements)
    energy += element->potential_energy(state.time, state.q);
  return energy;
}

double strain_energy(const Model& model, const State& state) {
  const Data& data = data_of(model);
  double energy = 0.0;
  for (int b = 0; b < model.body_count(); ++b)
    energy += data.bodies[b]->internal_energy(data.segment(state.q, b));
  return energy;
}

double constraint_force(const Model& model, const State& state, BodyId body,
                        Coordinate coordinate) {
  return generalised_constraint_force(model, state)(model.coordinate_index(body, coordinate));
}

Wrench joint_reaction(const Model& model, const State& state, int first_row, int rows,
                      BodyId body) {
  return model.dimension() == 3 ? spatial_joint_reaction(model, state, first_row, rows, body)
                                : planar_joint_reaction(model, state, first_row, rows, body);
}

Wrench beam_joint_reaction(const Model& model, const State& state, int first_row, int rows,
                           BodyId beam, const Eigen::Vector2d& point) {
  if (!model.is_beam(beam)) {
    throw Error("body " + std::to_string(beam) + " is not an AncfBeam2D", "a beam joint reaction",
                "this is a bug of fsi-server: please report it");
  }
  const int nodes = model.beam_node_count(beam);
  const Data& data = data_of(model);
  const Eigen::VectorXd generalised = joint_generalised_force(model, state, first_row, rows);
  const auto own = data.segment(generalised, beam);
  const auto q = data.segment(state.q, beam);
  const Eigen::Vector2d pivot = point_position(model, state, BodyPointSpec{beam, point}).head<2>();
  const auto cross = [](const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return a.x() * b.y() - a.y() * b.x();
  };
  Wrench reaction;
  for (int j = 0; j < nodes; ++j) {
    const Eigen::Vector2d on_position = own.segment<2>(4 * j);
    const Eigen::Vector2d on_slope = own.segment<2>(4 * j + 2);
    reaction.force.head<2>() += on_position;
    reaction.torque.z() += cross(Eigen::Vector2d(q.segment<2>(4 * j)) - pivot, on_position) +
                           cross(q.segment<2>(4 * j + 2), on_slope);
  }
  return reaction;
}

Wrench point_load_resultant(const Model& model, const State& state, BodyId body) {
  const Data& data = data_of(model);
  data.check_body(body, "a point-load resultant");
  Wrench resultant;
  if (const auto* spatial = data.as_spatial(body)) {
    const Eigen::Vector3d centre = spatial->spatial_reference_point(data.segment(state.q, body));
    for (int k = 0; k < model.marker_count(); ++k) {
      if (data.markers[k].body != body) continue;
      const Eigen::Vector3d load(data.point_loads[3 * k], data.point_loads[3 * k + 1],
                                 data.point_loads[3 * k + 2]);
      resultant.force += load;
      resultant.torque += (spatial_marker_position(data, state, k) - centre).cross(load);
    }
    return resultant;
  }
  const Eigen::Vector2d centre = data.bodies[body]->reference_point(data.segment(state.q, body));
  for (int k = 0; k < model.marker_count(); ++k) {
    if (data.markers[k].body != body) continue;
    const Eigen::Vector2d load(data.point_loads[2 * k], data.point_loads[2 * k + 1]);
    const Eigen::Vector2d arm = planar_marker_position(data, state, k) - centre;
    resultant.force += Eigen::Vector3d(load.x(), load.y(), 0.0);
    resultant.torque.z() += arm.x() * load.y() - arm.y() * load.x();
  }
  return resultant;
}

double force_element_force(const Model& model, const State& state, int element) {
  const ForceElement& force_element = model.force_element(element);
  const auto* measured = dynamic_cast<const detail::MeasuredForce*>(&force_element);
  if (measured == nullptr) {
    throw Error(force_element.description() + " measures no force", "spring force sensor",
                "measure a spring-damper, nonlinear spring-damper, spring actor or rotational "
                "spring-damper");
  }
  return measured->measured_force(state.time, state.q, state.v);
}

double force_element_power(const Model& model, const State& state, int element) {
  Eigen::VectorXd force = Eigen::VectorXd::Zero(state.v.size());
  model.force_element(element).add_force(state.time, state.q, state.v, force);
  return force.dot(state.v);
}

Eigen::Vector3d marker_position(const Model& model, const State& state, int marker) {
  const Data& data = data_of(model);
  data.check_marker(marker);
  return data.dimension == 3 ? spatial_marker_position(data, state, marker)
                             : planar(planar_marker_position(data, state, marker));
}

Eigen::Vector3d marker_velocity(const Model& model, const State& state, int marker) {
  const Data& data = data_of(model);
  data.check_marker(marker);
  return data.dimension == 3 ? spatial_marker_velocity(data, state, marker)
                             : planar(planar_marker_velocity(data, state, marker));
}

void marker_positions(const Model& model, const State& state, std::span<double> values) {
  copy_per_marker(model, state, values, "marker position buffer too small", marker_position);
}

void marker_velocities(const Model& model, const State& state, std::span<double> values) {
  copy_per_marker(model, state, values, "marker velocity buffer too small", marker_velocity);
}

Eigen::Vector3d point_position(const Model& model, const State& state, const BodyPointSpec& point) {
  return planar(data_of(model).point(point, "a position readout").position(state.q));
}

Eigen::Vector3d point_position(const Model& model, const State& state,
                               const SpatialPointSpec& point) {
  return data_of(model).spatial_point(point, "a position readout").position(state.q);
}

double beam_tangent_angle(const Model& model, const State& state, BodyId beam, double s) {
  const Data& data = data_of(model);
  const detail::AncfBeam2D& element = data.ancf_beam(beam, "a beam tangent readout");
  element.check_local_coordinates({s, 0.0}, "a beam tangent readout");
  const Eigen::Vector2d slope = element.slope(data.segment(state.q, beam), s);
  return std::atan2(slope.y(), slope.x());
}

double beam_tangent_rate(const Model& model, const State& state, BodyId beam, double s) {
  const Data& data = data_of(model);
  const detail::AncfBeam2D& element = data.ancf_beam(beam, "a beam tangent readout");
  element.check_local_coordinates({s, 0.0}, "a beam tangent readout");
  const auto q = data.segment(state.q, beam);
  const Eigen::Vector2d slope = element.slope(q, s);
  const Eigen::Vector2d rate = element.slope_rate(q, data.segment(state.v, beam), s);
  return (slope.x() * rate.y() - slope.y() * rate.x()) / slope.squaredNorm();
}

Eigen::Vector3d point_velocity(const Model& model, const State& state, const BodyPointSpec& point) {
  return planar(data_of(model).point(point, "a velocity readout").velocity(state.q, state.v));
}

Eigen::Vector3d point_velocity(const Model& model, const State& state,
                               const SpatialPointSpec& point) {
  return data_of(model).spatial_point(point, "a velocity readout").velocity(state.q, state.v);
}

Eigen::Matrix3d orientation(const Model& model, const State& state, BodyId body) {
  (void)model.rigid_body_3d(body);
  const auto q = data_of(model).segment(state.q, body);
  Eigen::Matrix3d r;
  for (int k = 0; k < 3; ++k)
    r.col(k) = q.segment<3>(3 + 3 * k);
  return r;
}

Eigen::Vector3d angular_velocity(const Model& model, const State& state, BodyId body) {
  const Eigen::Matrix3d r = orientation(model, state, body);
  const auto v = data_of(model).segment(state.v, body);
  Eigen::Matrix3d rate;
  for (int k = 0; k < 3; ++k)
    rate.col(k) = v.segment<3>(3 + 3 * k);
  // dR/dt = [omega]x R, so [omega]x = dR/dt R^T; its skew part is exact also off the manifold.
  const Eigen::Matrix3d spin = rate * r.transpose();
  const Eigen::Matrix3d skew = 0.5 * (spin - spin.transpose());
  return {skew(2, 1), skew(0, 2), skew(1, 0)};
}

}  // namespace fsi::mbd
