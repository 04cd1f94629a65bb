#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <future>
#include <thread>

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include "fsi/protocol/channel.hpp"

namespace fsi::protocol {
namespace {

using namespace std::chrono_literals;
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

TEST(Channel, ExchangesMessagesOverLoopback) {
  Listener listener("127.0.0.1", 0);
  ASSERT_GT(listener.port(), 0);
  auto client = std::async(std::launch::async, [port = listener.port()] {
    Channel channel = Channel::connect("127.0.0.1", port, 5s);
    channel.send(Hello{"test", "here", 2, 0});
    const auto welcome = channel.expect<Welcome>(5s);
    Step step = channel.expect<Step>(5s);
    Forces forces;
    forces.step = step.step;
    forces.forces = step.positions;
    channel.send(forces);
    return welcome.run_name;
  });
  Channel server = listener.accept(5s);
  const auto hello = server.expect<Hello>(5s);
  EXPECT_EQ(hello.mpi_ranks, 2u);
  server.send(Welcome{0, 0, "test", "loopback"});
  server.send(Step{3, 1.0, 0.5, {1.5, -2.5}, {0, 0}});
  const Forces forces = server.expect<Forces>(5s);
  EXPECT_EQ(forces.step, 3u);
  EXPECT_EQ(forces.forces, (std::vector<double>{1.5, -2.5}));
  EXPECT_EQ(client.get(), "loopback");
}

TEST(Channel, ConnectRetriesUntilTheServerListens) {
  std::uint16_t port = 0;
  {
    Listener probe("127.0.0.1", 0);
    port = probe.port();
  }
  const auto start = Clock::now();
  auto client = std::async(std::launch::async, [port] {
    Channel channel = Channel::connect("127.0.0.1", port, 10s);
    channel.send(Shutdown{"hello late server"});
  });
  std::this_thread::sleep_for(300ms);
  Listener listener("127.0.0.1", port);
  Channel server = listener.accept(10s);
  EXPECT_EQ(server.expect<Shutdown>(5s).reason, "hello late server");
  client.get();
  EXPECT_GE(seconds_since(start), 0.3);
}

TEST(Channel, ConnectGivesUpWithAClearMessage) {
  std::uint16_t port = 0;
  {
    Listener probe("127.0.0.1", 0);
    port = probe.port();
  }
  const auto start = Clock::now();
  try {
    Channel::connect("127.0.0.1", port, 400ms);
    FAIL() << "connected to nothing";
  } catch (const ProtocolError& error) {
    const std::string text = error.what();
    EXPECT_NE(text.find("cannot connect to fsi-server at 127.0.0.1:" + std::to_string(port)),
              std::string::npos)
        << text;
  }
  EXPECT_LT(seconds_since(start), 3.0);
}

TEST(Channel, PeerClosingEndsTheWaitAtOnce) {
  Listener listener("127.0.0.1", 0);
  auto client = std::async(std::launch::async, [port = listener.port()] {
    Channel channel = Channel::connect("127.0.0.1", port, 5s);
    std::this_thread::sleep_for(100ms);
    channel.close();
  });
  Channel server = listener.accept(5s);
  const auto start = Clock::now();
  try {
    server.receive(30s, "Forces");
    FAIL() << "received from a closed connection";
  } catch (const ProtocolError& error) {
    EXPECT_NE(std::string(error.what()).find("connection closed by peer"), std::string::npos);
    EXPECT_NE(std::string(error.what()).find("waiting for Forces"), std::string::npos);
  }
  EXPECT_LT(seconds_since(start), 2.0);
  client.get();
}

// A peer that writes part of a frame and then goes silent, through a raw socket.
class RawPeer {
 public:
  explicit RawPeer(std::uint16_t port) : fd_(::socket(AF_INET, SOCK_STREAM, 0)) {
    sockaddr_in address{};
    address.sin_family = AF_INET;
    address.sin_port = htons(port);
    address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    if (::connect(fd_, reinterpret_cast<sockaddr*>(&address), sizeof address) != 0) {
      throw std::runtime_error("raw connect failed");
    }
  }
  ~RawPeer() { ::close(fd_); }
  void write(std::span<const std::byte> bytes) {
    if (::send(fd_, bytes.data(), bytes.size(), 0) != static_cast<ssize_t>(bytes.size())) {
      throw std::runtime_error("raw send failed");
    }
  }

 private:
  int fd_;
};

TEST(Channel, HalfAFrameThenSilenceTimesOut) {
  Listener listener("127.0.0.1", 0);
  for (std::size_t cut : {10ul, 30ul}) {  // inside the header, inside the payload
    RawPeer peer(listener.port());
    Channel server = listener.accept(5s);
    const auto frame = encode_frame(MessageType::Forces, std::vector<std::byte>(100));
    peer.write(std::span(frame).first(cut));
    const auto start = Clock::now();
    try {
      server.receive(500ms, "Forces");
      FAIL() << "received from a silent peer";
    } catch (const ProtocolError& error) {
      EXPECT_NE(std::string(error.what()).find("within 0.5 s while waiting for Forces"),
                std::string::npos)
          << error.what();
    }
    const double waited = seconds_since(start);
    EXPECT_GE(waited, 0.45);
    EXPECT_LT(waited, 1.5);
  }
}

TEST(Channel, CorruptedFrameFromPeerNamesTheFault) {
  Listener listener("127.0.0.1", 0);
  RawPeer peer(listener.port());
  Channel server = listener.accept(5s);
  auto frame = encode_frame(MessageType::Step, encode(Step{1, 0, 1, {1}, {1}}));
  frame.back() ^= std::byte{0x40};
  peer.write(frame);
  try {
    server.receive(5s, "Step");
    FAIL();
  } catch (const ProtocolError& error) {
    EXPECT_NE(std::string(error.what()).find("CRC-32C mismatch in Step frame"), std::string::npos);
  }
}

TEST(Channel, ErrorFromPeerIsReportedByExpect) {
  Listener listener("127.0.0.1", 0);
  auto client = std::async(std::launch::async, [port = listener.port()] {
    Channel channel = Channel::connect("127.0.0.1", port, 5s);
    channel.send(ErrorMessage{ErrorCode::SetupFailed, "script1:7: unknown keyword"});
  });
  Channel server = listener.accept(5s);
  try {
    server.expect<Ready>(5s);
    FAIL();
  } catch (const ProtocolError& error) {
    EXPECT_NE(std::string(error.what()).find("peer reported: script1:7: unknown keyword"),
              std::string::npos);
  }
  client.get();
}

TEST(Channel, OtherMajorVersionHelloIsDecodableButStepIsNot) {
  Listener listener("127.0.0.1", 0);
  auto client = std::async(std::launch::async, [port = listener.port()] {
    ChannelOptions future_version;
    future_version.major = 2;
    future_version.minor = 4;
    Channel channel = Channel::connect("127.0.0.1", port, 5s, future_version);
    channel.send(Hello{"9.9", "future", 1, 0});
    channel.send(SnapshotRequest{1});
  });
  Channel server = listener.accept(5s);
  EXPECT_NO_THROW(server.expect<Hello>(5s));
  EXPECT_EQ(server.peer_major(), 2);
  EXPECT_EQ(server.peer_minor(), 4);
  try {
    server.receive(5s);
    FAIL();
  } catch (const ProtocolError& error) {
    EXPECT_NE(std::string(error.what()).find("protocol 2.4"), std::string::npos);
  }
  client.get();
}

TEST(Listener, BusyPortIsAClearError) {
  Listener first("127.0.0.1", 0);
  try {
    Listener second("127.0.0.1", first.port());
    // SO_REUSEADDR does not allow two listeners on one port on Linux.
    FAIL() << "two listeners on one port";
  } catch (const fsi::Error& error) {
    EXPECT_NE(std::string(error.what()).find("cannot listen on 127.0.0.1:"), std::string::npos);
  }
}

}  // namespace
}  // namespace fsi::protocol
