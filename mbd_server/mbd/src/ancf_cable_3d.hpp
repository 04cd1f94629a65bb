#pragma once
// Spatial ANCF cable (internal): Gerstmayr & Shabana's cable element (2006), the spatial form of
// the planar elastic-line beam (ancf_beam_2d.hpp); spec and energy in fsi/mbd/model.hpp,
// equations in docs/theory.md ("Spatial ANCF cable").
//
// Coordinates: per node the position r (3) and the slope r' = dr/dx (3), node after node; an
// element couples the 12 coordinates of its two nodes. Cubic Hermite interpolation along the
// undeformed arc length x. Strain energy per length 1/2 EA eps^2 + 1/2 EI |kappa|^2 with
// eps = |r'| - 1 and kappa = (r' x r'') / |r'|^2 (in a plane: the planar beam's curvature),
// optional viscous damping as the planar beam. Gauss 5 points (axial) and 3 (bending).
// Material points lie on the centre line, local = (s, 0, 0): r(s) is linear in q.

#include <Eigen/Dense>

#include <string>

#include "fsi/mbd/model.hpp"
#include "spatial_body.hpp"

namespace fsi::mbd::detail {

class AncfCable3D final : public SpatialBody {
 public:
  explicit AncfCable3D(const AncfCableSpec& spec);  // throws fsi::Error for invalid values

  const AncfCableSpec& spec() const { return spec_; }
  int node_count() const { return spec_.element_count + 1; }
  double length() const { return length_; }
  Eigen::VectorXd reference_coordinates() const;
  double strain_energy(const ConstVector& q) const;
  // The unit tangent r'/|r'| of the centre line at arc length s.
  Eigen::Vector3d tangent(const ConstVector& q, double s) const;

  const std::string& name() const override { return spec_.name; }
  int coordinate_count() const override { return 6 * node_count(); }
  void initial_state(Eigen::Ref<Eigen::VectorXd> q, Eigen::Ref<Eigen::VectorXd> v) const override;
  using Body::add_internal_force_derivatives;
  using Body::mass_matrix;
  void mass_matrix(MatrixSink& block) const override;
  void add_spatial_gravity_force(const Eigen::Vector3d& acceleration,
                                 Eigen::Ref<Eigen::VectorXd> force) const override;
  double spatial_gravity_potential(const ConstVector& q,
                                   const Eigen::Vector3d& acceleration) const override;
  void add_internal_force(const ConstVector& q, const ConstVector& v,
                          Eigen::Ref<Eigen::VectorXd> force) const override;
  void add_internal_force_derivatives(const ConstVector& q, const ConstVector& v,
                                      MatrixSink& by_position,
                                      MatrixSink& by_velocity) const override;
  // Only the element's 12 entries.
  void add_spatial_point_load(const ConstVector& q, const Eigen::Vector3d& local,
                              const Eigen::Vector3d& force,
                              Eigen::Ref<Eigen::VectorXd> generalised_force) const override;
  double internal_energy(const ConstVector& q) const override { return strain_energy(q); }
  void check_spatial_local(const Eigen::Vector3d& local, const std::string& user) const override;
  Eigen::Vector3d spatial_position(const ConstVector& q,
                                   const Eigen::Vector3d& local) const override;
  Eigen::Vector3d spatial_velocity(const ConstVector& q, const ConstVector& v,
                                   const Eigen::Vector3d& local) const override;
  void spatial_position_jacobian(const ConstVector& q, const Eigen::Vector3d& local,
                                 Eigen::Ref<Eigen::MatrixXd> jacobian) const override;
  // The centre of mass of the deformed cable.
  Eigen::Vector3d spatial_reference_point(const ConstVector& q) const override;

 private:
  int element_of(double s, double& x) const;

  AncfCableSpec spec_;
  double length_ = 0.0;
  double element_length_ = 0.0;
};

}  // namespace fsi::mbd::detail
