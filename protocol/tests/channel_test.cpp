#include <gtest/gtest.h>

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <cstring>
#include <future>
#include <memory>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "error_text.hpp"
#include "fsi/protocol/channel.hpp"

namespace fsi::protocol {
namespace {

using namespace test;

using namespace std::chrono_literals;
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// A port nobody listens on (the listener that found it is gone again).
std::uint16_t free_port() {
  Listener probe("127.0.0.1", 0);
  return probe.port();
}

// Each end's close() waits (up to ChannelOptions::close_linger) for the other end to close too, so
// tests close the server end before joining the client thread, and tests whose raw peer never
// closes use no linger.
ChannelOptions quick_close() {
  ChannelOptions options;
  options.close_linger = 0ms;
  return options;
}

// A peer that writes whatever bytes a test wants through a plain socket.
class RawPeer {
 public:
  explicit RawPeer(std::uint16_t port) : handle_(::socket(AF_INET, SOCK_STREAM, 0)) {
    sockaddr_in address{};
    address.sin_family = AF_INET;
    address.sin_port = htons(port);
    address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    if (::connect(handle_, reinterpret_cast<sockaddr*>(&address), sizeof address) != 0) {
      throw std::runtime_error("raw connect failed");
    }
  }
  ~RawPeer() { ::close(handle_); }
  RawPeer(const RawPeer&) = delete;
  RawPeer& operator=(const RawPeer&) = delete;

  void write(std::span<const std::byte> bytes) {
    if (::send(handle_, bytes.data(), bytes.size(), MSG_NOSIGNAL) !=
        static_cast<ssize_t>(bytes.size())) {
      throw std::runtime_error("raw send failed");
    }
  }

 private:
  int handle_;
};

// What a received frame's fault says, with a fresh raw connection per case.
std::string fault_from_raw_peer(std::span<const std::byte> bytes, ChannelOptions options) {
  Listener listener("127.0.0.1", 0, options);
  RawPeer peer(listener.port());
  Channel server = listener.accept(5s);
  peer.write(bytes);
  try {
    server.receive(5s, "Step");
  } catch (const ProtocolError& error) {
    return error.what();
  }
  return "(no error)";
}

// ---- the v1.0 session, with a scripted client (fake LIGGGHTS side) on a thread ----

Snapshot big_snapshot(std::uint64_t step) {
  Snapshot snapshot;
  snapshot.step = step;
  snapshot.time = 1e-3;
  snapshot.dimension = 2;
  const std::size_t particles = 150000;  // about 6 MB: several payload buffer growths
  for (std::size_t i = 0; i < particles; ++i) {
    snapshot.ids.push_back(i + 1);
    snapshot.positions.push_back(0.001 * static_cast<double>(i));
    snapshot.positions.push_back(-0.5);
    snapshot.velocities.push_back(0.0);
    snapshot.velocities.push_back(-1.0 / static_cast<double>(i + 1));
    snapshot.density.push_back(1000.0 + 1e-6 * static_cast<double>(i));
    snapshot.pressure.push_back(static_cast<double>(i % 97));
  }
  return snapshot;
}

std::uint64_t scripted_client(std::uint16_t port) {
  Channel channel = Channel::connect("127.0.0.1", port, 5s);
  channel.send(Hello{"0.1.0", "fake-client", 2, kNoCapabilities});
  const Welcome welcome = channel.expect<Welcome>(5s);
  if (welcome.run_name != "loopback") throw std::runtime_error("wrong run name");
  const protocol::Setup setup = channel.expect<protocol::Setup>(5s);
  const Mesh mesh = channel.expect<Mesh>(5s);
  const Particles particles = channel.expect<Particles>(5s);
  channel.send(Ready{particles.positions.size() / setup.dimension, "fake", 0.1, 0.2});
  Forces initial;
  initial.forces.assign(mesh.dynamic_vertex_count * mesh.dimension, 0.25);
  channel.send(initial);
  std::uint64_t steps = 0;
  while (true) {
    Message message = channel.receive_message(5s);
    if (auto* step = std::get_if<Step>(&message)) {
      Forces forces;
      forces.step = step->step;
      forces.forces = step->positions;  // echo, so the server can check what arrived
      forces.diagnostics.particle_count = particles.positions.size() / 2;
      channel.send(forces);
      ++steps;
    } else if (auto* request = std::get_if<SnapshotRequest>(&message)) {
      channel.send(big_snapshot(request->step));
    } else if (std::holds_alternative<Shutdown>(message)) {
      channel.send(Goodbye{steps, 1.5});
      return steps;
    } else {
      throw std::runtime_error("unexpected " + name(type_of(message)));
    }
  }
}

TEST(ProtocolChannel, WholeSessionOverLoopback) {
  Listener listener("127.0.0.1", 0);
  ASSERT_GT(listener.port(), 0);
  auto client = std::async(std::launch::async, scripted_client, listener.port());

  Channel server = listener.accept(5s);
  EXPECT_TRUE(contains(server.peer_description(), "127.0.0.1:"));
  const Hello hello = server.expect<Hello>(5s);
  EXPECT_EQ(hello.mpi_ranks, 2u);
  const VersionCheck version =
      check_peer_version(Role::Server, server.peer_major(), server.peer_minor());
  ASSERT_TRUE(version.compatible);
  server.send(Welcome{version.agreed_minor, kNoCapabilities, "0.1.0", "loopback"});
  server.send(protocol::Setup{2, 1e-5, 100, {{"h", "0.001"}}, "a.in1", "dimension 2", "a.in2", ""});
  server.send(Mesh{2, 2, 1, 1e-3, {0, 0, 1, 0, 2, 0}, {0, 0, 0, 0, 0, 0}, {0, 1, 1, 2}});
  server.send(Particles{2, 1, 1e-4, 1000, {0.5, 0.5, 0.6, 0.5}, {0, 0, 0, 0}});
  EXPECT_EQ(server.expect<Ready>(5s).particle_count, 2u);
  const Forces initial = server.expect<Forces>(5s);
  EXPECT_EQ(initial.step, 0u);
  EXPECT_EQ(initial.forces, (std::vector<double>(4, 0.25)));

  for (std::uint64_t step = 1; step <= 3; ++step) {
    const std::vector<double> positions{1.0 * step, -2.0, 3.0, 0.5 / step};
    server.send(Step{step, 1e-5 * step, 1e-5, positions, {0, 0, 0, 0}});
    const Forces forces = server.expect<Forces>(5s);
    EXPECT_EQ(forces.step, step);
    EXPECT_EQ(forces.forces, positions);
    EXPECT_EQ(forces.diagnostics.particle_count, 2u);
    if (step == 2) {
      server.send(SnapshotRequest{step});
      const auto start = Clock::now();
      const Snapshot snapshot = server.expect<Snapshot>(10s);
      std::printf("Snapshot of %zu particles over loopback in %.3f s\n", snapshot.ids.size(),
                  seconds_since(start));
      EXPECT_EQ(snapshot, big_snapshot(step));
    }
  }
  server.send(Shutdown{"end time reached"});
  const Goodbye goodbye = server.expect<Goodbye>(5s);
  EXPECT_EQ(goodbye.steps_done, 3u);
  server.close();
  EXPECT_EQ(client.get(), 3u);
}

TEST(ProtocolChannel, ReceiveHandsOverTheRawFrame) {
  Listener listener("127.0.0.1", 0);
  auto client = std::async(std::launch::async, [port = listener.port()] {
    Channel channel = Channel::connect("127.0.0.1", port, 5s);
    channel.send(Message{Shutdown{"first"}});
    channel.send(Shutdown{"second"});
    channel.expect<Goodbye>(5s);
  });
  Channel server = listener.accept(5s);
  const Frame first = server.receive(5s);
  EXPECT_EQ(first.header.type, MessageType::Shutdown);
  EXPECT_EQ(decode_as<Shutdown>(first.payload).reason, "first");
  const Frame second = server.receive(5s);
  EXPECT_EQ(decode_as<Shutdown>(second.payload).reason, "second");
  EXPECT_EQ(decode_as<Shutdown>(first.payload).reason, "first");  // not overwritten
  server.send(Goodbye{});
  server.close();
  client.get();
}

TEST(ProtocolChannel, ConnectRetriesUntilTheServerListens) {
  const std::uint16_t port = free_port();
  const auto start = Clock::now();
  auto client = std::async(std::launch::async, [port] {
    Channel channel = Channel::connect("127.0.0.1", port, 10s);
    channel.send(Shutdown{"hello, late server"});
    channel.expect<Goodbye>(5s);
  });
  std::this_thread::sleep_for(300ms);
  Listener listener("127.0.0.1", port);
  Channel server = listener.accept(10s);
  EXPECT_EQ(server.expect<Shutdown>(5s).reason, "hello, late server");
  server.send(Goodbye{});
  server.close();
  client.get();
  const double waited = seconds_since(start);
  EXPECT_GE(waited, 0.3);
  EXPECT_LT(waited, 2.0);  // back-off pauses are 50, 100, 200, 400 ms at this point
}

TEST(ProtocolChannel, ConnectGivesUpNamingHostAndPort) {
  const std::uint16_t port = free_port();
  const auto start = Clock::now();
  const std::string text =
      error_of<fsi::Error>([&] { Channel::connect("127.0.0.1", port, 400ms); });
  EXPECT_TRUE(contains(
      text, "cannot connect to fsi-server at 127.0.0.1:" + std::to_string(port) + " within 0.4 s"))
      << text;
  EXPECT_TRUE(contains(text, "Connection refused")) << text;
  EXPECT_TRUE(contains(text, "firewall")) << text;
  const double waited = seconds_since(start);
  EXPECT_GE(waited, 0.39);
  EXPECT_LT(waited, 1.5);
}

TEST(ProtocolChannel, PeerClosingEndsTheWaitAtOnce) {
  Listener listener("127.0.0.1", 0);
  auto client = std::async(std::launch::async, [port = listener.port()] {
    Channel channel = Channel::connect("127.0.0.1", port, 5s);
    std::this_thread::sleep_for(100ms);
    channel.close();
    EXPECT_FALSE(channel.is_open());
  });
  Channel server = listener.accept(5s);
  const auto start = Clock::now();
  const std::string text = error_of([&] { server.receive(30s, "Forces"); });
  EXPECT_TRUE(contains(text, "connection closed by peer 127.0.0.1:")) << text;
  EXPECT_TRUE(contains(text, "while waiting for Forces")) << text;
  EXPECT_LT(seconds_since(start), 1.0);
  server.close();
  client.get();
}

TEST(ProtocolChannel, HalfAFrameThenSilenceTimesOut) {
  Listener listener("127.0.0.1", 0, quick_close());
  const auto frame = encode_frame(MessageType::Forces, std::vector<std::byte>(100));
  const std::vector<std::pair<std::size_t, std::string>> cuts{
      {10, "received 10 of the 20 header bytes"},
      {30, "received 10 of the 100 payload bytes of a Forces frame"}};
  for (const auto& [cut, progress] : cuts) {
    RawPeer peer(listener.port());
    Channel server = listener.accept(5s);
    peer.write(std::span(frame).first(cut));
    const auto start = Clock::now();
    const std::string text = error_of([&] { server.receive(500ms, "Forces"); });
    EXPECT_TRUE(contains(text, "timed out after 0.5 s while waiting for Forces")) << text;
    EXPECT_TRUE(contains(text, progress)) << text;
    const double waited = seconds_since(start);
    EXPECT_GE(waited, 0.49);
    EXPECT_LT(waited, 1.0);
    // The rest of the frame may still come, so nothing after it can be trusted.
    peer.write(std::span(frame).subspan(cut));
    const std::string after_fault = error_of([&] { server.receive(500ms, "Forces"); });
    EXPECT_TRUE(contains(after_fault, "unusable after an earlier fault")) << after_fault;
  }
}

TEST(ProtocolChannel, TimeoutBeforeAFrameKeepsTheChannelUsable) {
  Listener listener("127.0.0.1", 0, quick_close());
  RawPeer peer(listener.port());
  Channel server = listener.accept(5s);
  const auto start = Clock::now();
  EXPECT_THROW(server.receive(200ms, "Forces"), ProtocolError);
  EXPECT_GE(seconds_since(start), 0.19);
  peer.write(encode_frame(MessageType::Goodbye, encode(Goodbye{5, 1.0})));
  EXPECT_EQ(server.expect<Goodbye>(5s).steps_done, 5u);
}

TEST(ProtocolChannel, FaultyFramesFromThePeerAreNamed) {
  const ChannelOptions options = quick_close();
  auto damaged = encode_frame(MessageType::Step, encode(Step{1, 0, 1, {1}, {1}}));
  damaged.back() ^= std::byte{0x40};
  std::string text = fault_from_raw_peer(damaged, options);
  EXPECT_TRUE(contains(text, "CRC-32C mismatch in Step frame: computed 0x")) << text;
  EXPECT_TRUE(contains(text, "from 127.0.0.1:")) << text;

  const std::string http = "GET / HTTP/1.1\r\nHost: x\r\n\r\n";
  text = fault_from_raw_peer(std::as_bytes(std::span(http)), options);
  EXPECT_TRUE(contains(text, "bad frame magic")) << text;

  ChannelOptions small = options;
  small.max_payload = 16;
  text = fault_from_raw_peer(encode_frame(MessageType::Step, std::vector<std::byte>(17)), small);
  EXPECT_TRUE(contains(text, "announces a payload of 17 bytes, more than the 16")) << text;

  text = fault_from_raw_peer(encode_frame(MessageType::Step, {}, 2, 0), options);
  EXPECT_TRUE(contains(text, "Step frame of protocol 2.0, but this side speaks " +
                                 version_text(kMajorVersion, kMinorVersion)))
      << text;

  auto unknown = encode_frame(MessageType::Step, {});
  unknown[8] = std::byte{0x7E};
  text = fault_from_raw_peer(unknown, options);
  EXPECT_TRUE(contains(text, "unknown type 0x007e")) << text;

  auto flagged = encode_frame(MessageType::Step, {});
  flagged[10] = std::byte{0x01};
  text = fault_from_raw_peer(flagged, options);
  EXPECT_TRUE(contains(text, "flags 0x0001")) << text;
}

TEST(ProtocolChannel, MalformedMessageIsNamedButTheStreamStaysInStep) {
  Listener listener("127.0.0.1", 0, quick_close());
  RawPeer peer(listener.port());
  Channel server = listener.accept(5s);
  auto payload = encode(Step{1, 0, 1, {1}, {1}});
  payload.pop_back();
  peer.write(encode_frame(MessageType::Step, payload));
  peer.write(encode_frame(MessageType::Goodbye, encode(Goodbye{})));
  const std::string text = error_of([&] { server.receive_message(5s); });
  EXPECT_TRUE(contains(text, "malformed Step message: field 'velocities'")) << text;
  EXPECT_NO_THROW(server.expect<Goodbye>(5s));
}

// ---- large messages: sent from the caller's arrays, read straight into the receiver's ----

// Doubles whose bits all matter: signs, subnormals, a NaN with a payload.
std::vector<double> awkward_doubles(std::size_t count, std::uint64_t seed) {
  std::vector<double> values(count);
  std::uint64_t bits = seed;
  for (auto& value : values) {
    bits = bits * 6364136223846793005u + 1442695040888963407u;
    std::memcpy(&value, &bits, sizeof value);
  }
  return values;
}

bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

// Writes a frame from a thread (a large one fills the socket buffers until the channel reads).
std::future<void> write_later(RawPeer& peer, std::vector<std::byte> bytes) {
  return std::async(std::launch::async,
                    [&peer, bytes = std::move(bytes)] { peer.write(std::span(bytes)); });
}

TEST(ProtocolChannel, LargeMessagesArriveBitExactInTheReusedStorage) {
  Listener listener("127.0.0.1", 0);
  Forces first;
  first.step = 1;
  first.forces = awkward_doubles(1'000'000, 1);
  Forces second = first;
  second.step = 2;
  second.forces = awkward_doubles(1'000'000, 2);
  auto client = std::async(std::launch::async, [&, port = listener.port()] {
    Channel channel = Channel::connect("127.0.0.1", port, 5s);
    channel.send(first);
    channel.send(second);
    channel.send(Goodbye{2, 0.5});
  });
  Channel server = listener.accept(5s);
  Forces received;
  received.forces.reserve(1'200'000);  // a fresh vector would get exactly what arrives
  server.expect_into(received, 10s);
  EXPECT_EQ(received.step, 1u);
  EXPECT_EQ(received.forces.capacity(), 1'200'000u);
  EXPECT_TRUE(same_bits(received.forces, first.forces));
  const double* storage = received.forces.data();
  server.expect_into(received, 10s);
  EXPECT_EQ(received.step, 2u);
  EXPECT_TRUE(same_bits(received.forces, second.forces));
  EXPECT_EQ(received.forces.data(), storage);  // read in place: no allocation, no copy
  EXPECT_EQ(received.forces.capacity(), 1'200'000u);
  EXPECT_EQ(server.expect<Goodbye>(5s).steps_done, 2u);
  server.close();
  client.get();
}

TEST(ProtocolChannel, DamagedLargeFrameIsACrcMismatchEvenIfItsContentIsAlsoWrong) {
  Listener listener("127.0.0.1", 0, quick_close());
  Step step{3, 0.5, 1e-3, awkward_doubles(300'000, 3), awkward_doubles(300'000, 4)};
  auto frame = encode_frame(MessageType::Step, encode(step));
  frame[frame.size() / 2] ^= std::byte{0x01};
  Step wrong = step;  // velocities no longer match the positions
  wrong.velocities.pop_back();
  auto wrong_frame = encode_frame(MessageType::Step, encode(wrong));
  wrong_frame[wrong_frame.size() / 3] ^= std::byte{0x10};
  for (auto* bytes : {&frame, &wrong_frame}) {
    RawPeer peer(listener.port());
    Channel server = listener.accept(5s);
    auto writer = write_later(peer, *bytes);
    Step received;
    const std::string text = error_of([&] { server.expect_into(received, 10s); });
    EXPECT_TRUE(contains(text, "CRC-32C mismatch in Step frame")) << text;
    writer.get();
    EXPECT_THROW(server.expect<Step>(1s), ProtocolError);  // the stream is not trusted any more
  }
}

TEST(ProtocolChannel, MalformedLargeMessageIsReadToItsEndSoTheStreamStaysInStep) {
  Listener listener("127.0.0.1", 0, quick_close());
  RawPeer peer(listener.port());
  Channel server = listener.accept(5s);
  Step step{3, 0.5, 1e-3, awkward_doubles(300'000, 5), awkward_doubles(299'999, 6)};
  auto frames = encode_frame(MessageType::Step, encode(step));
  auto overlong = encode(Forces{4, awkward_doubles(200'000, 7), {}});
  overlong.resize(overlong.size() + 100000);  // more than the channel stages at once
  const auto overlong_frame = encode_frame(MessageType::Forces, overlong);
  const auto goodbye = encode_frame(MessageType::Goodbye, encode(Goodbye{9, 1.0}));
  frames.insert(frames.end(), overlong_frame.begin(), overlong_frame.end());
  frames.insert(frames.end(), goodbye.begin(), goodbye.end());
  auto writer = write_later(peer, frames);
  Step received_step;
  const std::string step_text = error_of([&] { server.expect_into(received_step, 10s); });
  EXPECT_TRUE(contains(step_text, "malformed Step message: field 'velocities' has 299999 values"))
      << step_text;
  Forces received_forces;
  const std::string forces_text = error_of([&] { server.expect_into(received_forces, 10s); });
  EXPECT_TRUE(contains(forces_text, "100000 bytes follow the last field")) << forces_text;
  EXPECT_EQ(server.expect<Goodbye>(5s).steps_done, 9u);
  writer.get();
}

TEST(ProtocolChannel, PeerClosingInsideALargeArrayNamesTheBytesReceived) {
  Listener listener("127.0.0.1", 0, quick_close());
  const auto frame =
      encode_frame(MessageType::Forces, encode(Forces{1, awkward_doubles(500'000, 8), {}}));
  Channel server = [&] {
    auto peer = std::make_unique<RawPeer>(listener.port());
    Channel accepted = listener.accept(5s);
    auto writer = std::async(std::launch::async, [&] {
      peer->write(std::span(frame).first(kHeaderSize + 1'000'000));
      peer.reset();  // closes the connection
    });
    Forces received;
    const std::string text = error_of([&] { accepted.expect_into(received, 10s); });
    EXPECT_TRUE(contains(text, "connection closed by peer")) << text;
    EXPECT_TRUE(contains(text, "received 1000000 of the " +
                                   std::to_string(frame.size() - kHeaderSize) +
                                   " payload bytes of a Forces frame"))
        << text;
    writer.get();
    return accepted;
  }();
}

TEST(ProtocolChannel, ErrorFromPeerIsReportedByExpect) {
  Listener listener("127.0.0.1", 0);
  auto client = std::async(std::launch::async, [port = listener.port()] {
    Channel channel = Channel::connect("127.0.0.1", port, 5s);
    channel.send(ErrorMessage{ErrorCode::SetupFailed, "tank.in1:7: unknown command 'fixx'"});
  });
  Channel server = listener.accept(5s);
  try {
    server.expect<Ready>(5s);
    FAIL() << "an Error message passed as Ready";
  } catch (const PeerReportedError& error) {
    EXPECT_EQ(error.code(), ErrorCode::SetupFailed);
    EXPECT_EQ(error.peer_text(), "tank.in1:7: unknown command 'fixx'");
    EXPECT_TRUE(contains(error.what(), "peer reported: tank.in1:7: unknown command 'fixx'"));
    EXPECT_TRUE(contains(error.what(), "while waiting for Ready"));
  }
  server.close();
  client.get();
}

TEST(ProtocolChannel, UnexpectedMessageNamesBothTypes) {
  Listener listener("127.0.0.1", 0);
  auto client = std::async(std::launch::async, [port = listener.port()] {
    Channel channel = Channel::connect("127.0.0.1", port, 5s);
    channel.send(Goodbye{});
  });
  Channel server = listener.accept(5s);
  const std::string text = error_of([&] { server.expect<Forces>(5s); });
  EXPECT_TRUE(contains(text, "expected a Forces message but received Goodbye")) << text;
  server.close();
  client.get();
}

TEST(ProtocolChannel, VersionMismatchIsReportedOnBothSides) {
  Listener listener("127.0.0.1", 0);
  auto client = std::async(std::launch::async, [port = listener.port()]() -> std::string {
    ChannelOptions future;
    future.major = 2;
    future.minor = 4;
    Channel channel = Channel::connect("127.0.0.1", port, 5s, future);
    channel.send(Hello{"9.9", "future-host", 1, 0});
    channel.send(SnapshotRequest{1});  // a v2 frame the server must refuse
    try {
      channel.expect<Welcome>(5s);
    } catch (const PeerReportedError& error) {
      return error.what();
    }
    return "(welcomed)";
  });
  Channel server = listener.accept(5s);
  const Hello hello = server.expect<Hello>(5s);  // frozen layout: readable across majors
  EXPECT_EQ(hello.software_version, "9.9");
  EXPECT_EQ(server.peer_major(), 2);
  EXPECT_EQ(server.peer_minor(), 4);
  const VersionCheck version =
      check_peer_version(Role::Server, server.peer_major(), server.peer_minor());
  ASSERT_FALSE(version.compatible);
  server.send(ErrorMessage{ErrorCode::VersionMismatch, version.message});
  const std::string text = error_of([&] { server.receive(5s, "nothing more"); });
  EXPECT_TRUE(contains(text, "protocol 2.4")) << text;
  server.close();
  const std::string at_client = client.get();
  EXPECT_TRUE(contains(at_client, "fsi-client speaks protocol 2.4, this fsi-server speaks " +
                                      version_text(kMajorVersion, kMinorVersion)))
      << at_client;
  EXPECT_TRUE(contains(at_client, "[VersionMismatch]")) << at_client;
}

TEST(ProtocolChannel, LastErrorSurvivesACloseWithUnreadData) {
  Listener listener("127.0.0.1", 0);
  auto client = std::async(std::launch::async, [port = listener.port()] {
    Channel channel = Channel::connect("127.0.0.1", port, 5s);
    std::this_thread::sleep_for(200ms);  // the server's Step is now unread in our socket
    channel.send(ErrorMessage{ErrorCode::LiggghtsError, "lost atoms"});
  });
  Channel server = listener.accept(5s);
  server.send(Step{1, 1, 1, std::vector<double>(100000, 1.0), std::vector<double>(100000, 1.0)});
  try {
    server.expect<Forces>(5s);
    FAIL();
  } catch (const PeerReportedError& error) {
    EXPECT_EQ(error.peer_text(), "lost atoms");
  }
  server.close();
  client.get();
}

TEST(ProtocolChannel, SendTimesOutWhenThePeerDoesNotRead) {
  ChannelOptions options = quick_close();
  options.send_timeout = 200ms;
  Listener listener("127.0.0.1", 0, options);
  RawPeer peer(listener.port());
  Channel server = listener.accept(5s);
  const std::vector<std::byte> payload(64u << 20);
  const auto start = Clock::now();
  const std::string text = error_of([&] { server.send(MessageType::Snapshot, payload); });
  EXPECT_TRUE(contains(text, "timed out after 0.2 s sending a Snapshot frame")) << text;
  EXPECT_LT(seconds_since(start), 1.5);
  const std::string after_timeout = error_of([&] { server.send(Shutdown{}); });
  EXPECT_TRUE(contains(after_timeout, "earlier send timed out")) << after_timeout;
}

TEST(ProtocolChannel, SendingToAClosedPeerFails) {
  Listener listener("127.0.0.1", 0, quick_close());
  auto peer = std::make_unique<RawPeer>(listener.port());
  Channel server = listener.accept(5s);
  peer.reset();
  std::string text;
  for (int attempt = 0; attempt < 100 && text.empty(); ++attempt) {
    try {
      server.send(Shutdown{"anyone there?"});
      std::this_thread::sleep_for(10ms);
    } catch (const ProtocolError& error) {
      text = error.what();
    }
  }
  EXPECT_TRUE(contains(text, "connection closed by peer 127.0.0.1:")) << text;
  EXPECT_TRUE(contains(text, "while sending Shutdown")) << text;
}

TEST(ProtocolListener, BusyPortIsAClearError) {
  Listener first("127.0.0.1", 0);
  try {
    Listener second("127.0.0.1", first.port());
    FAIL() << "two listeners on one port";  // SO_REUSEADDR does not allow that on Linux
  } catch (const fsi::Error& error) {
    const std::string text = error.what();
    EXPECT_TRUE(contains(text, "cannot listen on 127.0.0.1:" + std::to_string(first.port())))
        << text;
    EXPECT_TRUE(contains(text, "choose another port")) << text;
  }
}

TEST(ProtocolListener, AddressMustBeNumeric) {
  const std::string text = error_of<fsi::Error>([&] { Listener listener("localhost-ish", 0); });
  EXPECT_TRUE(contains(text, "'localhost-ish' is not a numeric IP address"));
}

TEST(ProtocolListener, AcceptTimesOut) {
  Listener listener("127.0.0.1", 0);
  const auto start = Clock::now();
  const std::string text = error_of([&] { listener.accept(200ms); });
  EXPECT_TRUE(contains(text, "no fsi-client connected within 0.2 s")) << text;
  EXPECT_GE(seconds_since(start), 0.19);
  EXPECT_LT(seconds_since(start), 1.0);
}

}  // namespace
}  // namespace fsi::protocol

namespace fsi::protocol {
namespace {

// The peer computes for 1.2 s between two messages; the receiver allows 0.4 s of silence.
std::string wait_through_a_long_computation(bool with_heartbeats, std::uint64_t* heartbeats) {
  Listener listener("127.0.0.1", 0, quick_close());
  auto busy_peer = std::async(std::launch::async, [&, port = listener.port()] {
    Channel channel = Channel::connect("127.0.0.1", port, 5s, quick_close());
    HeartbeatSender heartbeat(channel, with_heartbeats, 100ms);
    channel.send(Goodbye{1, 0.0});
    {
      auto busy = heartbeat.busy();
      std::this_thread::sleep_for(1200ms);
    }
    try {
      channel.send(Goodbye{2, 0.0});
    } catch (const ProtocolError&) {
      // The receiver gave up already.
    }
    return heartbeat.sent();
  });
  Channel receiver = listener.accept(5s);
  std::string outcome;
  try {
    receiver.expect<Goodbye>(400ms);
    outcome = "steps " + std::to_string(receiver.expect<Goodbye>(400ms).steps_done);
  } catch (const ProtocolError& error) {
    outcome = error.what();
  }
  *heartbeats = receiver.heartbeats_received();
  receiver.close();
  const std::uint64_t sent = busy_peer.get();
  EXPECT_GE(sent, *heartbeats);
  return outcome;
}

TEST(ProtocolHeartbeat, TimeoutMeasuresSilenceNotComputeTime) {
  std::uint64_t heartbeats = 0;
  EXPECT_EQ(wait_through_a_long_computation(true, &heartbeats), "steps 2");
  // About 12 heartbeats in 1.2 s at 100 ms; a loaded machine may delay some.
  EXPECT_GE(heartbeats, 5u);
}

TEST(ProtocolHeartbeat, WithoutHeartbeatsTheSameComputationTimesOut) {
  std::uint64_t heartbeats = 0;
  const std::string outcome = wait_through_a_long_computation(false, &heartbeats);
  EXPECT_TRUE(contains(outcome, "timed out after 0.4 s while waiting for Goodbye")) << outcome;
  // The message tells a silent peer from one whose heartbeats stopped.
  EXPECT_TRUE(contains(outcome, "; no heartbeat arrived in this wait of 0.4")) << outcome;
  EXPECT_EQ(heartbeats, 0u);
}

TEST(ProtocolHeartbeat, ATimeoutSaysWhenTheHeartbeatsStopped) {
  // The peer computes with heartbeats for 0.6 s, then falls silent without answering.
  Listener listener("127.0.0.1", 0, quick_close());
  auto peer = std::async(std::launch::async, [&, port = listener.port()] {
    Channel channel = Channel::connect("127.0.0.1", port, 5s, quick_close());
    HeartbeatSender heartbeat(channel, true, 100ms);
    {
      auto busy = heartbeat.busy();
      std::this_thread::sleep_for(600ms);
    }
    std::this_thread::sleep_for(1000ms);
  });
  Channel receiver = listener.accept(5s);
  std::string outcome;
  try {
    receiver.expect<Goodbye>(400ms);
  } catch (const ProtocolError& error) {
    outcome = error.what();
  }
  receiver.close();
  peer.get();
  EXPECT_TRUE(contains(outcome, "timed out after 0.4 s while waiting for Goodbye")) << outcome;
  EXPECT_TRUE(contains(outcome, "heartbeat(s) arrived in this wait of")) << outcome;
  EXPECT_TRUE(contains(outcome, " before the timeout")) << outcome;
}

TEST(ProtocolHeartbeat, NothingIsSentOutsideBusyScopesAndStopIsFinal) {
  Listener listener("127.0.0.1", 0, quick_close());
  auto peer = std::async(std::launch::async, [port = listener.port()] {
    Channel channel = Channel::connect("127.0.0.1", port, 5s, quick_close());
    HeartbeatSender heartbeat(channel, true, 50ms);
    std::this_thread::sleep_for(300ms);  // idle: no heartbeats
    const std::uint64_t idle = heartbeat.sent();
    heartbeat.stop();
    heartbeat.stop();
    {
      auto busy = heartbeat.busy();  // after stop(): does nothing
      std::this_thread::sleep_for(200ms);
    }
    channel.send(Goodbye{heartbeat.sent() + 100 * idle, 0.0});
  });
  Channel receiver = listener.accept(5s);
  EXPECT_EQ(receiver.expect<Goodbye>(5s).steps_done, 0u);
  EXPECT_EQ(receiver.heartbeats_received(), 0u);
  receiver.close();
  peer.get();
}

TEST(ProtocolHeartbeat, HeartbeatWithAPayloadIsMalformed) {
  const std::string text = fault_from_raw_peer(
      encode_frame(MessageType::Heartbeat, std::vector<std::byte>(3)), quick_close());
  EXPECT_TRUE(contains(text, "malformed Heartbeat message: 3 payload bytes")) << text;
}

}  // namespace
}  // namespace fsi::protocol
