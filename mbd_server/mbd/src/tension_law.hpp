#pragma once
// The laws of the force elements that act along a line or about an angle (internal): the tension
// (or torque) as a function of the elongation (twist), its rate and the time, with its partial
// derivatives for the Newton matrix and the work stored at zero rate for the energy balance.
//
//   LinearTension            k elongation + c rate, exact
//   PiecewiseLinearTension   a table of (elongation, tension) points plus c rate (thesis §6.5)
//   UserTension              a user's function; derivatives by central differences, energy by
//                            Gauss-Legendre quadrature

#include <Eigen/Core>
#include <functional>
#include <vector>

namespace fsi::mbd::detail {

// The tension of a point-to-point element and its partial derivatives.
struct Tension {
  double value = 0.0;
  double by_elongation = 0.0;
  double by_rate = 0.0;
};

class TensionLaw {
 public:
  virtual ~TensionLaw() = default;
  // Written by a user (a function given to the model), not one of the engine's own forms.
  virtual bool user() const { return false; }
  // A law may depend on the time [s] (a user's); the table and the linear law do not.
  virtual Tension at(double elongation, double rate, double time) const = 0;
  // The work stored by stretching from 0 to `elongation` at zero rate, with the law held at `time`.
  virtual double energy(double elongation, double time) const = 0;
};

// k * elongation + c * rate, exact.
class LinearTension final : public TensionLaw {
 public:
  LinearTension(double stiffness, double damping) : stiffness_(stiffness), damping_(damping) {}
  Tension at(double elongation, double rate, double) const override {
    return {stiffness_ * elongation + damping_ * rate, stiffness_, damping_};
  }
  double energy(double elongation, double) const override {
    return 0.5 * stiffness_ * elongation * elongation;
  }

 private:
  double stiffness_;
  double damping_;
};

// Piecewise-linear in the elongation through the table points, continued with the end slopes,
// plus damping * rate (the spring actor of thesis §6.5).
class PiecewiseLinearTension final : public TensionLaw {
 public:
  PiecewiseLinearTension(std::vector<Eigen::Vector2d> points, double damping);
  Tension at(double elongation, double rate, double time) const override;
  double energy(double elongation, double time) const override;

 private:
  // The segment whose line holds at `elongation` (the end ones beyond the table).
  std::size_t segment(double elongation) const;
  double spring(double elongation) const;

  std::vector<Eigen::Vector2d> points_;
  double damping_;
};

// A user function of (elongation, rate, time); partial derivatives by central differences, energy
// by Gauss-Legendre quadrature over [0, elongation] at the given time.
class UserTension final : public TensionLaw {
 public:
  explicit UserTension(std::function<double(double, double, double)> tension);
  bool user() const override { return true; }
  Tension at(double elongation, double rate, double time) const override;
  double energy(double elongation, double time) const override;

 private:
  std::function<double(double, double, double)> tension_;
};

}  // namespace fsi::mbd::detail
