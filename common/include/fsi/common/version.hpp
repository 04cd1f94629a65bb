#pragma once
#include <string_view>

namespace fsi {

// Version of this software (CMake project version) and the git revision it was built from.
std::string_view software_version();
std::string_view git_revision();

}  // namespace fsi
