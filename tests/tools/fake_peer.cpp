// A scripted peer for fault tests: speaks the protocol with a chosen version but does nothing
// else. `fake_peer client HOST PORT MAJOR` sends Hello and prints what comes back;
// `fake_peer server PORT_FILE MAJOR` accepts one client and answers its Hello with a Welcome
// written in the given major version.
// `fake_peer client-token HOST PORT TOKEN_FILE` opens a session with that token and prints every
// message type the server sends until it closes (so a test sees that no set-up data came).
// `fake_peer client-capabilities HOST PORT BITS` opens a session without token offering those
// session capabilities (4: a client of protocol 1.2, settling only) and prints every message
// type the server sends until it closes, with the text of an Error.
// `fake_peer impostor PORT_FILE TOKEN_FILE` plays a server that does not know the client's token:
// it ignores the client's proof and answers with a proof made from its own token.
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>

#include "fsi/protocol/auth.hpp"
#include "fsi/protocol/channel.hpp"

using namespace std::chrono_literals;
namespace protocol = fsi::protocol;

int main(int argc, char** argv) {
  if (argc < 4) {
    std::fprintf(stderr,
                 "usage: fake_peer client HOST PORT MAJOR | fake_peer server PORT_FILE MAJOR\n");
    return 2;
  }
  const std::string mode = argv[1];
  try {
    protocol::ChannelOptions options;
    if (mode == "client" && argc >= 5) {
      options.major = static_cast<std::uint16_t>(std::atoi(argv[4]));
      options.minor = 0;
      auto channel = protocol::Channel::connect(
          argv[2], static_cast<std::uint16_t>(std::atoi(argv[3])), 10s, options);
      channel.send(protocol::Hello{"fake-peer", "test", 1, 0});
      const protocol::Frame frame = channel.receive(10s, "the server's answer");
      const auto message = protocol::decode(frame.header.type, frame.payload);
      if (const auto* error = std::get_if<protocol::ErrorMessage>(&message)) {
        std::printf("server refused: %s\n", error->text.c_str());
        return 1;
      }
      std::printf("server answered with %s\n", protocol::name(frame.header.type).c_str());
      return 0;
    }
    if (mode == "client-token" && argc >= 5) {
      auto channel = protocol::Channel::connect(
          argv[2], static_cast<std::uint16_t>(std::atoi(argv[3])), 10s, options);
      protocol::ClientHandshake handshake;
      handshake.token = protocol::read_token_file(argv[4]);
      handshake.hello = protocol::Hello{"fake-peer", "test", 1, 0};
      handshake.timeout = 10s;
      int status = 0;
      try {
        protocol::open_session(channel, handshake);
        std::printf("authenticated\n");
      } catch (const std::exception& error) {
        std::printf("handshake failed: %s\n", error.what());
        status = 1;
      }
      // Whatever else the server sends before it closes the connection.
      try {
        while (true) {
          const protocol::Frame frame = channel.receive(10s, "anything");
          std::printf("then received %s\n", protocol::name(frame.header.type).c_str());
        }
      } catch (const protocol::ProtocolError& error) {
        std::printf("then: %s\n", error.fault().c_str());
      }
      return status;
    }
    if (mode == "client-capabilities" && argc >= 5) {
      auto channel = protocol::Channel::connect(
          argv[2], static_cast<std::uint16_t>(std::atoi(argv[3])), 10s, options);
      protocol::ClientHandshake handshake;
      handshake.hello = protocol::Hello{"fake-peer", "test", 1, 0};
      handshake.timeout = 10s;
      handshake.session_capabilities =
          static_cast<std::uint32_t>(std::strtoul(argv[4], nullptr, 0));
      const auto opened = protocol::open_session(channel, handshake);
      std::printf("session capabilities %u\n", static_cast<unsigned>(opened.capabilities));
      try {
        while (true) {
          const protocol::Frame frame = channel.receive(10s, "anything");
          std::printf("received %s\n", protocol::name(frame.header.type).c_str());
          const auto message = protocol::decode(frame.header.type, frame.payload);
          if (const auto* error = std::get_if<protocol::ErrorMessage>(&message)) {
            std::printf("error: [%s] %s\n", protocol::name(error->code).c_str(),
                        error->text.c_str());
          }
        }
      } catch (const protocol::ProtocolError& error) {
        std::printf("then: %s\n", error.fault().c_str());
      }
      return 0;
    }
    if (mode == "impostor" && argc >= 4) {
      const protocol::Token guess = protocol::read_token_file(argv[3]);
      protocol::Listener listener("127.0.0.1", 0, options);
      { std::ofstream(std::string(argv[2]) + ".tmp") << listener.port() << "\n"; }
      std::rename((std::string(argv[2]) + ".tmp").c_str(), argv[2]);
      auto channel = listener.accept(30s);
      channel.expect<protocol::Hello>(30s);
      protocol::AuthChallenge challenge{protocol::random_nonce()};
      channel.send(challenge);
      const auto response = channel.expect<protocol::AuthResponse>(30s);
      channel.send(protocol::AuthProof{
          protocol::server_tag(guess, response.client_nonce, challenge.server_nonce)});
      channel.send(protocol::Welcome{protocol::kMinorVersion, protocol::kCapabilityAuthentication,
                                     "impostor", "stolen"});
      channel.send(protocol::Setup{2, 1e-5, 0, {}, "evil.in", "print 'evil'", "b.in", ""});
      try {
        channel.expect<protocol::Ready>(30s);
        std::printf("client accepted the impostor\n");
      } catch (const protocol::ProtocolError& error) {
        std::printf("%s\n", error.what());
      }
      return 0;
    }
    if (mode == "server") {
      options.major = static_cast<std::uint16_t>(std::atoi(argv[3]));
      options.minor = 0;
      protocol::Listener listener("127.0.0.1", 0, options);
      { std::ofstream(std::string(argv[2]) + ".tmp") << listener.port() << "\n"; }
      std::rename((std::string(argv[2]) + ".tmp").c_str(), argv[2]);
      auto channel = listener.accept(30s);
      const protocol::Frame hello = channel.receive(30s, "Hello");
      std::printf("client said %s\n", protocol::name(hello.header.type).c_str());
      protocol::Welcome welcome;
      welcome.software_version = "fake-server";
      channel.send(welcome);
      // Stay until the client hangs up.
      try {
        channel.receive(30s, "anything");
      } catch (const protocol::ProtocolError& error) {
        std::printf("%s\n", error.what());
      }
      return 0;
    }
  } catch (const std::exception& error) {
    std::fprintf(stderr, "fake_peer: %s\n", error.what());
    return 3;
  }
  return 2;
}
