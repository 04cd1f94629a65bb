#pragma once
// What the protocol tests read from the errors they provoke.

#include <cstddef>
#include <span>
#include <string>

#include "fsi/protocol/frame.hpp"
#include "fsi/protocol/messages.hpp"
#include "fsi/test_support/thrown.hpp"

namespace fsi::protocol::test {

inline bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

// What `action` throws as an Error (a ProtocolError unless told otherwise); if it returns, a text
// that no expectation matches, so the test fails showing it.
template <class Error = ProtocolError>
std::string error_of(auto&& action) {
  return test_support::message_thrown<Error>(action, "(no error: the call returned)");
}

inline std::string decode_error(MessageType type, std::span<const std::byte> payload) {
  return error_of([&] { decode(type, payload); });
}

inline std::string frame_error(std::span<const std::byte> frame,
                               std::size_t max_payload = kDefaultMaxPayload) {
  return error_of([&] { decode_frame(frame, max_payload); });
}

}  // namespace fsi::protocol::test
