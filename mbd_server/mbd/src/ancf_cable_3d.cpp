#include "ancf_cable_3d.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "fsi/common/error.hpp"
#include "fsi/common/text.hpp"
#include "hermite_element.hpp"

namespace fsi::mbd::detail {
namespace {

using Vector12 = Eigen::Matrix<double, 12, 1>;
using Matrix12 = Eigen::Matrix<double, 12, 12>;
using Matrix312 = Eigen::Matrix<double, 3, 12>;

constexpr int kAxialPoints = 5;
constexpr int kBendingPoints = 3;
constexpr int kMassPoints = 4;

// Input values in messages: all 17 digits.
std::string number(double value) {
  return significant(value, 17);
}

// (a x b)_k = a^T C_k b, (C_k)_ij the Levi-Civita symbol eps_kij.
std::array<Eigen::Matrix3d, 3> cross_forms() {
  std::array<Eigen::Matrix3d, 3> c;
  for (auto& m : c)
    m.setZero();
  c[0](1, 2) = 1.0;
  c[0](2, 1) = -1.0;
  c[1](2, 0) = 1.0;
  c[1](0, 2) = -1.0;
  c[2](0, 1) = 1.0;
  c[2](1, 0) = -1.0;
  return c;
}

// The strain measures at one point of an element: eps, then the three curvature components,
// each with its gradient and, on request, its Hessian with respect to the 12 coordinates.
struct Measures {
  std::array<double, 4> value{};
  std::array<Vector12, 4> gradient;
  std::array<Matrix12, 4> hessian;
};

Measures measures(const Vector12& qe, const HermiteShape& s, bool second_derivatives) {
  static const std::array<Eigen::Matrix3d, 3> kCross = cross_forms();
  const Matrix312 first = expand<3>(s.first);
  const Matrix312 second = expand<3>(s.second);
  const Eigen::Vector3d a = first * qe;   // r'
  const Eigen::Vector3d b = second * qe;  // r''
  const double length = a.norm();
  Measures m;
  m.value[0] = length - 1.0;
  m.gradient[0] = first.transpose() * a / length;
  if (second_derivatives) {
    const Eigen::Matrix3d tangent_map =
        (Eigen::Matrix3d::Identity() - a * a.transpose() / (length * length)) / length;
    m.hessian[0] = first.transpose() * tangent_map * first;
  }
  // kappa_k = c_k / g with c_k = a^T C_k b and g = |a|^2.
  const double g = a.squaredNorm();
  const Vector12 g_gradient = 2.0 * first.transpose() * a;
  const Matrix12 g_hessian = 2.0 * first.transpose() * first;
  for (int k = 0; k < 3; ++k) {
    const Eigen::Matrix3d& cross = kCross[k];
    const double c = a.dot(cross * b);
    const Vector12 c_gradient =
        first.transpose() * (cross * b) + second.transpose() * (cross.transpose() * a);
    m.value[k + 1] = c / g;
    m.gradient[k + 1] = c_gradient / g - c / (g * g) * g_gradient;
    if (!second_derivatives) continue;
    const Matrix12 c_hessian =
        first.transpose() * cross * second + second.transpose() * cross.transpose() * first;
    m.hessian[k + 1] =
        c_hessian / g -
        (c_gradient * g_gradient.transpose() + g_gradient * c_gradient.transpose()) / (g * g) +
        2.0 * c / (g * g * g) * g_gradient * g_gradient.transpose() - c / (g * g) * g_hessian;
  }
  return m;
}

}  // namespace

AncfCable3D::AncfCable3D(const AncfCableSpec& spec) : spec_(spec) {
  const std::string where = "ANCF cable '" + spec.name + "'";
  if (spec.name.empty()) {
    throw Error("an ANCF cable has no name", "ANCF cable", "give every body a unique name");
  }
  std::string problems =
      elastic_line_problems(spec.element_count, spec.axial_stiffness, spec.bending_stiffness,
                            spec.mass_per_length, spec.axial_damping, spec.bending_damping);
  if (!spec.start.allFinite() || !spec.end.allFinite()) problems += " start or end is not finite;";
  length_ = (spec.end - spec.start).norm();
  if (!(length_ > 0.0)) problems += " start and end coincide;";
  if (!problems.empty()) {
    problems.pop_back();
    throw Error("invalid parameters:" + problems, where,
                "give at least one element, positive EA, EI and rho A, non-negative damping and "
                "two distinct end points");
  }
  element_length_ = length_ / spec.element_count;
}

Eigen::VectorXd AncfCable3D::reference_coordinates() const {
  Eigen::VectorXd q(coordinate_count());
  const Eigen::Vector3d direction = (spec_.end - spec_.start) / length_;
  for (int node = 0; node < node_count(); ++node) {
    q.segment<3>(6 * node) = spec_.start + node * element_length_ * direction;
    q.segment<3>(6 * node + 3) = direction;
  }
  return q;
}

void AncfCable3D::initial_state(Eigen::Ref<Eigen::VectorXd> q,
                                Eigen::Ref<Eigen::VectorXd> v) const {
  q = reference_coordinates();
  v.setZero();
}

void AncfCable3D::mass_matrix(MatrixSink& block) const {
  const GaussRule rule = gauss_rule(kMassPoints);
  const double l = element_length_;
  Matrix12 element = Matrix12::Zero();
  for (int i = 0; i < rule.size; ++i) {
    const Matrix312 n = expand<3>(hermite_shape(0.5 * l * (rule.points[i] + 1.0), l).value);
    element += 0.5 * l * rule.weights[i] * spec_.mass_per_length * n.transpose() * n;
  }
  for (int e = 0; e < spec_.element_count; ++e)
    block.add_block(6 * e, 6 * e, element);
}

void AncfCable3D::add_spatial_gravity_force(const Eigen::Vector3d& acceleration,
                                            Eigen::Ref<Eigen::VectorXd> force) const {
  add_uniform_field_force<3>(spec_.element_count, element_length_, spec_.mass_per_length,
                             acceleration, force);
}

double AncfCable3D::spatial_gravity_potential(const ConstVector& q,
                                              const Eigen::Vector3d& acceleration) const {
  return -spec_.mass_per_length * length_ * acceleration.dot(spatial_reference_point(q));
}

Eigen::Vector3d AncfCable3D::spatial_reference_point(const ConstVector& q) const {
  return line_centre<3>(q, spec_.element_count, element_length_);
}

double AncfCable3D::strain_energy(const ConstVector& q) const {
  const double l = element_length_;
  const GaussRule axial = gauss_rule(kAxialPoints);
  const GaussRule bending = gauss_rule(kBendingPoints);
  double energy = 0.0;
  for (int e = 0; e < spec_.element_count; ++e) {
    const Vector12 qe = q.segment<12>(6 * e);
    for (int i = 0; i < axial.size; ++i) {
      const Measures m = measures(qe, hermite_shape(0.5 * l * (axial.points[i] + 1.0), l), false);
      energy += 0.25 * l * axial.weights[i] * spec_.axial_stiffness * m.value[0] * m.value[0];
    }
    for (int i = 0; i < bending.size; ++i) {
      const Measures m = measures(qe, hermite_shape(0.5 * l * (bending.points[i] + 1.0), l), false);
      for (int k = 1; k < 4; ++k)
        energy += 0.25 * l * bending.weights[i] * spec_.bending_stiffness * m.value[k] * m.value[k];
    }
  }
  return energy;
}

void AncfCable3D::add_internal_force(const ConstVector& q, const ConstVector& v,
                                     Eigen::Ref<Eigen::VectorXd> force) const {
  // Q = -integral (N grad eps + sum_k M_k grad kappa_k) dx with N = EA eps + d_eps deps/dt and
  // M_k = EI kappa_k + d_kappa dkappa_k/dt.
  const double l = element_length_;
  const GaussRule axial = gauss_rule(kAxialPoints);
  const GaussRule bending = gauss_rule(kBendingPoints);
  for (int e = 0; e < spec_.element_count; ++e) {
    const Vector12 qe = q.segment<12>(6 * e);
    const Vector12 ve = v.segment<12>(6 * e);
    Vector12 work = Vector12::Zero();
    for (int i = 0; i < axial.size; ++i) {
      const Measures m = measures(qe, hermite_shape(0.5 * l * (axial.points[i] + 1.0), l), false);
      const double normal =
          spec_.axial_stiffness * m.value[0] + spec_.axial_damping * m.gradient[0].dot(ve);
      work += 0.5 * l * axial.weights[i] * normal * m.gradient[0];
    }
    for (int i = 0; i < bending.size; ++i) {
      const Measures m = measures(qe, hermite_shape(0.5 * l * (bending.points[i] + 1.0), l), false);
      for (int k = 1; k < 4; ++k) {
        const double moment =
            spec_.bending_stiffness * m.value[k] + spec_.bending_damping * m.gradient[k].dot(ve);
        work += 0.5 * l * bending.weights[i] * moment * m.gradient[k];
      }
    }
    force.segment<12>(6 * e) -= work;
  }
}

void AncfCable3D::add_internal_force_derivatives(const ConstVector& q, const ConstVector& v,
                                                 MatrixSink& by_position,
                                                 MatrixSink& by_velocity) const {
  // Per measure e with stiffness k and damping c (the planar beam's formula):
  //   d/dq = -(k grad e grad e^T + (k e + c de/dt) hess e + c grad e (hess e v)^T),
  //   d/dv = -c grad e grad e^T.
  const double l = element_length_;
  const GaussRule axial = gauss_rule(kAxialPoints);
  const GaussRule bending = gauss_rule(kBendingPoints);
  for (int e = 0; e < spec_.element_count; ++e) {
    const Vector12 qe = q.segment<12>(6 * e);
    const Vector12 ve = v.segment<12>(6 * e);
    Matrix12 position = Matrix12::Zero();
    Matrix12 velocity = Matrix12::Zero();
    auto add = [&](double weight, double stiffness, double damping, const Measures& m, int k) {
      const Vector12& gradient = m.gradient[k];
      const double resultant = stiffness * m.value[k] + damping * gradient.dot(ve);
      position += weight * (stiffness * gradient * gradient.transpose() + resultant * m.hessian[k] +
                            damping * gradient * (m.hessian[k] * ve).transpose());
      velocity += weight * damping * gradient * gradient.transpose();
    };
    for (int i = 0; i < axial.size; ++i) {
      const Measures m = measures(qe, hermite_shape(0.5 * l * (axial.points[i] + 1.0), l), true);
      add(0.5 * l * axial.weights[i], spec_.axial_stiffness, spec_.axial_damping, m, 0);
    }
    for (int i = 0; i < bending.size; ++i) {
      const Measures m = measures(qe, hermite_shape(0.5 * l * (bending.points[i] + 1.0), l), true);
      for (int k = 1; k < 4; ++k)
        add(0.5 * l * bending.weights[i], spec_.bending_stiffness, spec_.bending_damping, m, k);
    }
    by_position.add_block(6 * e, 6 * e, position, -1.0);
    by_velocity.add_block(6 * e, 6 * e, velocity, -1.0);
  }
}

void AncfCable3D::check_spatial_local(const Eigen::Vector3d& local, const std::string& user) const {
  const double slack = 1e-12 * length_;
  const std::string where = "ANCF cable '" + spec_.name + "'";
  if (!(local.x() >= -slack && local.x() <= length_ + slack)) {
    throw Error(user + " on " + where + " has the axial coordinate s = " + number(local.x()) +
                    " outside [0, " + number(length_) + "]",
                where,
                "give s along the undeformed centre line, 0 at the start node, L at the end");
  }
  if (local.y() != 0.0 || local.z() != 0.0) {
    throw Error(user + " on " + where + " is off the centre line (local (" + number(local.x()) +
                    ", " + number(local.y()) + ", " + number(local.z()) +
                    ")); a cable has no cross-section orientation",
                where, "attach at (s, 0, 0); the tube surface around a cable follows its radius");
  }
}

int AncfCable3D::element_of(double s, double& x) const {
  const int e =
      std::clamp(static_cast<int>(std::floor(s / element_length_)), 0, spec_.element_count - 1);
  x = s - e * element_length_;
  return e;
}

Eigen::Vector3d AncfCable3D::spatial_position(const ConstVector& q,
                                              const Eigen::Vector3d& local) const {
  double x = 0.0;
  const int e = element_of(local.x(), x);
  return expand<3>(hermite_shape(x, element_length_).value) * q.segment<12>(6 * e);
}

Eigen::Vector3d AncfCable3D::spatial_velocity(const ConstVector&, const ConstVector& v,
                                              const Eigen::Vector3d& local) const {
  double x = 0.0;
  const int e = element_of(local.x(), x);
  return expand<3>(hermite_shape(x, element_length_).value) * v.segment<12>(6 * e);
}

Eigen::Vector3d AncfCable3D::tangent(const ConstVector& q, double s) const {
  double x = 0.0;
  const int e = element_of(s, x);
  return (expand<3>(hermite_shape(x, element_length_).first) * q.segment<12>(6 * e)).normalized();
}

void AncfCable3D::add_spatial_point_load(const ConstVector&, const Eigen::Vector3d& local,
                                         const Eigen::Vector3d& force,
                                         Eigen::Ref<Eigen::VectorXd> generalised_force) const {
  double x = 0.0;
  const int e = element_of(local.x(), x);
  generalised_force.segment<12>(6 * e) +=
      expand<3>(hermite_shape(x, element_length_).value).transpose() * force;
}

void AncfCable3D::spatial_position_jacobian(const ConstVector&, const Eigen::Vector3d& local,
                                            Eigen::Ref<Eigen::MatrixXd> jacobian) const {
  double x = 0.0;
  const int e = element_of(local.x(), x);
  jacobian.setZero();
  jacobian.middleCols<12>(6 * e) = expand<3>(hermite_shape(x, element_length_).value);
}

}  // namespace fsi::mbd::detail
