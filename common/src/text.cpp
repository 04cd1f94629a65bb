#include "fsi/common/text.hpp"

#include <charconv>
#include <cstdio>

namespace fsi {

std::string significant(double value, int digits) {
  char text[48];
  std::snprintf(text, sizeof text, "%.*g", digits, value);
  return text;
}

std::string exact(double value) {
  char text[40];
  const auto end = std::to_chars(text, text + sizeof text, value).ptr;
  return std::string(text, end);
}

std::string point_text(std::span<const double> point, int digits) {
  std::string text = "(";
  for (std::size_t k = 0; k < point.size(); ++k)
    text += (k ? ", " : "") + (digits > 0 ? significant(point[k], digits) : exact(point[k]));
  return text + ")";
}

}  // namespace fsi
