#include "integrand_check.hpp"

#include <string>

#include "fsi/common/error.hpp"

namespace fsi::mbd::detail {

void check_integrand(const Integrand& integrand, const char* where) {
  if (integrand.size >= 0 && (integrand.size == 0 || integrand.evaluate)) return;
  throw Error("an integrand of size " + std::to_string(integrand.size) +
                  (integrand.size > 0 ? " has no function" : ""),
              where, "give a size >= 0 and, for a size > 0, its function");
}

}  // namespace fsi::mbd::detail
