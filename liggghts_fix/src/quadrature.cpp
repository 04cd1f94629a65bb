#include "fsi/contact/quadrature.hpp"

#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

namespace fsi::contact {
namespace {

// Nodes x_k and weights w_k on [-1, 1], mapped to g = (1 + x)/2 and weight w/2.
constexpr QuadraturePoint mapped(double node, double weight) {
  return {0.5 * (1.0 + node), 0.5 * weight};
}

const std::array<QuadraturePoint, 1> kRule1{mapped(0.0, 2.0)};
const std::array<QuadraturePoint, 2> kRule2{mapped(-1.0 / std::sqrt(3.0), 1.0),
                                            mapped(1.0 / std::sqrt(3.0), 1.0)};
const std::array<QuadraturePoint, 3> kRule3{
    mapped(-std::sqrt(0.6), 5.0 / 9.0), mapped(0.0, 8.0 / 9.0), mapped(std::sqrt(0.6), 5.0 / 9.0)};
const double kNode4Inner = std::sqrt(3.0 / 7.0 - 2.0 / 7.0 * std::sqrt(6.0 / 5.0));
const double kNode4Outer = std::sqrt(3.0 / 7.0 + 2.0 / 7.0 * std::sqrt(6.0 / 5.0));
const double kWeight4Inner = (18.0 + std::sqrt(30.0)) / 36.0;
const double kWeight4Outer = (18.0 - std::sqrt(30.0)) / 36.0;
const std::array<QuadraturePoint, 4> kRule4{
    mapped(-kNode4Outer, kWeight4Outer), mapped(-kNode4Inner, kWeight4Inner),
    mapped(kNode4Inner, kWeight4Inner), mapped(kNode4Outer, kWeight4Outer)};
const double kNode5Inner = std::sqrt(5.0 - 2.0 * std::sqrt(10.0 / 7.0)) / 3.0;
const double kNode5Outer = std::sqrt(5.0 + 2.0 * std::sqrt(10.0 / 7.0)) / 3.0;
const double kWeight5Inner = (322.0 + 13.0 * std::sqrt(70.0)) / 900.0;
const double kWeight5Outer = (322.0 - 13.0 * std::sqrt(70.0)) / 900.0;
const std::array<QuadraturePoint, 5> kRule5{
    mapped(-kNode5Outer, kWeight5Outer), mapped(-kNode5Inner, kWeight5Inner),
    mapped(0.0, 128.0 / 225.0), mapped(kNode5Inner, kWeight5Inner),
    mapped(kNode5Outer, kWeight5Outer)};

}  // namespace

std::span<const QuadraturePoint> gauss_legendre(int points) {
  switch (points) {
    case 1:
      return kRule1;
    case 2:
      return kRule2;
    case 3:
      return kRule3;
    case 4:
      return kRule4;
    case 5:
      return kRule5;
    default:
      throw std::invalid_argument("Gauss-Legendre rule with " + std::to_string(points) +
                                  " points is not available; choose 1 to 5 points");
  }
}

}  // namespace fsi::contact
