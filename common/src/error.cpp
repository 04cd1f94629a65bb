#include "fsi/common/error.hpp"

#include <cstdio>
#include <cstdlib>

namespace fsi {
namespace {

std::string compose(const std::string& what, const std::string& where, const std::string& fix) {
  std::string message;
  if (!where.empty()) message += where + ": ";
  message += what;
  if (!fix.empty()) message += "\n  how to fix: " + fix;
  return message;
}

}  // namespace

Error::Error(const std::string& what, const std::string& where, const std::string& fix)
    : std::runtime_error(compose(what, where, fix)), fault_(what), location_(where), remedy_(fix) {}

void assertion_failed(const char* expression, const char* file, unsigned line, const char* function,
                      const std::string& detail) {
  std::fprintf(
      stderr, "internal error (a bug, please report it): assertion '%s' failed at %s:%u (%s): %s\n",
      expression, file, line, function, detail.c_str());
  std::fflush(stderr);
  std::abort();
}

}  // namespace fsi
