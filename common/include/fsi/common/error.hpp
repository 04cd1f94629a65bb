#pragma once
// The two error channels of the project (docs/user-guide.md, "Errors"):
//  - fsi::Error: a user's mistake or an environment fault (bad parameter, unreachable host,
//    protocol mismatch). Its message says what went wrong, where, and how to fix it.
//  - FSI_ASSERT: a programmer's mistake. Aborts with file and line; never used for user input.

#include <stdexcept>
#include <string>

namespace fsi {

class Error : public std::runtime_error {
 public:
  // what: the fault; where: file:line:column, message type, rank, ...; fix: what the user can do.
  Error(const std::string& what, const std::string& where = {}, const std::string& fix = {});

  const std::string& fault() const noexcept { return fault_; }
  const std::string& location() const noexcept { return location_; }
  const std::string& remedy() const noexcept { return remedy_; }

 private:
  std::string fault_;
  std::string location_;
  std::string remedy_;
};

// The place comes from __FILE__, __LINE__ and __func__ rather than std::source_location, which
// clang 14 (the fuzzing compiler, docs/testing.md) cannot provide with libstdc++ 12.
[[noreturn]] void assertion_failed(const char* expression, const char* file, unsigned line,
                                   const char* function, const std::string& detail);

}  // namespace fsi

#define FSI_ASSERT(condition, detail)                                              \
  do {                                                                             \
    if (!(condition)) {                                                            \
      ::fsi::assertion_failed(#condition, __FILE__, __LINE__, __func__, (detail)); \
    }                                                                              \
  } while (false)
