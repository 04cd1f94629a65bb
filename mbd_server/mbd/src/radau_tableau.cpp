#include <cmath>
#include <string>
#include <utility>

#include "fsi/common/error.hpp"
#include "fsi/mbd/integrator.hpp"

namespace fsi::mbd {
namespace {

[[noreturn]] void throw_unavailable(const std::string& family, int stages, const char* choices) {
  throw Error(family + " with " + std::to_string(stages) + " stages is not available",
              "integrator options", choices);
}

// Both families collocate with c_s = 1, so b is the last row of a (stiffly accurate).
ButcherTableau stiffly_accurate(std::string name, ButcherTableau tableau, int order) {
  tableau.name = std::move(name);
  tableau.b = tableau.a.row(tableau.a.rows() - 1).transpose();
  tableau.order = order;
  return tableau;
}

}  // namespace

// Radau IIA: collocation at the right Radau points (zeros of d^(s-1)/dx^(s-1) [x^(s-1) (x-1)^s]
// on [0, 1]), so c_s = 1 and the last row of a equals b (Hairer & Wanner, Solving ODEs II,
// §IV.5, Table 5.5 for s = 3).
ButcherTableau radau_iia(int stages) {
  ButcherTableau tableau;
  switch (stages) {
    case 1:
      tableau.a = Eigen::MatrixXd::Constant(1, 1, 1.0);
      tableau.c = Eigen::VectorXd::Constant(1, 1.0);
      break;
    case 2:
      tableau.a.resize(2, 2);
      tableau.a << 5.0 / 12.0, -1.0 / 12.0,  //
          3.0 / 4.0, 1.0 / 4.0;
      tableau.c.resize(2);
      tableau.c << 1.0 / 3.0, 1.0;
      break;
    case 3: {
      const double root6 = std::sqrt(6.0);
      tableau.a.resize(3, 3);
      tableau.a << (88.0 - 7.0 * root6) / 360.0, (296.0 - 169.0 * root6) / 1800.0,
          (-2.0 + 3.0 * root6) / 225.0,  //
          (296.0 + 169.0 * root6) / 1800.0, (88.0 + 7.0 * root6) / 360.0,
          (-2.0 - 3.0 * root6) / 225.0,  //
          (16.0 - root6) / 36.0, (16.0 + root6) / 36.0, 1.0 / 9.0;
      tableau.c.resize(3);
      tableau.c << (4.0 - root6) / 10.0, (4.0 + root6) / 10.0, 1.0;
      break;
    }
    default:
      throw_unavailable("Radau IIA", stages, "choose 1, 2 or 3 stages (orders 1, 3, 5)");
  }
  return stiffly_accurate("Radau IIA", std::move(tableau), 2 * stages - 1);
}

// Lobatto IIIA: collocation at the Lobatto points (c_1 = 0, c_s = 1), so the first row of a is
// zero and the last equals b (Hairer & Wanner, Solving ODEs II, §IV.5, Table 5.7).
ButcherTableau lobatto_iiia(int stages) {
  ButcherTableau tableau;
  switch (stages) {
    case 2:
      tableau.a.resize(2, 2);
      tableau.a << 0.0, 0.0,  //
          0.5, 0.5;
      tableau.c.resize(2);
      tableau.c << 0.0, 1.0;
      break;
    case 3:
      tableau.a.resize(3, 3);
      tableau.a << 0.0, 0.0, 0.0,              //
          5.0 / 24.0, 1.0 / 3.0, -1.0 / 24.0,  //
          1.0 / 6.0, 2.0 / 3.0, 1.0 / 6.0;
      tableau.c.resize(3);
      tableau.c << 0.0, 0.5, 1.0;
      break;
    default:
      throw_unavailable("Lobatto IIIA", stages,
                        "choose 2 or 3 stages (orders 2, 4; 2 on constrained systems)");
  }
  return stiffly_accurate("Lobatto IIIA", std::move(tableau), 2 * stages - 2);
}

ButcherTableau butcher_tableau(TableauFamily family, int stages) {
  return family == TableauFamily::LobattoIIIA ? lobatto_iiia(stages) : radau_iia(stages);
}

}  // namespace fsi::mbd
