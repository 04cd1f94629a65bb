#pragma once
// What a force element reports to a sensor (internal): the tension of a spring along its line, or
// the torque of a rotational spring on its first body. force_element_force (fsi/mbd/readouts.hpp)
// reads it.

#include <Eigen/Dense>

namespace fsi::mbd::detail {

class MeasuredForce {
 public:
  virtual ~MeasuredForce() = default;
  virtual double measured_force(double time, const Eigen::VectorXd& q,
                                const Eigen::VectorXd& v) const = 0;
};

}  // namespace fsi::mbd::detail
