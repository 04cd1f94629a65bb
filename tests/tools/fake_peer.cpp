// A scripted peer for fault tests: speaks the protocol with a chosen version but does nothing
// else. `fake_peer client HOST PORT MAJOR` sends Hello and prints what comes back;
// `fake_peer server PORT_FILE MAJOR` accepts one client and answers its Hello with a Welcome
// written in the given major version.
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>

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
    if (mode == "server") {
      options.major = static_cast<std::uint16_t>(std::atoi(argv[3]));
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
