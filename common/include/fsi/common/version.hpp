#pragma once
#include <string>
#include <string_view>

namespace fsi {

// Version of this software (CMake project version) and the git revision it was built from.
std::string_view software_version();
std::string_view git_revision();
// Both as every program's --version prints them: "0.1.0 (git 1a2b3c4)".
std::string version_text();

}  // namespace fsi
