#include "force_elements.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <utility>

namespace fsi::mbd::detail {

// ---- rotational spring-damper ----

RotationalSpringDamper::RotationalSpringDamper(std::string description, int angle_a, int angle_b,
                                               double rest_angle,
                                               std::shared_ptr<const TensionLaw> law)
    : SparseForceElement(std::move(description)),
      angle_a_(angle_a),
      angle_b_(angle_b),
      rest_angle_(rest_angle),
      law_(std::move(law)) {}

double RotationalSpringDamper::measured_force(double time, const Eigen::VectorXd& q,
                                              const Eigen::VectorXd& v) const {
  return -law_->at(twist(q), twist_rate(v), time).value;
}

void RotationalSpringDamper::add_force(double time, const Eigen::VectorXd& q,
                                       const Eigen::VectorXd& v, Eigen::VectorXd& force) const {
  const double torque = measured_force(time, q, v);
  if (angle_a_ >= 0) force(angle_a_) += torque;
  if (angle_b_ >= 0) force(angle_b_) -= torque;
}

bool RotationalSpringDamper::add_jacobian_entries(double time, const Eigen::VectorXd& q,
                                                  const Eigen::VectorXd& v,
                                                  MatrixSink& force_by_position,
                                                  MatrixSink& force_by_velocity) const {
  // The torque depends on phi_a - phi_b and its rate only: the pattern [-1 1; 1 -1] times the
  // law's partial derivatives.
  const Tension law = law_->at(twist(q), twist_rate(v), time);
  const std::array<std::pair<int, double>, 2> ends = {{{angle_a_, 1.0}, {angle_b_, -1.0}}};
  for (const auto& [row, row_sign] : ends) {
    for (const auto& [column, column_sign] : ends) {
      if (row < 0 || column < 0) continue;
      force_by_position.add(row, column, -row_sign * column_sign * law.by_elongation);
      force_by_velocity.add(row, column, -row_sign * column_sign * law.by_rate);
    }
  }
  return true;
}

double RotationalSpringDamper::potential_energy(double time, const Eigen::VectorXd& q) const {
  return law_->energy(twist(q), time);
}

// ---- time-dependent loads ----

Torque::Torque(std::string description, int angle, std::function<double(double)> torque)
    : SparseForceElement(std::move(description)), angle_(angle), torque_(std::move(torque)) {}

void Torque::add_force(double time, const Eigen::VectorXd&, const Eigen::VectorXd&,
                       Eigen::VectorXd& force) const {
  force(angle_) += torque_(time);
}

// ---- spatial torque ----

namespace {

Eigen::Matrix3d cross_matrix(const Eigen::Vector3d& w) {
  Eigen::Matrix3d m;
  m << 0.0, -w.z(), w.y(), w.z(), 0.0, -w.x(), -w.y(), w.x(), 0.0;
  return m;
}

}  // namespace

SpatialTorque::SpatialTorque(std::string description, int axes_offset,
                             std::function<Eigen::Vector3d(double)> torque)
    : SparseForceElement(std::move(description)),
      axes_offset_(axes_offset),
      torque_(std::move(torque)) {}

void SpatialTorque::add_force(double time, const Eigen::VectorXd& q, const Eigen::VectorXd&,
                              Eigen::VectorXd& force) const {
  const Eigen::Vector3d tau = torque_(time);
  for (int k = 0; k < 3; ++k) {
    const int e = axes_offset_ + 3 * k;
    force.segment<3>(e) += 0.5 * tau.cross(q.segment<3>(e));
  }
}

bool SpatialTorque::add_jacobian_entries(double time, const Eigen::VectorXd&,
                                         const Eigen::VectorXd&, MatrixSink& force_by_position,
                                         MatrixSink&) const {
  const Eigen::Matrix3d block = 0.5 * cross_matrix(torque_(time));
  for (int k = 0; k < 3; ++k) {
    const int e = axes_offset_ + 3 * k;
    force_by_position.add_block(e, e, block);
  }
  return true;
}

}  // namespace fsi::mbd::detail
