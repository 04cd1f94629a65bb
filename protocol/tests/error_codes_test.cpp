// The Error code each fault is answered with (docs/protocol.md §7), from the exception a real
// Channel throws for it.
#include <gtest/gtest.h>

#include <chrono>
#include <future>
#include <stdexcept>
#include <string>

#include "fsi/protocol/channel.hpp"
#include "fsi/protocol/messages.hpp"

namespace fsi::protocol {
namespace {

using namespace std::chrono_literals;

// Runs `client` against a fresh loopback server channel and returns the code the server would
// send for the fault its `server_wait` throws.
template <class Client, class Wait>
std::optional<ErrorCode> server_answer(Client client, Wait server_wait) {
  Listener listener("127.0.0.1", 0);
  auto peer = std::async(std::launch::async, [&client, port = listener.port()] {
    Channel channel = Channel::connect("127.0.0.1", port, 5s);
    client(channel);
    channel.close();
  });
  Channel server = listener.accept(5s);
  std::optional<ErrorCode> code;
  try {
    server_wait(server);
    ADD_FAILURE() << "the wait did not fail";
  } catch (const std::exception& failure) {
    code = error_code_for(failure, ErrorCode::SetupFailed);
  }
  server.close();
  peer.get();
  return code;
}

TEST(ProtocolErrorCodes, AMessageOutOfTurnIsAnsweredWithUnexpectedMessage) {
  const auto code =
      server_answer([](Channel& c) { c.send(Goodbye{}); }, [](Channel& s) { s.expect<Ready>(5s); });
  EXPECT_EQ(code, ErrorCode::UnexpectedMessage);
}

TEST(ProtocolErrorCodes, ATimeoutIsAnsweredWithPeerAborted) {
  const auto code = server_answer([](Channel&) { std::this_thread::sleep_for(400ms); },
                                  [](Channel& s) { s.expect<Ready>(100ms); });
  EXPECT_EQ(code, ErrorCode::PeerAborted);
}

TEST(ProtocolErrorCodes, AFrameOfAnotherMajorIsAnsweredWithVersionMismatch) {
  ChannelOptions future;
  future.major = kMajorVersion + 1;
  Listener listener("127.0.0.1", 0);
  auto peer = std::async(std::launch::async, [&future, port = listener.port()] {
    Channel channel = Channel::connect("127.0.0.1", port, 5s, future);
    channel.send(Ready{});
    channel.close();
  });
  Channel server = listener.accept(5s);
  try {
    server.expect<Ready>(5s);
    ADD_FAILURE() << "a frame of another major was accepted";
  } catch (const std::exception& failure) {
    EXPECT_EQ(error_code_for(failure, ErrorCode::SetupFailed), ErrorCode::VersionMismatch)
        << failure.what();
  }
  server.close();
  peer.get();
}

TEST(ProtocolErrorCodes, ThePeersOwnErrorIsNeverAnswered) {
  const auto code = server_answer(
      [](Channel& c) {
        c.send(ErrorMessage{ErrorCode::LiggghtsError, "ERROR: Lost atoms"});
      },
      [](Channel& s) { s.expect<Ready>(5s); });
  EXPECT_FALSE(code.has_value());
}

TEST(ProtocolErrorCodes, AClosedConnectionIsAProtocolFault) {
  const auto code = server_answer([](Channel&) {}, [](Channel& s) { s.expect<Ready>(5s); });
  EXPECT_EQ(code, ErrorCode::MalformedMessage);
}

TEST(ProtocolErrorCodes, AFailureOutsideTheProtocolGetsTheCallersCode) {
  EXPECT_EQ(error_code_for(std::runtime_error("Newton failed"), ErrorCode::PeerAborted),
            ErrorCode::PeerAborted);
  EXPECT_EQ(
      error_code_for(fsi::Error("unknown command", "tank.in1:7", "fix it"), ErrorCode::SetupFailed),
      ErrorCode::SetupFailed);
}

}  // namespace
}  // namespace fsi::protocol
