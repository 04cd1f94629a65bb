#pragma once
// Body element interface (internal): what the model needs from a body to assemble the equations
// of motion and to move its material points. A body owns a contiguous block of n_b generalised
// coordinates; every function receives only that block. Element types (planar rigid bodies,
// planar ANCF beams; later 3D bodies) implement this interface; the integrator never sees it.

#include <Eigen/Dense>

#include <string>

#include "fsi/mbd/matrix_sink.hpp"
#include "fsi/mbd/model.hpp"

namespace fsi::mbd::detail {

using ConstVector = Eigen::Ref<const Eigen::VectorXd>;

class Body {
 public:
  virtual ~Body() = default;

  virtual const std::string& name() const = 0;
  virtual int coordinate_count() const = 0;
  virtual void initial_state(Eigen::Ref<Eigen::VectorXd> q,
                             Eigen::Ref<Eigen::VectorXd> v) const = 0;
  // Adds the constant mass matrix block (n_b x n_b, body coordinates) to `block`, its non-zeros
  // only; a coordinate-dependent one needs a different stage formulation in the integrator.
  virtual void mass_matrix(MatrixSink& block) const = 0;
  // Generalised force of a uniform acceleration field (gravity), added to `force`.
  virtual void add_gravity_force(const Eigen::Vector2d& acceleration,
                                 Eigen::Ref<Eigen::VectorXd> force) const = 0;
  virtual double gravity_potential(const ConstVector& q,
                                   const Eigen::Vector2d& acceleration) const = 0;

  // Internal generalised force Q_int(q, v) of a deformable body (elastic and, if modelled,
  // dissipative), added to `force`; it enters F like any applied force. Rigid bodies have none.
  virtual void add_internal_force(const ConstVector& /*q*/, const ConstVector& /*v*/,
                                  Eigen::Ref<Eigen::VectorXd> /*force*/) const {}
  // Its exact derivatives dQ_int/dq and dQ_int/dv (n_b x n_b each, body coordinates), added
  // entry by entry (a beam element by element): the Newton matrix and the static solver use
  // them directly.
  virtual void add_internal_force_derivatives(const ConstVector& /*q*/, const ConstVector& /*v*/,
                                              MatrixSink& /*by_position*/,
                                              MatrixSink& /*by_velocity*/) const {}
  // The potential of the elastic part of Q_int (strain energy), zero for rigid bodies.
  virtual double internal_energy(const ConstVector& /*q*/) const { return 0.0; }
  // Throws fsi::Error naming `user` if `local` is not a material point of the body (e.g. an
  // axial coordinate beyond a beam's end). Every point of the plane belongs to a rigid body.
  virtual void check_local_coordinates(const Eigen::Vector2d& /*local*/,
                                       const std::string& /*user*/) const {}

  // Material point with body-fixed local coordinates.
  virtual Eigen::Vector2d position(const ConstVector& q, const Eigen::Vector2d& local) const = 0;
  virtual Eigen::Vector2d velocity(const ConstVector& q, const ConstVector& v,
                                   const Eigen::Vector2d& local) const = 0;
  // dr/dq (2 x n_b), written.
  virtual void position_jacobian(const ConstVector& q, const Eigen::Vector2d& local,
                                 Eigen::Ref<Eigen::MatrixXd> jacobian) const = 0;
  // d/dq [(dr/dq) v] at fixed v (2 x n_b), written: how the point's velocity changes with the
  // coordinates. Times v it is the acceleration-free part of d^2r/dt^2 (the centripetal term).
  virtual void velocity_jacobian(const ConstVector& q, const ConstVector& v,
                                 const Eigen::Vector2d& local,
                                 Eigen::Ref<Eigen::MatrixXd> jacobian) const = 0;
  // Adds (dr/dq)^T f of a world-frame force f at a material point (size n_b). The default goes
  // through position_jacobian (O(n_b)); a beam adds only its element's 8 entries, so that many
  // loaded markers on a long beam cost O(markers), not O(markers x n_b).
  virtual void add_point_load(const ConstVector& q, const Eigen::Vector2d& local,
                              const Eigen::Vector2d& force,
                              Eigen::Ref<Eigen::VectorXd> generalised_force) const {
    Eigen::MatrixXd jacobian(2, coordinate_count());
    position_jacobian(q, local, jacobian);
    generalised_force += jacobian.transpose() * force;
  }
  // d/dq [(dr/dq)^T f] for a constant world-frame force f (n_b x n_b, body coordinates), added.
  virtual void add_point_load_derivative(const ConstVector& q, const Eigen::Vector2d& local,
                                         const Eigen::Vector2d& force,
                                         MatrixSink& derivative) const = 0;
  // The point torques of resultants are taken about (the centre of mass of a rigid body).
  virtual Eigen::Vector2d reference_point(const ConstVector& q) const = 0;

  // Dense forms of the matrix outputs above, into matrices of the body's size (tests).
  void mass_matrix(Eigen::Ref<Eigen::MatrixXd> block) const {
    block.setZero();
    DenseMatrixSink sink(block);
    mass_matrix(sink);
  }
  void add_internal_force_derivatives(const ConstVector& q, const ConstVector& v,
                                      Eigen::Ref<Eigen::MatrixXd> by_position,
                                      Eigen::Ref<Eigen::MatrixXd> by_velocity) const {
    DenseMatrixSink position_sink(by_position), velocity_sink(by_velocity);
    add_internal_force_derivatives(q, v, position_sink, velocity_sink);
  }
  void add_point_load_derivative(const ConstVector& q, const Eigen::Vector2d& local,
                                 const Eigen::Vector2d& force,
                                 Eigen::Ref<Eigen::MatrixXd> derivative) const {
    DenseMatrixSink sink(derivative);
    add_point_load_derivative(q, local, force, sink);
  }
};

class RigidBody2D final : public Body {
 public:
  explicit RigidBody2D(const RigidBody2DSpec& spec);  // throws fsi::Error for invalid values

  const RigidBody2DSpec& spec() const { return spec_; }
  double initial_coordinate(Coordinate coordinate) const;

  const std::string& name() const override { return spec_.name; }
  int coordinate_count() const override { return 3; }
  void initial_state(Eigen::Ref<Eigen::VectorXd> q, Eigen::Ref<Eigen::VectorXd> v) const override;
  using Body::add_point_load_derivative;
  using Body::mass_matrix;
  void mass_matrix(MatrixSink& block) const override;
  void add_gravity_force(const Eigen::Vector2d& acceleration,
                         Eigen::Ref<Eigen::VectorXd> force) const override;
  double gravity_potential(const ConstVector& q,
                           const Eigen::Vector2d& acceleration) const override;
  Eigen::Vector2d position(const ConstVector& q, const Eigen::Vector2d& local) const override;
  Eigen::Vector2d velocity(const ConstVector& q, const ConstVector& v,
                           const Eigen::Vector2d& local) const override;
  void position_jacobian(const ConstVector& q, const Eigen::Vector2d& local,
                         Eigen::Ref<Eigen::MatrixXd> jacobian) const override;
  void velocity_jacobian(const ConstVector& q, const ConstVector& v, const Eigen::Vector2d& local,
                         Eigen::Ref<Eigen::MatrixXd> jacobian) const override;
  void add_point_load_derivative(const ConstVector& q, const Eigen::Vector2d& local,
                                 const Eigen::Vector2d& force,
                                 MatrixSink& derivative) const override;
  Eigen::Vector2d reference_point(const ConstVector& q) const override;

 private:
  RigidBody2DSpec spec_;
};

}  // namespace fsi::mbd::detail
