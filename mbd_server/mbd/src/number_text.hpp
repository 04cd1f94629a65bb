#pragma once
// Numbers in the engine's messages (internal): `digits` significant digits, "%g" style — 9 are
// enough to see a residual and short enough to read; 17 show an input value exactly.

#include <cstdio>
#include <string>

namespace fsi::mbd::detail {

inline std::string number_text(double value, int digits = 9) {
  char text[40];
  std::snprintf(text, sizeof text, "%.*g", digits, value);
  return text;
}

}  // namespace fsi::mbd::detail
