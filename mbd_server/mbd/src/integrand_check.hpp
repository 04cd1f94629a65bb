#pragma once
// The check every integrator's set_integrand makes (fsi/mbd/integrand.hpp).

#include "fsi/mbd/integrand.hpp"

namespace fsi::mbd::detail {

// Throws fsi::Error, located at `where`, for a negative size or a size without a function.
void check_integrand(const Integrand& integrand, const char* where);

}  // namespace fsi::mbd::detail
