#pragma once
// Numbers and points in every module's messages and logs: how they print, in one place.

#include <span>
#include <string>

namespace fsi {

// `digits` significant digits in printf's "%g" style ("0.0123", "1.75e+04").
std::string significant(double value, int digits);

// The shortest text that reads back as the same double ("0.1", not "0.10000000000000001"): an
// input value quoted back to its author exactly.
std::string exact(double value);

// A point as "(x, y)" or "(x, y, z)", each coordinate with `digits` significant digits, or
// exactly when `digits` is 0.
std::string point_text(std::span<const double> point, int digits);

}  // namespace fsi
