#pragma once
// Planar ANCF beam (internal): Gerstmayr & Irschik's elastic-line element ("ANCF cable 2D"),
// equations in docs/theory.md ("Planar ANCF beam").
//
// Coordinates: per node the position r (2) and the slope r' = dr/dx (2), node after node, so an
// element couples the 8 coordinates of its two nodes and neighbours share a node. Cubic Hermite
// interpolation r(x) = S(x) q_e along the undeformed arc length x; the stress-free reference is
// the straight line of the spec (|r'| = 1, no curvature). Strain energy per unit length
// 1/2 EA eps^2 + 1/2 EI kappa^2 with eps = |r'| - 1 and kappa = (r' x r'') / |r'|^2.
// Optional viscous damping adds d_eps deps/dt to the axial force and d_kappa dkappa/dt to the
// bending moment.
//
// Material points: local = (s, eta), s in [0, L] along the undeformed centre line, eta along
// the unit normal n = e_z x r' / |r'| of the deformed line (left of the direction start -> end):
// p = r(s) + eta n(s). eta = +-h/2 are the two faces of a beam of thickness h.

#include <Eigen/Dense>

#include <string>

#include "body.hpp"
#include "fsi/mbd/model.hpp"

namespace fsi::mbd::detail {

class AncfBeam2D final : public Body {
 public:
  explicit AncfBeam2D(const AncfBeamSpec& spec);  // throws fsi::Error for invalid values

  const AncfBeamSpec& spec() const { return spec_; }
  int node_count() const { return spec_.element_count + 1; }
  double length() const { return length_; }
  double element_length() const { return element_length_; }
  // Nodal coordinates of the straight, stress-free reference line.
  Eigen::VectorXd reference_coordinates() const;
  // Strain energy of the axial and bending deformation [J] (2D: per unit depth).
  double strain_energy(const ConstVector& q) const;

  const std::string& name() const override { return spec_.name; }
  int coordinate_count() const override { return 4 * node_count(); }
  void initial_state(Eigen::Ref<Eigen::VectorXd> q, Eigen::Ref<Eigen::VectorXd> v) const override;
  using Body::add_internal_force_derivatives;
  using Body::add_point_load_derivative;
  using Body::mass_matrix;
  void mass_matrix(MatrixSink& block) const override;
  void add_gravity_force(const Eigen::Vector2d& acceleration,
                         Eigen::Ref<Eigen::VectorXd> force) const override;
  double gravity_potential(const ConstVector& q,
                           const Eigen::Vector2d& acceleration) const override;
  void add_internal_force(const ConstVector& q, const ConstVector& v,
                          Eigen::Ref<Eigen::VectorXd> force) const override;
  void add_internal_force_derivatives(const ConstVector& q, const ConstVector& v,
                                      MatrixSink& by_position,
                                      MatrixSink& by_velocity) const override;
  double internal_energy(const ConstVector& q) const override { return strain_energy(q); }
  void check_local_coordinates(const Eigen::Vector2d& local,
                               const std::string& user) const override;
  Eigen::Vector2d position(const ConstVector& q, const Eigen::Vector2d& local) const override;
  Eigen::Vector2d velocity(const ConstVector& q, const ConstVector& v,
                           const Eigen::Vector2d& local) const override;
  // The centre line's slope r' = dr/dx at arc length s, and its rate.
  Eigen::Vector2d slope(const ConstVector& q, double arc_length) const;
  Eigen::Vector2d slope_rate(const ConstVector& q, const ConstVector& v, double arc_length) const;
  void position_jacobian(const ConstVector& q, const Eigen::Vector2d& local,
                         Eigen::Ref<Eigen::MatrixXd> jacobian) const override;
  void velocity_jacobian(const ConstVector& q, const ConstVector& v, const Eigen::Vector2d& local,
                         Eigen::Ref<Eigen::MatrixXd> jacobian) const override;
  void add_point_load_derivative(const ConstVector& q, const Eigen::Vector2d& local,
                                 const Eigen::Vector2d& force,
                                 MatrixSink& derivative) const override;
  void add_point_load(const ConstVector& q, const Eigen::Vector2d& local,
                      const Eigen::Vector2d& force,
                      Eigen::Ref<Eigen::VectorXd> generalised_force) const override;
  // The centre of mass of the deformed beam.
  Eigen::Vector2d reference_point(const ConstVector& q) const override;

 private:
  // The element holding arc length s and the position within it, x in [0, element length].
  int element_of(double s, double& x) const;
  struct CentreLinePoint;
  CentreLinePoint centre_line_point(const ConstVector& q, double arc_length) const;

  AncfBeamSpec spec_;
  double length_ = 0.0;
  double element_length_ = 0.0;
};

}  // namespace fsi::mbd::detail
