// Boost.Asio 1.74 with GCC 12 in C++20 needs <utility> before <boost/asio.hpp> (ARCHITECTURE §12).
#include <utility>

#include <boost/asio.hpp>

#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <sys/socket.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <limits>
#include <thread>
#include <vector>

#include "fsi/protocol/channel.hpp"

namespace fsi::protocol {
namespace asio = boost::asio;
using tcp = asio::ip::tcp;
using Clock = std::chrono::steady_clock;
using Deadline = std::optional<Clock::time_point>;
using boost::system::error_code;

namespace {

// The first piece of a payload is read into at most this much memory; the buffer then doubles
// with the bytes that actually arrive, so a header announcing a huge payload costs nothing until
// the data is there.
constexpr std::size_t kFirstPayloadPiece = std::size_t{1} << 20;

// Decoding straight from the socket: fields are read through a staging buffer of this size;
// longer reads go into the destination directly, in pieces whose CRC runs (on data still in the
// cache) while the peer sends the next piece.
constexpr std::size_t kStagingBytes = std::size_t{64} << 10;
constexpr std::size_t kCrcPieceBytes = std::size_t{256} << 10;

constexpr const char* kPeerEnded =
    "the other program ended or lost the network; its output or log says why";

Deadline deadline_after(std::optional<Milliseconds> timeout) {
  if (!timeout) return std::nullopt;
  return Clock::now() + *timeout;
}

std::string duration_text(Milliseconds duration) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g s", static_cast<double>(duration.count()) / 1000.0);
  return text;
}

std::string endpoint_text(const tcp::endpoint& endpoint) {
  const auto address = endpoint.address();
  const std::string host = address.is_v6() ? "[" + address.to_string() + "]" : address.to_string();
  return host + ":" + std::to_string(endpoint.port());
}

bool is_disconnect(const error_code& error) {
  return error == asio::error::eof || error == asio::error::connection_reset ||
         error == asio::error::broken_pipe || error == asio::error::connection_aborted ||
         error == asio::error::not_connected || error == asio::error::bad_descriptor;
}

// Runs the context until `finished` is set by the handler of the one outstanding operation. If
// the deadline passes first, cancel() aborts the operation and the context runs on until its
// handler has seen the abort. Returns whether the deadline passed; the operation may still have
// completed in that race, which its error code tells.
template <class Cancel>
bool run_until(asio::io_context& context, const bool& finished, const Deadline& deadline,
               Cancel&& cancel) {
  context.restart();
  bool expired = false;
  while (!finished) {
    if (deadline && !expired) {
      if (Clock::now() >= *deadline) {
        expired = true;
        cancel();
        continue;
      }
      context.run_one_until(*deadline);
    } else {
      context.run_one();
    }
    if (context.stopped() && !finished) context.restart();
  }
  return expired;
}

// Keep-alive probes let a blocking wait without timeout notice a peer host that vanished
// without closing the connection (about 2 minutes: 60 s idle, then 6 probes 10 s apart).
void enable_keep_alive(tcp::socket& socket) {
  error_code ignored;
  socket.set_option(asio::socket_base::keep_alive(true), ignored);
  const int handle = socket.native_handle();
  const int idle_seconds = 60;
  const int probe_interval_seconds = 10;
  const int probe_count = 6;
  ::setsockopt(handle, IPPROTO_TCP, TCP_KEEPIDLE, &idle_seconds, sizeof idle_seconds);
  ::setsockopt(handle, IPPROTO_TCP, TCP_KEEPINTVL, &probe_interval_seconds,
               sizeof probe_interval_seconds);
  ::setsockopt(handle, IPPROTO_TCP, TCP_KEEPCNT, &probe_count, sizeof probe_count);
}

// Asio's transfer_all moves at most 64 KiB per system call, so a frame of megabytes would take
// hundreds of calls and as many wake-ups; this completion condition asks for all that is left.
struct TransferAllAtOnce {
  std::size_t operator()(const error_code& error, std::size_t) const {
    return error ? 0 : std::numeric_limits<std::size_t>::max();
  }
};

struct Transfer {
  error_code error;
  std::size_t bytes = 0;
  bool timed_out = false;
};

}  // namespace

struct Channel::Impl {
  asio::io_context context;
  tcp::socket socket{context};
  ChannelOptions options;
  std::string peer = "unconnected peer";
  std::uint16_t peer_major = 0;
  std::uint16_t peer_minor = 0;
  std::uint64_t heartbeats_received = 0;
  // The current wait for a frame (receive_header): when it began and the heartbeats it saw, for
  // the timeout's message (a peer that fell silent against one that never sent any).
  Clock::time_point wait_began{};
  std::uint64_t wait_heartbeats = 0;
  Clock::time_point last_heartbeat{};
  std::array<std::byte, kHeaderSize> header_bytes{};
  std::vector<std::byte> payload_buffer;  // reused from frame to frame
  std::vector<std::byte> staging;         // for decoding from the socket (FrameSource)
  GatheredPayload gathered;               // reused for every sent message
  std::vector<asio::const_buffer> send_buffers;
  std::string unusable_because;       // set once the incoming stream can no longer be trusted
  std::string send_unusable_because;  // set once a frame went out only in part

  explicit Impl(const ChannelOptions& channel_options) : options(channel_options) {}

  void configure_connected_socket() {
    error_code ignored;
    socket.set_option(tcp::no_delay(true), ignored);
    enable_keep_alive(socket);
    const auto remote = socket.remote_endpoint(ignored);
    if (!ignored) peer = endpoint_text(remote);
  }

  // Fills `into` from the socket. Straight system calls rather than an Asio operation: a frame
  // of megabytes arrives in hundreds of pieces, and each Asio read would cost a pass through the
  // io_context (an epoll_wait) besides the recv. recv asks for everything that is left; poll
  // waits, up to the deadline, only when nothing is there.
  Transfer read(std::span<std::byte> into, const Deadline& deadline) {
    Transfer transfer;
    const int handle = socket.native_handle();
    while (transfer.bytes < into.size()) {
      const ssize_t received =
          ::recv(handle, into.data() + transfer.bytes, into.size() - transfer.bytes, MSG_DONTWAIT);
      if (received > 0) {
        transfer.bytes += static_cast<std::size_t>(received);
        continue;
      }
      if (received == 0) {
        transfer.error = asio::error::eof;
        break;
      }
      if (errno == EINTR) continue;
      if (errno != EAGAIN && errno != EWOULDBLOCK) {
        transfer.error = error_code(errno, boost::system::system_category());
        break;
      }
      int wait_milliseconds = -1;
      if (deadline) {
        const auto left = *deadline - Clock::now();
        if (left <= Clock::duration::zero()) {
          transfer.timed_out = true;
          break;
        }
        // Rounded up, so that the wait does not end just before the deadline.
        wait_milliseconds = static_cast<int>(
            std::min<Clock::rep>(std::chrono::ceil<Milliseconds>(left).count(), 1 << 30));
      }
      pollfd wait_for_data{handle, POLLIN, 0};
      if (::poll(&wait_for_data, 1, wait_milliseconds) < 0 && errno != EINTR) {
        transfer.error = error_code(errno, boost::system::system_category());
        break;
      }
    }
    return transfer;
  }

  // Reports a failed read. Only a timeout before the first byte of a frame leaves the stream in
  // step; everything else makes the channel unusable for further receives.
  [[noreturn]] void fail_read(const Transfer& transfer, std::optional<Milliseconds> timeout,
                              std::string_view waiting_for, std::size_t frame_bytes_before,
                              const std::string& progress) {
    const std::size_t frame_bytes = frame_bytes_before + transfer.bytes;
    const std::string in_frame = frame_bytes > 0 ? " (" + progress + ")" : std::string();
    const std::string where = "connection to " + peer;
    std::string fault;
    std::string fix;
    if (transfer.timed_out) {
      fault = "timed out after " + duration_text(timeout.value_or(Milliseconds{0})) +
              " while waiting for " + std::string(waiting_for) + " from " + peer + in_frame +
              heartbeat_history();
      fix =
          "the peer is stuck, overloaded or waiting for us; check its output, or allow a "
          "longer timeout";
    } else if (is_disconnect(transfer.error)) {
      fault = "connection closed by peer " + peer + " while waiting for " +
              std::string(waiting_for) + in_frame;
      fix = kPeerEnded;
    } else {
      fault = "receiving from " + peer + " failed while waiting for " + std::string(waiting_for) +
              in_frame + ": " + transfer.error.message();
      fix = "check the network and the peer";
    }
    if (!(transfer.timed_out && frame_bytes == 0)) unusable_because = fault;
    if (transfer.timed_out) throw PeerTimeoutError(fault, where, fix);
    throw ProtocolError(fault, where, fix);
  }

  // What the heartbeats said during the wait that timed out: none at all (the peer never told us
  // it computes), or how many and how long before the timeout the last one came.
  std::string heartbeat_history() const {
    const auto seconds = [](Clock::duration span) {
      char text[32];
      std::snprintf(text, sizeof text, "%.2f s", std::chrono::duration<double>(span).count());
      return std::string(text);
    };
    const auto now = Clock::now();
    if (wait_heartbeats == 0)
      return "; no heartbeat arrived in this wait of " + seconds(now - wait_began);
    return "; " + std::to_string(wait_heartbeats) + " heartbeat(s) arrived in this wait of " +
           seconds(now - wait_began) + ", the last " + seconds(now - last_heartbeat) +
           " before the timeout";
  }

  // Adds the peer and the wait to a fault found in a received frame, and marks the stream
  // unusable: after a bad header the frame boundaries are lost.
  [[noreturn]] void fail_frame(const ProtocolError& error, std::string_view waiting_for) {
    unusable_because = error.fault();
    const std::string where =
        error.location() + " from " + peer + ", while waiting for " + std::string(waiting_for);
    if (dynamic_cast<const VersionMismatchError*>(&error) != nullptr)
      throw VersionMismatchError(error.fault(), where, error.remedy());
    throw ProtocolError(error.fault(), where, error.remedy());
  }

  class FrameSource;

  // A header that was read and checked, and the deadline of its frame.
  struct Incoming {
    FrameHeader header;
    Deadline deadline;
  };

  // Reads one frame; its payload is the first payload_length bytes of payload_buffer.
  FrameHeader receive_frame(std::optional<Milliseconds> timeout, std::string_view waiting_for) {
    const Incoming incoming = receive_header(timeout, waiting_for);
    read_payload(incoming, timeout, waiting_for);
    return incoming.header;
  }

  // Reads frame headers, consuming Heartbeat frames, until one of another type arrives; its
  // payload is next on the socket.
  Incoming receive_header(std::optional<Milliseconds> timeout, std::string_view waiting_for) {
    if (!socket.is_open()) {
      throw ProtocolError(
          "cannot wait for " + std::string(waiting_for) + ": the channel to " + peer + " is closed",
          "connection to " + peer, "this is a bug in the caller");
    }
    if (!unusable_because.empty()) {
      throw ProtocolError("cannot wait for " + std::string(waiting_for) + " from " + peer +
                              ": the channel is unusable after an earlier fault (" +
                              unusable_because + ")",
                          "connection to " + peer, "close the channel and reconnect");
    }
    // Heartbeats (1.1) say "still computing": each one starts the timeout again, so the timeout
    // measures the peer's silence rather than its compute time.
    wait_began = Clock::now();
    wait_heartbeats = 0;
    while (true) {
      const Incoming incoming = receive_one_header(timeout, waiting_for);
      const FrameHeader& header = incoming.header;
      if (header.type != MessageType::Heartbeat) return incoming;
      read_payload(incoming, timeout, waiting_for);
      if (header.payload_length != 0) {
        fail_frame(
            ProtocolError("malformed Heartbeat message: " + std::to_string(header.payload_length) +
                              " payload bytes, a Heartbeat has none",
                          "Heartbeat frame",
                          "the peer is faulty; use matching releases of fsi-server and "
                          "fsi-client"),
            waiting_for);
      }
      ++heartbeats_received;
      ++wait_heartbeats;
      last_heartbeat = Clock::now();
    }
  }

  Incoming receive_one_header(std::optional<Milliseconds> timeout, std::string_view waiting_for) {
    const Deadline deadline = deadline_after(timeout);
    const Transfer head = read(header_bytes, deadline);
    if (head.error || head.timed_out) {
      fail_read(head, timeout, waiting_for, 0,
                "received " + std::to_string(head.bytes) + " of the 20 header bytes");
    }
    FrameHeader header;
    try {
      header = decode_header(header_bytes, options.max_payload, options.major);
    } catch (const ProtocolError& error) {
      fail_frame(error, waiting_for);
    }
    peer_major = header.major;
    peer_minor = header.minor;
    return Incoming{header, deadline};
  }

  std::string payload_progress(std::size_t received, const FrameHeader& header) const {
    return "received " + std::to_string(received) + " of the " +
           std::to_string(header.payload_length) + " payload bytes of a " + name(header.type) +
           " frame";
  }

  // Reads the payload of the frame whose header came last into payload_buffer and checks the CRC.
  void read_payload(const Incoming& incoming, std::optional<Milliseconds> timeout,
                    std::string_view waiting_for) {
    const FrameHeader& header = incoming.header;
    const std::size_t length = header.payload_length;
    std::size_t filled = 0;
    // The CRC runs over each piece as it arrives, while the peer still sends the rest.
    std::uint32_t crc = crc32c(std::span<const std::byte>(header_bytes).first(16));
    while (filled < length) {
      const std::size_t target =
          std::min(length, std::max({payload_buffer.size(), 2 * filled, kFirstPayloadPiece}));
      if (payload_buffer.size() < target) payload_buffer.resize(target);
      const Transfer piece =
          read(std::span(payload_buffer).subspan(filled, target - filled), incoming.deadline);
      crc = crc32c(std::span<const std::byte>(payload_buffer).subspan(filled, piece.bytes), crc);
      filled += piece.bytes;
      if (piece.error || piece.timed_out) {
        fail_read(piece, timeout, waiting_for, kHeaderSize + filled - piece.bytes,
                  payload_progress(filled, header));
      }
    }
    try {
      check_crc(header, crc, length);
    } catch (const ProtocolError& error) {
      fail_frame(error, waiting_for);
    }
  }

  // Decodes the payload of the frame whose header came last straight from the socket. A fault in
  // the content is reported once the rest of the frame is read and its CRC is right (a damaged
  // frame is reported as damaged, and the stream stays in step).
  template <class Decode>
  void decode_payload(const Incoming& incoming, std::optional<Milliseconds> timeout,
                      std::string_view waiting_for, Decode&& decode);

  void close() {
    if (!socket.is_open()) return;
    error_code ignored;
    socket.shutdown(tcp::socket::shutdown_send, ignored);
    // Closing with unread data makes the kernel send a reset, which may destroy the last message
    // we sent before the peer reads it. So read and discard until the peer closes too.
    if (options.close_linger.count() > 0 && !ignored) {
      const Deadline deadline = Clock::now() + options.close_linger;
      std::array<std::byte, 4096> discard;
      while (true) {
        bool finished = false;
        error_code error;
        socket.async_read_some(asio::buffer(discard), [&](const error_code& e, std::size_t) {
          error = e;
          finished = true;
        });
        run_until(context, finished, deadline, [this] {
          error_code cancel_ignored;
          socket.cancel(cancel_ignored);
        });
        if (error) break;  // end of stream, deadline or a broken connection
      }
    }
    socket.close(ignored);
  }
};

// The payload of the frame whose header was just read, as it arrives from the socket. Small reads
// are served from a staging buffer; reads of kStagingBytes or more go straight into the
// destination. The CRC runs over every byte as it comes in and is checked at the end.
class Channel::Impl::FrameSource final : public PayloadSource {
 public:
  FrameSource(Channel::Impl& channel, const Channel::Impl::Incoming& incoming,
              std::optional<Milliseconds> timeout, std::string_view waiting_for)
      : channel_(channel),
        incoming_(incoming),
        timeout_(timeout),
        waiting_for_(waiting_for),
        crc_(crc32c(std::span<const std::byte>(channel.header_bytes).first(16))) {
    if (channel_.staging.size() < kStagingBytes) channel_.staging.resize(kStagingBytes);
  }

  std::size_t remaining() const override { return length() - consumed_; }
  std::size_t available() const override { return staged_end_ - staged_begin_; }

  void read(std::span<std::byte> into) override {
    const std::size_t staged = std::min(into.size(), available());
    if (staged > 0) std::memcpy(into.data(), channel_.staging.data() + staged_begin_, staged);
    staged_begin_ += staged;
    consumed_ += staged;
    const auto rest = into.subspan(staged);
    if (rest.empty()) return;
    if (rest.size() >= kStagingBytes) {
      receive_checked(rest);
      consumed_ += rest.size();
      return;
    }
    // rest.size() <= remaining() = length() - received_, since nothing is staged any more.
    const std::size_t refill = std::min(kStagingBytes, length() - received_);
    receive_checked(std::span(channel_.staging).first(refill));
    std::memcpy(rest.data(), channel_.staging.data(), rest.size());
    staged_begin_ = rest.size();
    staged_end_ = refill;
    consumed_ += rest.size();
  }

  // Into payload_buffer, which the channel keeps from frame to frame; it grows in steps doubling
  // from 1 MiB as the bytes arrive, so memory still follows the bytes that actually arrive.
  std::span<const std::byte> read_buffered(std::size_t bytes) override {
    auto& buffer = channel_.payload_buffer;
    const std::size_t staged = std::min(bytes, available());
    if (buffer.size() < staged) buffer.resize(staged);
    if (staged > 0) std::memcpy(buffer.data(), channel_.staging.data() + staged_begin_, staged);
    staged_begin_ += staged;
    std::size_t filled = staged;
    while (filled < bytes) {
      const std::size_t target =
          std::min(bytes, std::max({buffer.size(), 2 * filled, kFirstPayloadPiece}));
      if (buffer.size() < target) buffer.resize(target);
      receive_checked(std::span(buffer).subspan(filled, target - filled));
      filled = target;
    }
    consumed_ += bytes;
    return std::span<const std::byte>(buffer).first(bytes);
  }

  void end() override { check_crc(); }

  // After a fault in the content: reads what is left of the frame and checks its CRC.
  void finish_after_content_fault() {
    staged_begin_ = staged_end_;
    while (received_ < length()) {
      const std::size_t piece = std::min(kStagingBytes, length() - received_);
      receive_checked(std::span(channel_.staging).first(piece));
    }
    consumed_ = length();
    if (!crc_checked_) check_crc();
  }

  // Whether the fault thrown was the connection's or the CRC's rather than the content's.
  bool connection_failed() const { return connection_failed_; }

 private:
  std::size_t length() const { return incoming_.header.payload_length; }

  void receive_checked(std::span<std::byte> into) {
    std::size_t done = 0;
    while (done < into.size()) {
      const std::size_t piece = std::min(kCrcPieceBytes, into.size() - done);
      const Transfer transfer = channel_.read(into.subspan(done, piece), incoming_.deadline);
      crc_ = crc32c(into.subspan(done, transfer.bytes), crc_);
      done += transfer.bytes;
      received_ += transfer.bytes;
      if (transfer.error || transfer.timed_out) {
        connection_failed_ = true;
        channel_.fail_read(transfer, timeout_, waiting_for_,
                           kHeaderSize + received_ - transfer.bytes,
                           channel_.payload_progress(received_, incoming_.header));
      }
    }
  }

  void check_crc() {
    crc_checked_ = true;
    try {
      fsi::protocol::check_crc(incoming_.header, crc_, length());
    } catch (const ProtocolError& error) {
      connection_failed_ = true;
      channel_.fail_frame(error, waiting_for_);
    }
  }

  Channel::Impl& channel_;
  const Channel::Impl::Incoming& incoming_;
  std::optional<Milliseconds> timeout_;
  std::string_view waiting_for_;
  std::uint32_t crc_;
  std::size_t received_ = 0;  // from the socket
  std::size_t consumed_ = 0;  // by the decoder
  std::size_t staged_begin_ = 0;
  std::size_t staged_end_ = 0;
  bool crc_checked_ = false;
  bool connection_failed_ = false;
};

template <class Decode>
void Channel::Impl::decode_payload(const Incoming& incoming, std::optional<Milliseconds> timeout,
                                   std::string_view waiting_for, Decode&& decode) {
  FrameSource source(*this, incoming, timeout, waiting_for);
  try {
    decode(static_cast<PayloadSource&>(source));
  } catch (const ProtocolError& error) {
    if (source.connection_failed()) throw;
    source.finish_after_content_fault();
    // The frame was whole, so the stream is still in step; the caller decides what to do.
    throw ProtocolError(error.fault(), error.location() + " from " + peer, error.remedy());
  }
}

Channel::Channel(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
Channel::Channel(Channel&&) noexcept = default;

Channel& Channel::operator=(Channel&& other) noexcept {
  if (this != &other) {
    if (impl_) impl_->close();
    impl_ = std::move(other.impl_);
  }
  return *this;
}

Channel::~Channel() {
  if (impl_) impl_->close();
}

Channel Channel::connect(const std::string& host, std::uint16_t port, Milliseconds give_up_after,
                         const ChannelOptions& options) {
  auto impl = std::make_unique<Impl>(options);
  const std::string target = host + ":" + std::to_string(port);
  const auto deadline = Clock::now() + give_up_after;
  Milliseconds pause{50};
  int attempts = 0;
  std::string last_problem;
  while (true) {
    ++attempts;
    tcp::resolver resolver(impl->context);
    tcp::resolver::results_type endpoints;
    error_code error;
    bool finished = false;
    resolver.async_resolve(host, std::to_string(port),
                           [&](const error_code& e, tcp::resolver::results_type results) {
                             error = e;
                             endpoints = std::move(results);
                             finished = true;
                           });
    run_until(impl->context, finished, deadline, [&] { resolver.cancel(); });
    if (error) {
      if (error != asio::error::operation_aborted || last_problem.empty()) {
        last_problem = error == asio::error::operation_aborted
                           ? "name resolution did not finish in time"
                           : "cannot resolve '" + host + "': " + error.message();
      }
    } else {
      finished = false;
      asio::async_connect(impl->socket, endpoints, [&](const error_code& e, const tcp::endpoint&) {
        error = e;
        finished = true;
      });
      run_until(impl->context, finished, deadline, [&] {
        error_code ignored;
        impl->socket.close(ignored);
      });
      if (!error) {
        impl->configure_connected_socket();
        return Channel(std::move(impl));
      }
      // An attempt cut short by the deadline says less than the refusal before it.
      if (error != asio::error::operation_aborted || last_problem.empty()) {
        last_problem =
            error == asio::error::operation_aborted ? "no answer in time" : error.message();
      }
      error_code ignored;
      impl->socket.close(ignored);
    }
    const auto left = deadline - Clock::now();
    if (left <= Clock::duration::zero()) break;
    std::this_thread::sleep_for(std::min<Clock::duration>(pause, left));
    if (Clock::now() >= deadline) break;
    pause = std::min(pause * 2, Milliseconds{1000});
  }
  throw ProtocolError("cannot connect to fsi-server at " + target + " within " +
                          duration_text(give_up_after) + " (" + std::to_string(attempts) +
                          " attempts; last: " + last_problem + ")",
                      "connecting to " + target,
                      "check that fsi-server is running and listening on " + target +
                          " (it prints its address and port when it starts), that host and "
                          "port are right, and that no firewall blocks the port; or allow more "
                          "time to connect");
}

void Channel::send(MessageType type, std::span<const std::byte> payload) {
  send_pieces(type, std::span(&payload, 1));
}

void Channel::send_pieces(MessageType type, std::span<const std::span<const std::byte>> pieces) {
  Impl& impl = *impl_;
  if (!impl.socket.is_open()) {
    throw ProtocolError(
        "cannot send " + name(type) + ": the channel to " + impl.peer + " is closed",
        "connection to " + impl.peer, "this is a bug in the caller");
  }
  if (!impl.send_unusable_because.empty()) {
    throw ProtocolError("cannot send " + name(type) + " to " + impl.peer + ": " +
                            impl.send_unusable_because + ", so the peer can no longer find frames",
                        "connection to " + impl.peer, "close the channel and reconnect");
  }
  const auto header =
      encode_header_for_pieces(type, pieces, impl.options.major, impl.options.minor);
  std::size_t payload_size = 0;
  auto& buffers = impl.send_buffers;
  buffers.clear();
  buffers.push_back(asio::buffer(header.data(), header.size()));
  for (const auto& piece : pieces) {
    if (piece.empty()) continue;
    buffers.push_back(asio::buffer(piece.data(), piece.size()));
    payload_size += piece.size();
  }
  const auto& pieces_to_write = buffers;
  Transfer transfer;
  if (!impl.options.send_timeout) {
    asio::write(impl.socket, pieces_to_write, TransferAllAtOnce{}, transfer.error);
  } else {
    bool finished = false;
    asio::async_write(impl.socket, pieces_to_write, TransferAllAtOnce{},
                      [&](const error_code& error, std::size_t bytes) {
                        transfer.error = error;
                        transfer.bytes = bytes;
                        finished = true;
                      });
    const bool expired =
        run_until(impl.context, finished, deadline_after(impl.options.send_timeout), [&] {
          error_code ignored;
          impl.socket.cancel(ignored);
        });
    transfer.timed_out = expired && transfer.error == asio::error::operation_aborted;
  }
  if (!transfer.error && !transfer.timed_out) return;
  const std::string where = "connection to " + impl.peer;
  if (transfer.timed_out) {
    // Part of the frame may be out; the peer can no longer find frame boundaries.
    impl.send_unusable_because = "an earlier send timed out part-way";
    throw ProtocolError("timed out after " + duration_text(*impl.options.send_timeout) +
                            " sending a " + name(type) + " frame of " +
                            std::to_string(kHeaderSize + payload_size) + " bytes to " + impl.peer +
                            " (" + std::to_string(transfer.bytes) + " sent)",
                        where, "the peer does not read; check that it is alive");
  }
  if (is_disconnect(transfer.error)) {
    throw ProtocolError("connection closed by peer " + impl.peer + " while sending " + name(type),
                        where, kPeerEnded);
  }
  throw ProtocolError(
      "sending " + name(type) + " to " + impl.peer + " failed: " + transfer.error.message(), where,
      "check the network and the peer");
}

void Channel::send(const Message& message) {
  std::visit([this](const auto& alternative) { send(alternative); }, message);
}

GatheredPayload& Channel::gathered_payload() {
  return impl_->gathered;
}

Frame Channel::receive(std::optional<Milliseconds> timeout, std::string_view waiting_for) {
  Impl& impl = *impl_;
  Frame frame;
  frame.header = impl.receive_frame(timeout, waiting_for);
  // The caller keeps the payload, so the buffer goes with it instead of being copied.
  impl.payload_buffer.resize(frame.header.payload_length);
  frame.payload = std::move(impl.payload_buffer);
  impl.payload_buffer = {};
  return frame;
}

Message Channel::receive_message(std::optional<Milliseconds> timeout,
                                 std::string_view waiting_for) {
  Impl& impl = *impl_;
  const Impl::Incoming incoming = impl.receive_header(timeout, waiting_for);
  Message message;
  impl.decode_payload(incoming, timeout, waiting_for, [&](PayloadSource& source) {
    message = decode(incoming.header.type, source);
  });
  return message;
}

template <ProtocolMessage T>
void Channel::expect_into(T& message, std::optional<Milliseconds> timeout) {
  Impl& impl = *impl_;
  const std::string waiting_for = name(T::kType);
  const Impl::Incoming incoming = impl.receive_header(timeout, waiting_for);
  if (incoming.header.type == T::kType) {
    impl.decode_payload(incoming, timeout, waiting_for,
                        [&](PayloadSource& source) { decode_into(source, message); });
    return;
  }
  Message other;
  impl.decode_payload(incoming, timeout, waiting_for,
                      [&](PayloadSource& source) { other = decode(incoming.header.type, source); });
  throw_unexpected(T::kType, other);
}

#define FSI_PROTOCOL_INSTANTIATE_EXPECT(enumerator, message, id) \
  template void Channel::expect_into(message&, std::optional<Milliseconds>);
FSI_PROTOCOL_MESSAGES(FSI_PROTOCOL_INSTANTIATE_EXPECT)
#undef FSI_PROTOCOL_INSTANTIATE_EXPECT

void Channel::throw_unexpected(MessageType expected, const Message& received) const {
  const std::string where =
      "connection to " + impl_->peer + ", while waiting for " + name(expected);
  if (const auto* error = std::get_if<ErrorMessage>(&received)) {
    throw PeerReportedError(error->code, error->text, where);
  }
  throw UnexpectedMessageError(
      "expected a " + name(expected) + " message but received " + name(type_of(received)), where,
      "use matching releases of fsi-server and fsi-client");
}

std::string Channel::peer_description() const {
  return impl_->peer;
}
const ChannelOptions& Channel::options() const {
  return impl_->options;
}
std::uint16_t Channel::peer_major() const {
  return impl_->peer_major;
}
std::uint64_t Channel::heartbeats_received() const {
  return impl_->heartbeats_received;
}
std::uint16_t Channel::peer_minor() const {
  return impl_->peer_minor;
}
bool Channel::is_open() const {
  return impl_ && impl_->socket.is_open();
}
void Channel::close() {
  if (impl_) impl_->close();
}

bool Channel::try_send_heartbeat() {
  Impl& impl = *impl_;
  if (!impl.socket.is_open() || !impl.send_unusable_because.empty()) return false;
  const auto frame =
      encode_header(MessageType::Heartbeat, {}, impl.options.major, impl.options.minor);
  const int handle = impl.socket.native_handle();
  std::size_t sent = 0;
  const auto give_up = Clock::now() + Milliseconds{1000};
  while (sent < frame.size()) {
    const ssize_t written =
        ::send(handle, frame.data() + sent, frame.size() - sent, MSG_DONTWAIT | MSG_NOSIGNAL);
    if (written > 0) {
      sent += static_cast<std::size_t>(written);
      continue;
    }
    const bool would_block = written < 0 && (errno == EAGAIN || errno == EWOULDBLOCK);
    // Nothing went out: skip this heartbeat (a peer that does not read needs none).
    if (sent == 0) return false;
    // Part of the header is out: the rest must follow, or the stream has lost its frame
    // boundaries.
    if (!would_block || Clock::now() >= give_up) {
      impl.send_unusable_because = "a heartbeat went out only in part";
      return false;
    }
    pollfd wait_for_room{handle, POLLOUT, 0};
    ::poll(&wait_for_room, 1, 50);
  }
  return true;
}

HeartbeatSender::HeartbeatSender(Channel& channel, bool enabled, Milliseconds interval)
    : channel_(channel), interval_(interval) {
  if (enabled) thread_ = std::thread([this] { run(); });
}

HeartbeatSender::~HeartbeatSender() {
  stop();
}

void HeartbeatSender::stop() {
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  wake_.notify_all();
  if (thread_.joinable() && thread_.get_id() != std::this_thread::get_id()) thread_.join();
}

std::uint64_t HeartbeatSender::sent() const {
  std::lock_guard lock(mutex_);
  return sent_;
}

void HeartbeatSender::set_busy(bool busy) {
  // No wake-up of the thread: toggling costs a lock per compute phase, not two context switches.
  // Taking the lock waits for a heartbeat being sent, so afterwards the owner has the channel.
  std::lock_guard lock(mutex_);
  busy_ = busy;
  if (busy) busy_since_ = std::chrono::steady_clock::now();
}

void HeartbeatSender::run() {
  // The thread looks four times per interval, so the peer hears from a busy side at most
  // 1.25 intervals apart.
  const auto tick = std::max(Milliseconds{1}, interval_ / 4);
  std::unique_lock lock(mutex_);
  while (!stopping_) {
    wake_.wait_for(lock, tick, [this] { return stopping_; });
    if (stopping_ || !busy_) continue;
    const auto now = std::chrono::steady_clock::now();
    if (now - busy_since_ < interval_) continue;
    // Still busy an interval after the start or the last heartbeat. The lock is held while
    // sending (see set_busy).
    if (channel_.is_open() && channel_.try_send_heartbeat()) {
      ++sent_;
      last_sent_ = std::chrono::steady_clock::now();
    }
    busy_since_ = now;
  }
}

std::optional<std::chrono::steady_clock::time_point> HeartbeatSender::last_sent() const {
  std::lock_guard lock(mutex_);
  return last_sent_;
}

HeartbeatSender::Busy HeartbeatSender::busy() {
  return Busy(thread_.joinable() ? this : nullptr);
}

HeartbeatSender::Busy::Busy(HeartbeatSender* sender) : sender_(sender) {
  if (sender_) sender_->set_busy(true);
}
HeartbeatSender::Busy::Busy(Busy&& other) noexcept
    : sender_(std::exchange(other.sender_, nullptr)) {}
HeartbeatSender::Busy& HeartbeatSender::Busy::operator=(Busy&& other) noexcept {
  if (this != &other) {
    if (sender_) sender_->set_busy(false);
    sender_ = std::exchange(other.sender_, nullptr);
  }
  return *this;
}
HeartbeatSender::Busy::~Busy() {
  if (sender_) sender_->set_busy(false);
}

bool is_loopback_address(const std::string& numeric_address) {
  error_code error;
  const auto address = asio::ip::make_address(numeric_address, error);
  return !error && address.is_loopback();
}

struct Listener::Impl {
  asio::io_context context;
  tcp::acceptor acceptor{context};
  ChannelOptions options;
  std::string address;
  std::uint16_t port = 0;
};

Listener::Listener(const std::string& address, std::uint16_t port, const ChannelOptions& options)
    : impl_(std::make_unique<Impl>()) {
  impl_->options = options;
  impl_->address = address;
  const std::string where = "listening on " + address + ":" + std::to_string(port);
  error_code error;
  const auto ip = asio::ip::make_address(address, error);
  if (error) {
    throw fsi::Error("'" + address + "' is not a numeric IP address", where,
                     "give an address such as 127.0.0.1 (this host only) or 0.0.0.0 (all "
                     "interfaces)");
  }
  const tcp::endpoint endpoint(ip, port);
  impl_->acceptor.open(endpoint.protocol(), error);
  if (!error) impl_->acceptor.set_option(tcp::acceptor::reuse_address(true), error);
  if (!error) impl_->acceptor.bind(endpoint, error);
  if (!error) impl_->acceptor.listen(asio::socket_base::max_listen_connections, error);
  if (error) {
    std::string fix = "choose an address of this host and a free port";
    if (error == asio::error::address_in_use) {
      fix = "another program (perhaps another fsi-server) uses port " + std::to_string(port) +
            "; stop it or choose another port (0 lets the system choose one)";
    } else if (error == asio::error::access_denied) {
      fix = "ports below 1024 need privileges; choose a port above 1023";
    } else if (error == boost::system::errc::address_not_available) {
      fix = address +
            " is not an address of this host; use 127.0.0.1, 0.0.0.0 or an address "
            "listed by 'ip addr'";
    }
    throw fsi::Error(
        "cannot listen on " + address + ":" + std::to_string(port) + ": " + error.message(), where,
        fix);
  }
  impl_->port = impl_->acceptor.local_endpoint(error).port();
}

Listener::Listener(Listener&&) noexcept = default;
Listener& Listener::operator=(Listener&&) noexcept = default;
Listener::~Listener() = default;

std::uint16_t Listener::port() const {
  return impl_->port;
}
std::string Listener::address() const {
  return impl_->address;
}

Channel Listener::accept(std::optional<Milliseconds> timeout) {
  auto channel = std::make_unique<Channel::Impl>(impl_->options);
  const std::string where = "listening on " + impl_->address + ":" + std::to_string(impl_->port);
  bool finished = false;
  error_code error;
  // The accepted socket belongs to the channel's own io_context.
  impl_->acceptor.async_accept(channel->socket, [&](const error_code& e) {
    error = e;
    finished = true;
  });
  const bool expired = run_until(impl_->context, finished, deadline_after(timeout), [this] {
    error_code ignored;
    impl_->acceptor.cancel(ignored);
  });
  if (expired && error == asio::error::operation_aborted) {
    throw ProtocolError(
        "no fsi-client connected within " + duration_text(*timeout), where,
        "start the client (mpirun -np N fsi-client --server HOST:" + std::to_string(impl_->port) +
            "), check that it can reach this address (firewall), or allow more "
            "time");
  }
  if (error) {
    throw ProtocolError("accepting a connection failed: " + error.message(), where,
                        "check the system's limits on open files and connections");
  }
  channel->configure_connected_socket();
  return Channel(std::move(channel));
}

}  // namespace fsi::protocol
