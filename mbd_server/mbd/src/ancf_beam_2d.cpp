#include "ancf_beam_2d.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "fsi/common/error.hpp"
#include "fsi/common/text.hpp"
#include "hermite_element.hpp"

namespace fsi::mbd::detail {
namespace {

using Vector8 = Eigen::Matrix<double, 8, 1>;
using Matrix8 = Eigen::Matrix<double, 8, 8>;
using Matrix28 = Eigen::Matrix<double, 2, 8>;

using Shape = HermiteShape;

Shape shape(double x, double l) {
  return hermite_shape(x, l);
}

Matrix28 expand(const Eigen::Vector4d& n) {
  return detail::expand<2>(n);
}

// Rotation by +90 degrees: n = R t is the left normal of t.
Eigen::Matrix2d quarter_turn() {
  Eigen::Matrix2d r;
  r << 0.0, -1.0, 1.0, 0.0;
  return r;
}

// d/da [T(a) w] for T(a) = (I - t t^T) / |a|, t = a / |a|, the derivative of the unit tangent:
// d(a / |a|) = T(a) da. Symmetric.
Eigen::Matrix2d tangent_derivative(const Eigen::Vector2d& a, const Eigen::Vector2d& w) {
  const double length = a.norm();
  const double l3 = length * length * length;
  const double aw = a.dot(w);
  return -(w * a.transpose() + a * w.transpose() + aw * Eigen::Matrix2d::Identity()) / l3 +
         3.0 * aw / (l3 * length * length) * a * a.transpose();
}

Eigen::Matrix2d tangent_map(const Eigen::Vector2d& a) {
  const double length = a.norm();
  return (Eigen::Matrix2d::Identity() - a * a.transpose() / (length * length)) / length;
}

// Input values in messages: all 17 digits.
std::string number(double value) {
  return significant(value, 17);
}

// Strain energy density and, on request, its gradient and Hessian with respect to the 8
// element coordinates at one point of an element.
struct Deformation {
  double axial_strain = 0.0;
  double curvature = 0.0;
  Vector8 axial_gradient;
  Vector8 curvature_gradient;
  Matrix8 axial_hessian;
  Matrix8 curvature_hessian;
};

Deformation deformation(const Vector8& qe, const Shape& s, bool second_derivatives) {
  const Matrix28 first = expand(s.first);
  const Matrix28 second = expand(s.second);
  const Eigen::Vector2d a = first * qe;   // r'
  const Eigen::Vector2d b = second * qe;  // r''
  const double length = a.norm();
  Deformation d;
  d.axial_strain = length - 1.0;
  d.axial_gradient = first.transpose() * a / length;

  // kappa = c / g with c = a x b (the z component) and g = |a|^2.
  Eigen::Matrix2d cross;  // c = a^T cross b
  cross << 0.0, 1.0, -1.0, 0.0;
  const double c = a.dot(cross * b);
  const double g = a.squaredNorm();
  d.curvature = c / g;
  const Vector8 c_gradient =
      first.transpose() * (cross * b) + second.transpose() * (cross.transpose() * a);
  const Vector8 g_gradient = 2.0 * first.transpose() * a;
  d.curvature_gradient = c_gradient / g - c / (g * g) * g_gradient;
  if (!second_derivatives) return d;

  d.axial_hessian = first.transpose() * tangent_map(a) * first;
  const Matrix8 c_hessian =
      first.transpose() * cross * second + second.transpose() * cross.transpose() * first;
  const Matrix8 g_hessian = 2.0 * first.transpose() * first;
  d.curvature_hessian =
      c_hessian / g -
      (c_gradient * g_gradient.transpose() + g_gradient * c_gradient.transpose()) / (g * g) +
      2.0 * c / (g * g * g) * g_gradient * g_gradient.transpose() - c / (g * g) * g_hessian;
  return d;
}

// Gauss rules: 5 points for the axial and 3 for the bending work (Exudyn's ANCFCable2D default,
// "order 9 / order 5"); 4 points integrate the mass matrix exactly (degree 6).
constexpr int kAxialPoints = 5;
constexpr int kBendingPoints = 3;
constexpr int kMassPoints = 4;

}  // namespace

AncfBeam2D::AncfBeam2D(const AncfBeamSpec& spec) : spec_(spec) {
  const std::string where = "ANCF beam '" + spec.name + "'";
  if (spec.name.empty()) {
    throw Error("an ANCF beam has no name", "ANCF beam", "give every body a unique name");
  }
  std::string problems =
      elastic_line_problems(spec.element_count, spec.axial_stiffness, spec.bending_stiffness,
                            spec.mass_per_length, spec.axial_damping, spec.bending_damping);
  if (!spec.start.allFinite() || !spec.end.allFinite()) {
    problems += " start or end is not finite;";
  }
  length_ = (spec.end - spec.start).norm();
  if (!(length_ > 0.0)) problems += " start and end coincide;";
  if (!problems.empty()) {
    problems.pop_back();
    throw Error("invalid parameters:" + problems, where,
                "give at least one element, positive EA, EI and rho A (2D: per unit depth), "
                "non-negative damping and two distinct end points");
  }
  element_length_ = length_ / spec.element_count;
}

Eigen::VectorXd AncfBeam2D::reference_coordinates() const {
  Eigen::VectorXd q(coordinate_count());
  const Eigen::Vector2d tangent = (spec_.end - spec_.start) / length_;
  for (int node = 0; node < node_count(); ++node) {
    q.segment<2>(4 * node) = spec_.start + node * element_length_ * tangent;
    q.segment<2>(4 * node + 2) = tangent;
  }
  return q;
}

// The rigid motion of the spec: a node at r moves at velocity + w z x (r - start), its slope r'
// turns at w z x r' (z x (a, b) = (-b, a)): no strain rate anywhere.
void AncfBeam2D::initial_state(Eigen::Ref<Eigen::VectorXd> q, Eigen::Ref<Eigen::VectorXd> v) const {
  q = reference_coordinates();
  const double w = spec_.angular_velocity;
  const auto turned = [w](const Eigen::Vector2d& a) {
    return Eigen::Vector2d(-w * a.y(), w * a.x());
  };
  for (int node = 0; node < node_count(); ++node) {
    v.segment<2>(4 * node) = spec_.velocity + turned(q.segment<2>(4 * node) - spec_.start);
    v.segment<2>(4 * node + 2) = turned(q.segment<2>(4 * node + 2));
  }
}

void AncfBeam2D::mass_matrix(MatrixSink& block) const {
  const GaussRule rule = gauss_rule(kMassPoints);
  const double l = element_length_;
  Matrix8 element = Matrix8::Zero();
  for (int i = 0; i < rule.size; ++i) {
    const Matrix28 n = expand(shape(0.5 * l * (rule.points[i] + 1.0), l).value);
    element += 0.5 * l * rule.weights[i] * spec_.mass_per_length * n.transpose() * n;
  }
  for (int e = 0; e < spec_.element_count; ++e)
    block.add_block(4 * e, 4 * e, element);
}

void AncfBeam2D::add_gravity_force(const Eigen::Vector2d& acceleration,
                                   Eigen::Ref<Eigen::VectorXd> force) const {
  add_uniform_field_force<2>(spec_.element_count, element_length_, spec_.mass_per_length,
                             acceleration, force);
}

double AncfBeam2D::gravity_potential(const ConstVector& q,
                                     const Eigen::Vector2d& acceleration) const {
  return -spec_.mass_per_length * length_ * acceleration.dot(reference_point(q));
}

Eigen::Vector2d AncfBeam2D::reference_point(const ConstVector& q) const {
  return line_centre<2>(q, spec_.element_count, element_length_);
}

double AncfBeam2D::strain_energy(const ConstVector& q) const {
  const double l = element_length_;
  double energy = 0.0;
  const GaussRule axial = gauss_rule(kAxialPoints);
  const GaussRule bending = gauss_rule(kBendingPoints);
  for (int e = 0; e < spec_.element_count; ++e) {
    const Vector8 qe = q.segment<8>(4 * e);
    for (int i = 0; i < axial.size; ++i) {
      const double eps =
          deformation(qe, shape(0.5 * l * (axial.points[i] + 1.0), l), false).axial_strain;
      energy += 0.25 * l * axial.weights[i] * spec_.axial_stiffness * eps * eps;
    }
    for (int i = 0; i < bending.size; ++i) {
      const double kappa =
          deformation(qe, shape(0.5 * l * (bending.points[i] + 1.0), l), false).curvature;
      energy += 0.25 * l * bending.weights[i] * spec_.bending_stiffness * kappa * kappa;
    }
  }
  return energy;
}

void AncfBeam2D::add_internal_force(const ConstVector& q, const ConstVector& v,
                                    Eigen::Ref<Eigen::VectorXd> force) const {
  // The axial force N = EA eps + d_eps deps/dt and the bending moment M = EI kappa +
  // d_kappa dkappa/dt do the virtual work integral (N d(eps) + M d(kappa)) dx; Q = -that
  // (-dU/dq for the elastic part).
  const double l = element_length_;
  const GaussRule axial = gauss_rule(kAxialPoints);
  const GaussRule bending = gauss_rule(kBendingPoints);
  for (int e = 0; e < spec_.element_count; ++e) {
    const Vector8 qe = q.segment<8>(4 * e);
    const Vector8 ve = v.segment<8>(4 * e);
    Vector8 work = Vector8::Zero();
    for (int i = 0; i < axial.size; ++i) {
      const Deformation d = deformation(qe, shape(0.5 * l * (axial.points[i] + 1.0), l), false);
      const double normal_force =
          spec_.axial_stiffness * d.axial_strain + spec_.axial_damping * d.axial_gradient.dot(ve);
      work += 0.5 * l * axial.weights[i] * normal_force * d.axial_gradient;
    }
    for (int i = 0; i < bending.size; ++i) {
      const Deformation d = deformation(qe, shape(0.5 * l * (bending.points[i] + 1.0), l), false);
      const double moment = spec_.bending_stiffness * d.curvature +
                            spec_.bending_damping * d.curvature_gradient.dot(ve);
      work += 0.5 * l * bending.weights[i] * moment * d.curvature_gradient;
    }
    force.segment<8>(4 * e) -= work;
  }
}

void AncfBeam2D::add_internal_force_derivatives(const ConstVector& q, const ConstVector& v,
                                                MatrixSink& by_position,
                                                MatrixSink& by_velocity) const {
  // For a strain measure e (eps or kappa) with stiffness k and damping c, the force
  // -(k e + c de/dt) grad e, de/dt = grad e . v, has
  //   d/dq = -(k grad e grad e^T + (k e + c de/dt) hess e + c grad e (hess e v)^T),
  //   d/dv = -c grad e grad e^T.
  const double l = element_length_;
  const GaussRule axial = gauss_rule(kAxialPoints);
  const GaussRule bending = gauss_rule(kBendingPoints);
  auto add = [](double weight, double stiffness, double damping, double measure,
                const Vector8& gradient, const Matrix8& hessian, const Vector8& ve,
                Matrix8& position, Matrix8& velocity) {
    const double resultant = stiffness * measure + damping * gradient.dot(ve);
    position += weight * (stiffness * gradient * gradient.transpose() + resultant * hessian +
                          damping * gradient * (hessian * ve).transpose());
    velocity += weight * damping * gradient * gradient.transpose();
  };
  for (int e = 0; e < spec_.element_count; ++e) {
    const Vector8 qe = q.segment<8>(4 * e);
    const Vector8 ve = v.segment<8>(4 * e);
    Matrix8 position = Matrix8::Zero();
    Matrix8 velocity = Matrix8::Zero();
    for (int i = 0; i < axial.size; ++i) {
      const Deformation d = deformation(qe, shape(0.5 * l * (axial.points[i] + 1.0), l), true);
      add(0.5 * l * axial.weights[i], spec_.axial_stiffness, spec_.axial_damping, d.axial_strain,
          d.axial_gradient, d.axial_hessian, ve, position, velocity);
    }
    for (int i = 0; i < bending.size; ++i) {
      const Deformation d = deformation(qe, shape(0.5 * l * (bending.points[i] + 1.0), l), true);
      add(0.5 * l * bending.weights[i], spec_.bending_stiffness, spec_.bending_damping, d.curvature,
          d.curvature_gradient, d.curvature_hessian, ve, position, velocity);
    }
    by_position.add_block(4 * e, 4 * e, position, -1.0);
    by_velocity.add_block(4 * e, 4 * e, velocity, -1.0);
  }
}

void AncfBeam2D::check_local_coordinates(const Eigen::Vector2d& local,
                                         const std::string& user) const {
  const double slack = 1e-12 * length_;
  if (!(local.x() >= -slack && local.x() <= length_ + slack)) {
    throw Error(user + " on ANCF beam '" + spec_.name + "' has the axial coordinate s = " +
                    number(local.x()) + " outside [0, " + number(length_) + "]",
                "ANCF beam '" + spec_.name + "'",
                "give s along the undeformed centre line, 0 at the start node, L at the end");
  }
}

int AncfBeam2D::element_of(double s, double& x) const {
  const int e =
      std::clamp(static_cast<int>(std::floor(s / element_length_)), 0, spec_.element_count - 1);
  x = s - e * element_length_;
  return e;
}

Eigen::Vector2d AncfBeam2D::position(const ConstVector& q, const Eigen::Vector2d& local) const {
  double x = 0.0;
  const int e = element_of(local.x(), x);
  const Shape s = shape(x, element_length_);
  const Vector8 qe = q.segment<8>(4 * e);
  const Eigen::Vector2d slope = expand(s.first) * qe;
  return expand(s.value) * qe + local.y() * quarter_turn() * slope.normalized();
}

Eigen::Vector2d AncfBeam2D::velocity(const ConstVector& q, const ConstVector& v,
                                     const Eigen::Vector2d& local) const {
  double x = 0.0;
  const int e = element_of(local.x(), x);
  const Shape s = shape(x, element_length_);
  const Vector8 qe = q.segment<8>(4 * e);
  const Vector8 ve = v.segment<8>(4 * e);
  const Matrix28 first = expand(s.first);
  const Eigen::Vector2d slope = first * qe;
  return expand(s.value) * ve + local.y() * quarter_turn() * tangent_map(slope) * (first * ve);
}

// A body point's place on the centre line: its element, the shape maps S and S' (2 x 8) there and
// the slope r' = S' q_e.
struct AncfBeam2D::CentreLinePoint {
  int element;
  Matrix28 value;
  Matrix28 first;
  Eigen::Vector2d slope;

  // dp/dq_e = S + eta R T(r') S' for the point at distance eta from the centre line.
  Matrix28 position_jacobian(double eta) const {
    return value + eta * quarter_turn() * tangent_map(slope) * first;
  }
};

AncfBeam2D::CentreLinePoint AncfBeam2D::centre_line_point(const ConstVector& q,
                                                          double arc_length) const {
  double x = 0.0;
  const int e = element_of(arc_length, x);
  const Shape s = shape(x, element_length_);
  const Matrix28 first = expand(s.first);
  return {e, expand(s.value), first, first * q.segment<8>(4 * e)};
}

Eigen::Vector2d AncfBeam2D::slope(const ConstVector& q, double arc_length) const {
  return centre_line_point(q, arc_length).slope;
}

Eigen::Vector2d AncfBeam2D::slope_rate(const ConstVector& q, const ConstVector& v,
                                       double arc_length) const {
  const CentreLinePoint point = centre_line_point(q, arc_length);
  return point.first * v.segment<8>(4 * point.element);
}

void AncfBeam2D::position_jacobian(const ConstVector& q, const Eigen::Vector2d& local,
                                   Eigen::Ref<Eigen::MatrixXd> jacobian) const {
  const CentreLinePoint point = centre_line_point(q, local.x());
  jacobian.setZero();
  jacobian.middleCols<8>(4 * point.element) = point.position_jacobian(local.y());
}

void AncfBeam2D::add_point_load(const ConstVector& q, const Eigen::Vector2d& local,
                                const Eigen::Vector2d& force,
                                Eigen::Ref<Eigen::VectorXd> generalised_force) const {
  const CentreLinePoint point = centre_line_point(q, local.x());
  const Matrix28 jacobian = point.position_jacobian(local.y());
  generalised_force.segment<8>(4 * point.element) += jacobian.transpose() * force;
}

void AncfBeam2D::velocity_jacobian(const ConstVector& q, const ConstVector& v,
                                   const Eigen::Vector2d& local,
                                   Eigen::Ref<Eigen::MatrixXd> jacobian) const {
  // (dp/dq) v = S v + eta R T(r') (S' v); only T depends on q.
  const CentreLinePoint point = centre_line_point(q, local.x());
  const Eigen::Vector2d slope_rate = point.first * v.segment<8>(4 * point.element);
  jacobian.setZero();
  jacobian.middleCols<8>(4 * point.element) =
      local.y() * quarter_turn() * tangent_derivative(point.slope, slope_rate) * point.first;
}

void AncfBeam2D::add_point_load_derivative(const ConstVector& q, const Eigen::Vector2d& local,
                                           const Eigen::Vector2d& force,
                                           MatrixSink& derivative) const {
  // (dp/dq)^T f = S^T f + eta S'^T T(r') R^T f (T is symmetric); only T depends on q.
  if (local.y() == 0.0) return;
  const CentreLinePoint point = centre_line_point(q, local.x());
  const Matrix8 element = local.y() * point.first.transpose() *
                          tangent_derivative(point.slope, quarter_turn().transpose() * force) *
                          point.first;
  derivative.add_block(4 * point.element, 4 * point.element, element);
}

}  // namespace fsi::mbd::detail
