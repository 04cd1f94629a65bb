// Throughput and latency of fsi::protocol on loopback, each against a baseline measured in the
// same run. Not a pass/fail test.
//
//  throughput: a Forces message with N doubles (CRC-32C, gathered send from the message's own
//              array; receive into a reused Forces while checking the CRC) against raw POSIX
//              sockets moving the same bytes with no framing, measured in turn within each
//              repetition. Also printed: raw sockets plus the two CRC passes the frame format
//              asks for (its floor), and the protocol decoding into a new Forces each time.
//  latency:    one coupled-step exchange with V dynamic 2D vertices: Step (r, v) out, Forces (f)
//              back, the peer answering at once, so the round trip excludes compute; against the
//              same byte counts over raw sockets.
//
//   build/bin/bench_protocol_transport [--doubles 4000000] [--vertices 1000] [--round-trips 3000]
#include <arpa/inet.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <span>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "fsi/protocol/channel.hpp"
#include "fsi/protocol/frame.hpp"

namespace {

namespace protocol = fsi::protocol;
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

double median(std::vector<double> values) {
  std::nth_element(values.begin(), values.begin() + values.size() / 2, values.end());
  return values[values.size() / 2];
}

// ---- raw sockets: the baseline ----

void check(bool ok, const char* what) {
  if (!ok) throw std::runtime_error(std::string(what) + ": " + std::strerror(errno));
}

int raw_listen(std::uint16_t& port) {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  check(fd >= 0, "socket");
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  check(::bind(fd, reinterpret_cast<sockaddr*>(&address), sizeof address) == 0, "bind");
  check(::listen(fd, 1) == 0, "listen");
  socklen_t length = sizeof address;
  check(::getsockname(fd, reinterpret_cast<sockaddr*>(&address), &length) == 0, "getsockname");
  port = ntohs(address.sin_port);
  return fd;
}

void no_delay(int fd) {
  const int one = 1;
  ::setsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &one, sizeof one);
}

int raw_connect(std::uint16_t port) {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  check(fd >= 0, "socket");
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  address.sin_port = htons(port);
  check(::connect(fd, reinterpret_cast<sockaddr*>(&address), sizeof address) == 0, "connect");
  no_delay(fd);
  return fd;
}

void write_all(int fd, const void* data, std::size_t size) {
  const char* p = static_cast<const char*>(data);
  while (size > 0) {
    const ssize_t n = ::write(fd, p, size);
    check(n > 0, "write");
    p += n;
    size -= static_cast<std::size_t>(n);
  }
}

void read_all(int fd, void* data, std::size_t size) {
  char* p = static_cast<char*>(data);
  while (size > 0) {
    const ssize_t n = ::read(fd, p, size);
    check(n > 0, "read");
    p += n;
    size -= static_cast<std::size_t>(n);
  }
}

struct RawPair {
  int client = -1;
  int server = -1;
  RawPair() {
    std::uint16_t port = 0;
    const int listener = raw_listen(port);
    std::thread accept([&] {
      server = ::accept(listener, nullptr, nullptr);
      no_delay(server);
    });
    client = raw_connect(port);
    accept.join();
    ::close(listener);
  }
  ~RawPair() {
    ::close(client);
    ::close(server);
  }
};

// ---- fsi::protocol channels ----

struct ChannelPair {
  protocol::Channel client;
  protocol::Channel server;
};

ChannelPair channel_pair() {
  protocol::Listener listener("127.0.0.1", 0);
  std::optional<protocol::Channel> accepted;
  std::thread accept([&] { accepted.emplace(listener.accept(std::chrono::seconds(10))); });
  protocol::Channel client =
      protocol::Channel::connect("127.0.0.1", listener.port(), std::chrono::seconds(10));
  accept.join();
  return ChannelPair{std::move(client), std::move(*accepted)};
}

std::vector<double> values(std::size_t count, double seed) {
  std::vector<double> v(count);
  for (std::size_t i = 0; i < count; ++i)
    v[i] = seed + 1e-3 * static_cast<double>(i);
  return v;
}

void throughput(std::size_t doubles, int repeats) {
  protocol::Forces message;
  message.step = 1;
  message.forces = values(doubles, 0.5);
  const std::size_t bytes = doubles * sizeof(double);

  // The receiver decodes into one Forces reused for every message (Channel::expect_into), as the
  // raw baseline reads into one buffer; the two are measured in turn within every repetition, so
  // that the load of a shared machine, which drifts over seconds, weighs on both alike. "fresh"
  // decodes into a new Forces each time (expect<>), which adds allocating and first touching 8
  // bytes per double; it runs in a loop of its own afterwards, so that its allocations do not
  // disturb the other two.
  std::vector<double> framed, fresh, raw;
  ChannelPair channels = channel_pair();
  RawPair sockets;
  protocol::Forces received;
  std::vector<double> buffer(doubles);
  // "raw + CRC": the raw sockets plus the two passes the frame format asks for (the sender's CRC
  // before the first byte, as it is in the header; the receiver's over each 256 KiB piece), the
  // floor for any implementation of the format.
  std::vector<double> raw_with_crc;
  const auto payload = std::as_bytes(std::span(message.forces));
  volatile std::uint32_t crc_sink = 0;
  for (int r = 0; r < repeats + 1; ++r) {
    auto start = Clock::now();
    std::thread sender([&] { channels.client.send(message); });
    channels.server.expect_into(received, std::chrono::seconds(60));
    sender.join();
    if (r > 0) framed.push_back(seconds_since(start));
    if (received.forces.size() != doubles) throw std::runtime_error("short Forces message");

    start = Clock::now();
    sender = std::thread([&] { write_all(sockets.client, message.forces.data(), bytes); });
    read_all(sockets.server, buffer.data(), bytes);
    sender.join();
    if (r > 0) raw.push_back(seconds_since(start));

    start = Clock::now();
    sender = std::thread([&] {
      crc_sink = protocol::crc32c(payload);
      write_all(sockets.client, message.forces.data(), bytes);
    });
    auto* into = reinterpret_cast<std::byte*>(buffer.data());
    std::uint32_t crc = 0;
    for (std::size_t done = 0; done < bytes;) {
      const std::size_t piece = std::min<std::size_t>(bytes - done, std::size_t{256} << 10);
      read_all(sockets.server, into + done, piece);
      crc = protocol::crc32c(std::span<const std::byte>(into + done, piece), crc);
      done += piece;
    }
    sender.join();
    if (crc != crc_sink) throw std::runtime_error("raw + CRC: the CRCs differ");
    if (r > 0) raw_with_crc.push_back(seconds_since(start));
  }
  for (int r = 0; r < repeats + 1; ++r) {
    const auto start = Clock::now();
    std::thread sender([&] { channels.client.send(message); });
    const auto new_message = channels.server.expect<protocol::Forces>(std::chrono::seconds(60));
    sender.join();
    if (r > 0) fresh.push_back(seconds_since(start));
    if (new_message.forces.size() != doubles) throw std::runtime_error("short Forces message");
  }
  if (received.forces != message.forces) throw std::runtime_error("Forces changed on the way");
  const double framed_rate = static_cast<double>(doubles) / median(framed);
  const double fresh_rate = static_cast<double>(doubles) / median(fresh);
  const double raw_rate = static_cast<double>(doubles) / median(raw);
  const double raw_with_crc_rate = static_cast<double>(doubles) / median(raw_with_crc);
  std::printf("throughput, %zu doubles (%.1f MB) per message, median of %d (interleaved):\n",
              doubles, static_cast<double>(bytes) / 1e6, repeats);
  std::printf(
      "  fsi::protocol Forces (CRC+gathered send, receive+CRC into a reused Forces): "
      "%.3g doubles/s\n",
      framed_rate);
  std::printf(
      "  fsi::protocol Forces, decoded into a new Forces each time:                  "
      "%.3g doubles/s\n",
      fresh_rate);
  std::printf(
      "  raw socket, same bytes, no framing:                                         "
      "%.3g doubles/s\n",
      raw_rate);
  std::printf(
      "  raw socket + the format's two CRC passes (sender before writing, receiver per piece): "
      "%.3g doubles/s (ratio to raw %.3f)\n",
      raw_with_crc_rate, raw_with_crc_rate / raw_rate);
  std::vector<double> paired;  // raw time / protocol time within one repetition
  for (std::size_t i = 0; i < framed.size(); ++i)
    paired.push_back(raw[i] / framed[i]);
  std::printf("  ratio protocol/raw: %.3f (new Forces each time: %.3f)\n", framed_rate / raw_rate,
              fresh_rate / raw_rate);
  std::printf("  median of the %d per-repetition ratios: %.3f\n\n", repeats, median(paired));
}

void latency(std::size_t vertices, int round_trips) {
  protocol::Step step;
  step.step = 1;
  step.time = 2.5e-6;
  step.time_step = 2.5e-6;
  step.positions = values(2 * vertices, 0.1);
  step.velocities = values(2 * vertices, 0.2);
  protocol::Forces forces;
  forces.step = 1;
  forces.forces = values(2 * vertices, 0.3);

  std::vector<double> framed, raw;
  {
    ChannelPair pair = channel_pair();
    std::thread peer([&] {  // the client side: answer every Step at once
      for (int r = 0; r < round_trips + 100; ++r) {
        const auto received = pair.client.expect<protocol::Step>(std::chrono::seconds(60));
        forces.step = received.step;
        pair.client.send(forces);
      }
    });
    for (int r = 0; r < round_trips + 100; ++r) {
      step.step = static_cast<std::uint64_t>(r + 1);
      const auto start = Clock::now();
      pair.server.send(step);
      const auto reply = pair.server.expect<protocol::Forces>(std::chrono::seconds(60));
      const double s = seconds_since(start);
      if (reply.step != step.step) throw std::runtime_error("out-of-order Forces");
      if (r >= 100) framed.push_back(s);  // the first 100 warm up
    }
    peer.join();
  }
  {
    RawPair pair;
    const std::size_t out_bytes = 4 * vertices * sizeof(double) + 24;
    const std::size_t back_bytes = 2 * vertices * sizeof(double) + 8;
    std::vector<char> out(out_bytes, 1), back(back_bytes, 2), in_client(out_bytes),
        in_server(back_bytes);
    std::thread peer([&] {
      for (int r = 0; r < round_trips + 100; ++r) {
        read_all(pair.client, in_client.data(), out_bytes);
        write_all(pair.client, back.data(), back_bytes);
      }
    });
    for (int r = 0; r < round_trips + 100; ++r) {
      const auto start = Clock::now();
      write_all(pair.server, out.data(), out_bytes);
      read_all(pair.server, in_server.data(), back_bytes);
      const double s = seconds_since(start);
      if (r >= 100) raw.push_back(s);
    }
    peer.join();
  }
  std::sort(framed.begin(), framed.end());
  std::sort(raw.begin(), raw.end());
  auto percentile = [](const std::vector<double>& v, double p) {
    return v[static_cast<std::size_t>(p * static_cast<double>(v.size() - 1))] * 1e6;
  };
  std::printf(
      "latency, step exchange with %zu dynamic 2D vertices (Step r,v out; Forces f back), "
      "%d round trips:\n",
      vertices, round_trips);
  std::printf("  fsi::protocol: median %.1f us, 90 %% %.1f us, 99 %% %.1f us\n",
              percentile(framed, 0.5), percentile(framed, 0.9), percentile(framed, 0.99));
  std::printf("  raw socket:    median %.1f us, 90 %% %.1f us, 99 %% %.1f us\n",
              percentile(raw, 0.5), percentile(raw, 0.9), percentile(raw, 0.99));
}

}  // namespace

int main(int argc, char** argv) {
  std::size_t doubles = 4'000'000;
  std::size_t vertices = 1000;
  int round_trips = 3000;
  for (int i = 1; i < argc; ++i) {
    const std::string option = argv[i];
    if (i + 1 >= argc) {
      std::fprintf(stderr, "%s: option %s needs a value\n", argv[0], option.c_str());
      return 2;
    }
    const long value = std::atol(argv[++i]);
    if (value <= 0) {
      std::fprintf(stderr, "%s: %s needs a positive integer\n", argv[0], option.c_str());
      return 2;
    }
    if (option == "--doubles") {
      doubles = static_cast<std::size_t>(value);
    } else if (option == "--vertices") {
      vertices = static_cast<std::size_t>(value);
    } else if (option == "--round-trips") {
      round_trips = static_cast<int>(value);
    } else {
      std::fprintf(stderr, "usage: %s [--doubles N] [--vertices V] [--round-trips R]\n", argv[0]);
      return 2;
    }
  }
  try {
    throughput(doubles, 15);
    latency(vertices, round_trips);
  } catch (const std::exception& failure) {
    std::fprintf(stderr, "bench_protocol_transport: %s\n", failure.what());
    return 1;
  }
  return 0;
}
