#pragma once
// The text of the fsi::Error a test provokes, shared by the engine's tests that read error
// messages (over the project-wide test_support::message_thrown).

#include <string>

#include "fsi/test_support/thrown.hpp"

namespace fsi::mbd::testing {

// The message of the fsi::Error that `action` throws, or `when_accepted` when it throws none
// (a text no expectation matches, so a failing test shows it).
template <typename Action>
std::string error_message(Action&& action, std::string when_accepted = "accepted") {
  return test_support::message_thrown(action, when_accepted);
}

}  // namespace fsi::mbd::testing
