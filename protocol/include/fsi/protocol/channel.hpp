#pragma once
// A framed, checked message connection over TCP. Boost.Asio stays behind a pimpl. The API is
// synchronous; every wait can carry a timeout. A closed connection, a timeout or a malformed
// frame throws ProtocolError naming the fault, the peer and what was being waited for.
//
// A Channel or Listener is used by one thread at a time. Both are move-only; a moved-from object
// may only be destroyed or assigned to.

#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <thread>

#include "fsi/protocol/frame.hpp"
#include "fsi/protocol/messages.hpp"

namespace fsi::protocol {

using Milliseconds = std::chrono::milliseconds;

// How often a busy side sends Heartbeat frames (docs/protocol.md, "Waiting"; the first one an
// interval after the compute phase began, then one per interval, each at most a quarter interval
// late). A peer's receive timeout must be longer than 1.25 intervals.
inline constexpr Milliseconds kHeartbeatInterval{500};

struct ChannelOptions {
  // Version written into every sent header. Only tests that fake another peer change it.
  std::uint16_t major = kMajorVersion;
  std::uint16_t minor = kMinorVersion;
  // Largest payload accepted from the peer; longer frames are refused before any allocation.
  std::size_t max_payload = kDefaultMaxPayload;
  // Limit for one send (a peer that stops reading fills the socket buffers); none waits as long
  // as it takes.
  std::optional<Milliseconds> send_timeout;
  // close() first tells the peer "no more data" and waits up to this long for the peer to close
  // too, so that a last Error message is not destroyed by a TCP reset.
  Milliseconds close_linger{500};
};

class Channel {
 public:
  // Connects to an fsi-server at host:port (name or address), retrying with exponential back-off
  // (50 ms doubling to 1 s) until the server listens or give_up_after has passed; then throws
  // ProtocolError naming host:port.
  static Channel connect(const std::string& host, std::uint16_t port, Milliseconds give_up_after,
                         const ChannelOptions& options = {});

  Channel(Channel&&) noexcept;
  Channel& operator=(Channel&&) noexcept;
  ~Channel();  // closes like close()

  // One frame, header and payload gathered into one write.
  void send(MessageType type, std::span<const std::byte> payload);
  // A message's large arrays go out from where they lie (encode_gathered), without a copy.
  template <ProtocolMessage T>
  void send(const T& message) {
    GatheredPayload& payload = gathered_payload();
    encode_gathered(message, payload);
    send_pieces(T::kType, payload.pieces);
  }
  void send(const Message& message);

  // Receives one complete frame with a checked header and CRC, skipping Heartbeat frames: each
  // Heartbeat starts the timeout again, so it measures the peer's silence. No timeout waits for
  // ever; waiting_for words the errors ("Forces", "the set-up", ...). A timeout before the first
  // byte of a frame leaves the channel usable; any other receive fault makes later receives throw.
  Frame receive(std::optional<Milliseconds> timeout, std::string_view waiting_for = "a message");
  // Receives and decodes one message; large arrays are read straight into the message's vectors.
  Message receive_message(std::optional<Milliseconds> timeout,
                          std::string_view waiting_for = "a message");
  // Receives a T. An Error message throws "peer reported: <its text>"; any other message throws
  // naming the expected and the received type.
  template <ProtocolMessage T>
  T expect(std::optional<Milliseconds> timeout) {
    T message{};
    expect_into(message, timeout);
    return message;
  }
  // The same, decoding into message with the payload read from the socket straight into its
  // vectors: a message reused from step to step costs no allocation and no copy (decode_into).
  // After a throw, message holds an unspecified mix of old and new values.
  template <ProtocolMessage T>
  void expect_into(T& message, std::optional<Milliseconds> timeout);

  // "127.0.0.1:40312"
  std::string peer_description() const;
  const ChannelOptions& options() const;
  // Version in the last header received from the peer (0.0 before the first frame).
  std::uint16_t peer_major() const;
  std::uint16_t peer_minor() const;
  // Heartbeat frames consumed by receives so far.
  std::uint64_t heartbeats_received() const;
  bool is_open() const;
  // Ends the connection gracefully (see ChannelOptions::close_linger). Idempotent.
  void close();

 private:
  friend class Listener;
  friend class HeartbeatSender;
  // Sends one Heartbeat frame without blocking; false if it did not go out (socket buffer full,
  // connection gone). Only for HeartbeatSender, while the owning thread leaves the channel alone.
  bool try_send_heartbeat();
  // Reused for every message this channel sends (keeps the largest size it has needed).
  GatheredPayload& gathered_payload();
  // One frame whose payload is the concatenation of pieces, all gathered into one write.
  void send_pieces(MessageType type, std::span<const std::span<const std::byte>> pieces);
  struct Impl;
  explicit Channel(std::unique_ptr<Impl> impl);
  [[noreturn]] void throw_unexpected(MessageType expected, const Message& received) const;
  std::unique_ptr<Impl> impl_;
};

// Sends Heartbeat frames from a background thread while its owner computes (protocol 1.1,
// capability kCapabilityHeartbeat), so that the peer's receive timeout measures silence rather
// than compute time. During a Busy scope the owning thread must not use the channel; ending the
// scope waits for a heartbeat that is being sent, then the channel is the owner's again. Sends
// never block: a heartbeat that does not fit into the socket buffer is skipped.
class HeartbeatSender {
 public:
  // enabled = false (the peer did not announce kCapabilityHeartbeat): sends nothing.
  HeartbeatSender(Channel& channel, bool enabled, Milliseconds interval = kHeartbeatInterval);
  HeartbeatSender(const HeartbeatSender&) = delete;
  HeartbeatSender& operator=(const HeartbeatSender&) = delete;
  ~HeartbeatSender();

  // While alive, a Heartbeat goes out every interval. A default-constructed Busy does nothing.
  class Busy {
   public:
    Busy() = default;
    explicit Busy(HeartbeatSender* sender);
    Busy(Busy&& other) noexcept;
    Busy& operator=(Busy&& other) noexcept;
    ~Busy();

   private:
    HeartbeatSender* sender_ = nullptr;
  };
  [[nodiscard]] Busy busy();
  // Ends heartbeats for good, e.g. before an exit handler sends on the channel. Idempotent;
  // callable from any thread.
  void stop();
  std::uint64_t sent() const;
  // When the latest heartbeat went out; nullopt before the first.
  std::optional<std::chrono::steady_clock::time_point> last_sent() const;

 private:
  void run();
  void set_busy(bool busy);
  Channel& channel_;
  Milliseconds interval_;
  mutable std::mutex mutex_;
  std::condition_variable wake_;
  bool busy_ = false;
  bool stopping_ = false;
  std::chrono::steady_clock::time_point busy_since_;  // start of busy, or the last heartbeat
  std::uint64_t sent_ = 0;
  std::optional<std::chrono::steady_clock::time_point> last_sent_;
  std::thread thread_;
};

// Whether a numeric address is a loopback one (127.0.0.0/8, ::1): only this host can reach it.
// Names and malformed addresses are not.
bool is_loopback_address(const std::string& numeric_address);

class Listener {
 public:
  // Listens on address (numeric IPv4 or IPv6; 127.0.0.1 keeps the server private to this host)
  // and port (0: the operating system chooses, see port()). SO_REUSEADDR is set, so a restarted
  // server can reuse its port at once. Throws fsi::Error naming address:port and the remedy.
  Listener(const std::string& address, std::uint16_t port, const ChannelOptions& options = {});
  Listener(Listener&&) noexcept;
  Listener& operator=(Listener&&) noexcept;
  ~Listener();

  std::uint16_t port() const;
  std::string address() const;
  // Waits for one client; the channel gets the listener's options. No timeout waits for ever.
  Channel accept(std::optional<Milliseconds> timeout);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace fsi::protocol
