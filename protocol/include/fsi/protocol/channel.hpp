#pragma once
// A framed, checked message connection over TCP (Boost.Asio behind a pimpl). Every receive can
// carry a timeout; a closed connection, a timeout or a malformed frame throws ProtocolError that
// names the fault and what was being waited for.

#include <chrono>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <variant>

#include "fsi/protocol/frame.hpp"
#include "fsi/protocol/messages.hpp"

namespace fsi::protocol {

using Milliseconds = std::chrono::milliseconds;

struct ChannelOptions {
  std::uint16_t major = kMajorVersion;  // version written into sent headers (tests fake others)
  std::uint16_t minor = kMinorVersion;
  std::size_t max_payload = kDefaultMaxPayload;
};

class Channel {
 public:
  // Connects to host:port, retrying with back-off (50 ms doubling to 1 s) until the server
  // listens or give_up_after has passed.
  static Channel connect(const std::string& host, std::uint16_t port, Milliseconds give_up_after,
                         const ChannelOptions& options = {});

  Channel(Channel&&) noexcept;
  Channel& operator=(Channel&&) noexcept;
  ~Channel();

  void send(MessageType type, std::span<const std::byte> payload);
  template <class T>
  void send(const T& message) {
    const auto payload = encode(message);
    send(T::kType, payload);
  }

  // Receives one complete, CRC-checked frame. timeout: none waits forever.
  Frame receive(std::optional<Milliseconds> timeout, const std::string& waiting_for = "a message");
  Message receive_message(std::optional<Milliseconds> timeout,
                          const std::string& waiting_for = "a message");
  // Receives a message of type T; an Error message from the peer or any other message throws.
  template <class T>
  T expect(std::optional<Milliseconds> timeout) {
    Message message = receive_message(timeout, name(T::kType));
    if (auto* wanted = std::get_if<T>(&message)) return std::move(*wanted);
    throw_unexpected(name(T::kType), message);
  }

  std::string peer_description() const;
  const ChannelOptions& options() const;
  // Version the peer wrote into its last received header.
  std::uint16_t peer_major() const;
  std::uint16_t peer_minor() const;
  void close();

 private:
  friend class Listener;
  struct Impl;
  explicit Channel(std::unique_ptr<Impl> impl);
  [[noreturn]] void throw_unexpected(const std::string& expected, const Message& got) const;
  std::unique_ptr<Impl> impl_;
};

class Listener {
 public:
  // port 0: the operating system chooses (see port()).
  Listener(const std::string& address, std::uint16_t port, const ChannelOptions& options = {});
  Listener(Listener&&) noexcept;
  ~Listener();

  std::uint16_t port() const;
  std::string address() const;
  Channel accept(std::optional<Milliseconds> timeout);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace fsi::protocol
