#pragma once
// The text of the fsi::Error a test provokes, shared by the tests that read error messages.

#include <string>

#include "fsi/common/error.hpp"

namespace fsi::mbd::testing {

// The message of the fsi::Error that `action` throws, or `when_accepted` when it throws none
// (a text no expectation matches, so a failing test shows it).
template <typename Action>
std::string error_message(Action&& action, std::string when_accepted = "accepted") {
  try {
    action();
  } catch (const fsi::Error& error) {
    return error.what();
  }
  return when_accepted;
}

}  // namespace fsi::mbd::testing
