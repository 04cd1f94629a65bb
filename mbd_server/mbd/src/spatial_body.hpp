#pragma once
// Spatial (3D) bodies (internal). A model holds either planar bodies (body.hpp: RigidBody2D,
// AncfBeam2D, points in the plane) or spatial ones (this file: RigidBody3D, PointMass3D,
// AncfCable3D, points in space); Model refuses a mix. A spatial body is a Body for everything
// that does not depend on the dimension (coordinates, mass, internal forces) and adds the
// spatial point functions; the planar point functions of Body are never called on it (Model
// routes by the body's kind) and assert.
//
// Every spatial body here has a constant mass matrix and material points that are LINEAR in its
// coordinates (r = J(local) q_b): natural coordinates of the rigid body, the point mass, the
// cable's centre line. So the point Jacobians do not depend on q and the load derivatives and
// velocity Jacobians vanish; the interface still carries them for later element types.

#include <Eigen/Dense>

#include <string>

#include "body.hpp"
#include "body_point.hpp"

namespace fsi::mbd::detail {

class SpatialBody : public Body {
 public:
  virtual void add_spatial_gravity_force(const Eigen::Vector3d& acceleration,
                                         Eigen::Ref<Eigen::VectorXd> force) const = 0;
  virtual double spatial_gravity_potential(const ConstVector& q,
                                           const Eigen::Vector3d& acceleration) const = 0;
  // Throws fsi::Error naming `user` if `local` is not a material point of the body.
  virtual void check_spatial_local(const Eigen::Vector3d& local, const std::string& user) const = 0;
  virtual Eigen::Vector3d spatial_position(const ConstVector& q,
                                           const Eigen::Vector3d& local) const = 0;
  virtual Eigen::Vector3d spatial_velocity(const ConstVector& q, const ConstVector& v,
                                           const Eigen::Vector3d& local) const = 0;
  // dr/dq (3 x n_b), written.
  virtual void spatial_position_jacobian(const ConstVector& q, const Eigen::Vector3d& local,
                                         Eigen::Ref<Eigen::MatrixXd> jacobian) const = 0;
  // d/dq [(dr/dq) v] (3 x n_b), written; zero for points linear in q.
  virtual void spatial_velocity_jacobian(const ConstVector& /*q*/, const ConstVector& /*v*/,
                                         const Eigen::Vector3d& /*local*/,
                                         Eigen::Ref<Eigen::MatrixXd> jacobian) const {
    jacobian.setZero();
  }
  // Adds (dr/dq)^T f (size n_b); the default goes through spatial_position_jacobian (O(n_b)).
  virtual void add_spatial_point_load(const ConstVector& q, const Eigen::Vector3d& local,
                                      const Eigen::Vector3d& force,
                                      Eigen::Ref<Eigen::VectorXd> generalised_force) const {
    Eigen::MatrixXd jacobian(3, coordinate_count());
    spatial_position_jacobian(q, local, jacobian);
    generalised_force += jacobian.transpose() * force;
  }
  // d/dq [(dr/dq)^T f] (n_b x n_b, body coordinates), added; nothing for points linear in q.
  virtual void add_spatial_point_load_derivative(const ConstVector& /*q*/,
                                                 const Eigen::Vector3d& /*local*/,
                                                 const Eigen::Vector3d& /*force*/,
                                                 MatrixSink& /*derivative*/) const {}
  // The point torques of resultants are taken about (the centre of mass).
  virtual Eigen::Vector3d spatial_reference_point(const ConstVector& q) const = 0;

  // --- the planar interface, which a spatial body does not offer ---
  void add_gravity_force(const Eigen::Vector2d&, Eigen::Ref<Eigen::VectorXd>) const final {
    planar_call();
  }
  double gravity_potential(const ConstVector&, const Eigen::Vector2d&) const final {
    planar_call();
    return 0.0;
  }
  Eigen::Vector2d position(const ConstVector&, const Eigen::Vector2d&) const final {
    planar_call();
    return {};
  }
  Eigen::Vector2d velocity(const ConstVector&, const ConstVector&,
                           const Eigen::Vector2d&) const final {
    planar_call();
    return {};
  }
  void position_jacobian(const ConstVector&, const Eigen::Vector2d&,
                         Eigen::Ref<Eigen::MatrixXd>) const final {
    planar_call();
  }
  void velocity_jacobian(const ConstVector&, const ConstVector&, const Eigen::Vector2d&,
                         Eigen::Ref<Eigen::MatrixXd>) const final {
    planar_call();
  }
  using Body::add_point_load_derivative;
  void add_point_load_derivative(const ConstVector&, const Eigen::Vector2d&, const Eigen::Vector2d&,
                                 MatrixSink&) const final {
    planar_call();
  }
  void add_point_load(const ConstVector&, const Eigen::Vector2d&, const Eigen::Vector2d&,
                      Eigen::Ref<Eigen::VectorXd>) const final {
    planar_call();
  }
  Eigen::Vector2d reference_point(const ConstVector&) const final {
    planar_call();
    return {};
  }

 private:
  [[noreturn]] void planar_call() const;
};

// A material point of a spatial body, or a fixed point of space, seen from the full q (the
// spatial counterpart of BodyPoint).
class SpatialPoint {
 public:
  // body == nullptr: a fixed point at the world position `local`.
  SpatialPoint(const SpatialBody* body, int offset, const Eigen::Vector3d& local)
      : body_(body), offset_(offset), local_(local) {}

  bool on_ground() const { return body_ == nullptr; }
  const SpatialBody* body() const { return body_; }
  const Eigen::Vector3d& local() const { return local_; }
  Eigen::Vector3d position(const Eigen::VectorXd& q) const;
  Eigen::Vector3d velocity(const Eigen::VectorXd& q, const Eigen::VectorXd& v) const;
  // Adds sign * dr/dq (3 x n, its non-zero columns) to `jacobian`.
  void add_jacobian(const Eigen::VectorXd& q, double sign, SpatialColumns& jacobian) const;
  // Adds sign * d/dq [(dr/dq) v] (3 x n, its non-zero columns) to `jacobian`.
  void add_velocity_jacobian(const Eigen::VectorXd& q, const Eigen::VectorXd& v, double sign,
                             SpatialColumns& jacobian) const;
  // The acceleration-free part of d^2r/dt^2.
  Eigen::Vector3d acceleration_remainder(const Eigen::VectorXd& q, const Eigen::VectorXd& v) const;
  // Adds d/dq [(dr/dq)^T f] at constant f (n x n) into `derivative`.
  void add_load_derivative(const Eigen::VectorXd& q, const Eigen::Vector3d& force,
                           MatrixSink& derivative) const;
  // Adds the generalised force (dr/dq)^T f of a world-frame force f (size n).
  void add_load(const Eigen::VectorXd& q, const Eigen::Vector3d& force,
                Eigen::VectorXd& generalised_force) const;

 private:
  auto block(const Eigen::VectorXd& x) const {
    return x.segment(offset_, body_->coordinate_count());
  }

  const SpatialBody* body_;
  int offset_;
  Eigen::Vector3d local_;
};

}  // namespace fsi::mbd::detail
