#pragma once
// What the unit tests read from the errors they provoke: one place for every module's tests.

#include <string>

#include "fsi/common/error.hpp"

namespace fsi::test_support {

// The message of the `Error` that `action` throws. If it throws none, `if_none`: each test suite
// picks a text its expectations tell apart from any message ("" where an empty text means
// "accepted").
template <class Error = fsi::Error>
std::string message_thrown(auto&& action, const std::string& if_none = "") {
  try {
    action();
  } catch (const Error& error) {
    return error.what();
  }
  return if_none;
}

}  // namespace fsi::test_support
