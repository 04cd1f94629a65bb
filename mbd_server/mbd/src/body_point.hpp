#pragma once
// A material point of a body, or a fixed point of the ground, as seen from the model's full
// coordinate vector q: the building block of joints and spring-dampers (internal).

#include <Eigen/Dense>

#include "body.hpp"

namespace fsi::mbd::detail {

class BodyPoint {
 public:
  // body == nullptr: a ground point at the world position `local`.
  BodyPoint(const Body* body, int offset, const Eigen::Vector2d& local)
      : body_(body), offset_(offset), local_(local) {}

  bool on_ground() const { return body_ == nullptr; }
  Eigen::Vector2d position(const Eigen::VectorXd& q) const;
  Eigen::Vector2d velocity(const Eigen::VectorXd& q, const Eigen::VectorXd& v) const;
  // Adds sign * dr/dq into the 2 x n matrix `jacobian`.
  void add_jacobian(const Eigen::VectorXd& q, double sign, Eigen::MatrixXd& jacobian) const;
  // Adds sign * d/dq [(dr/dq) v] (2 x n) into `jacobian`.
  void add_velocity_jacobian(const Eigen::VectorXd& q, const Eigen::VectorXd& v, double sign,
                             Eigen::MatrixXd& jacobian) const;
  // The acceleration-free part of d^2r/dt^2: d/dq [(dr/dq) v] v.
  Eigen::Vector2d acceleration_remainder(const Eigen::VectorXd& q, const Eigen::VectorXd& v) const;
  // Adds d/dq [(dr/dq)^T f] at constant f (n x n) into `derivative`.
  void add_load_derivative(const Eigen::VectorXd& q, const Eigen::Vector2d& force,
                           Eigen::MatrixXd& derivative) const;

 private:
  auto block(const Eigen::VectorXd& x) const {
    return x.segment(offset_, body_->coordinate_count());
  }

  const Body* body_;
  int offset_;
  Eigen::Vector2d local_;
};

}  // namespace fsi::mbd::detail
