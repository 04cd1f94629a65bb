// Boost.Asio 1.74 with GCC 12 in C++20 needs <utility> before <boost/asio.hpp> (ARCHITECTURE §12).
#include <utility>
// clang-format off
#include <boost/asio.hpp>
// clang-format on

#include <array>
#include <thread>
#include <vector>

#include "fsi/protocol/channel.hpp"

namespace fsi::protocol {
namespace asio = boost::asio;
using tcp = asio::ip::tcp;

namespace {

std::string endpoint_text(const tcp::endpoint& endpoint) {
  const auto address = endpoint.address();
  return (address.is_v6() ? "[" + address.to_string() + "]" : address.to_string()) + ":" +
         std::to_string(endpoint.port());
}

std::string seconds_text(Milliseconds duration) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g s", static_cast<double>(duration.count()) / 1000.0);
  return text;
}

// Runs the context until the operation flagged by `done` finishes or the timeout passes; on a
// timeout the socket's operations are cancelled. Returns false on timeout.
template <class Cancel>
bool run_until(asio::io_context& context, const bool& done, std::optional<Milliseconds> timeout,
               Cancel&& cancel) {
  context.restart();
  if (!timeout) {
    while (!done && context.run_one() > 0) {
    }
    return done;
  }
  const auto deadline = std::chrono::steady_clock::now() + *timeout;
  while (!done) {
    if (context.run_one_until(deadline) == 0 && !done) {
      if (std::chrono::steady_clock::now() >= deadline) break;
    }
  }
  if (done) return true;
  cancel();
  context.restart();
  while (!done && context.run_one() > 0) {
  }
  return false;
}

}  // namespace

struct Channel::Impl {
  asio::io_context context;
  tcp::socket socket{context};
  ChannelOptions options;
  std::string peer;
  std::uint16_t peer_major = 0;
  std::uint16_t peer_minor = 0;
  std::array<std::byte, kHeaderSize> header_bytes{};

  void configure() {
    socket.set_option(tcp::no_delay(true));
    boost::system::error_code ignored;
    peer = endpoint_text(socket.remote_endpoint(ignored));
  }

  // Reads exactly buffer.size() bytes or throws.
  void read_exactly(std::span<std::byte> buffer, std::optional<Milliseconds> timeout,
                    const std::string& waiting_for, const char* part) {
    bool done = false;
    boost::system::error_code error;
    std::size_t got = 0;
    asio::async_read(socket, asio::buffer(buffer.data(), buffer.size()),
                     [&](const boost::system::error_code& e, std::size_t n) {
                       error = e;
                       got = n;
                       done = true;
                     });
    const bool in_time = run_until(context, done, timeout, [&] {
      boost::system::error_code ignored;
      socket.cancel(ignored);
    });
    if (!in_time) {
      throw ProtocolError("no " + std::string(part) + " from " + peer + " within " +
                              seconds_text(*timeout) + " while waiting for " + waiting_for,
                          "connection to " + peer,
                          "the peer hangs or is overloaded; check it, or raise the timeout");
    }
    if (error) {
      const bool closed = error == asio::error::eof || error == asio::error::connection_reset ||
                          error == asio::error::broken_pipe;
      if (closed) {
        throw ProtocolError(
            "connection closed by peer " + peer + " while waiting for " + waiting_for +
                (got > 0 ? " (after " + std::to_string(got) + " bytes of a " + part + ")"
                         : std::string()),
            "connection to " + peer, "the other program ended; see its output for the reason");
      }
      throw ProtocolError("receive from " + peer + " failed while waiting for " + waiting_for +
                              ": " + error.message(),
                          "connection to " + peer, "check the network and the peer");
    }
  }
};

Channel::Channel(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
Channel::Channel(Channel&&) noexcept = default;
Channel& Channel::operator=(Channel&&) noexcept = default;
Channel::~Channel() = default;

Channel Channel::connect(const std::string& host, std::uint16_t port, Milliseconds give_up_after,
                         const ChannelOptions& options) {
  auto impl = std::make_unique<Impl>();
  impl->options = options;
  const auto deadline = std::chrono::steady_clock::now() + give_up_after;
  Milliseconds pause{50};
  std::string last_problem;
  while (true) {
    boost::system::error_code error;
    tcp::resolver resolver(impl->context);
    const auto endpoints = resolver.resolve(host, std::to_string(port), error);
    if (!error) {
      bool done = false;
      asio::async_connect(impl->socket, endpoints,
                          [&](const boost::system::error_code& e, const tcp::endpoint&) {
                            error = e;
                            done = true;
                          });
      const auto left =
          std::chrono::duration_cast<Milliseconds>(deadline - std::chrono::steady_clock::now());
      const bool in_time = run_until(impl->context, done, std::max(left, Milliseconds{1}), [&] {
        boost::system::error_code ignored;
        impl->socket.close(ignored);
      });
      if (in_time && !error) {
        impl->configure();
        return Channel(std::move(impl));
      }
      last_problem = in_time ? error.message() : "connection attempt timed out";
      boost::system::error_code ignored;
      impl->socket.close(ignored);
    } else {
      last_problem = "cannot resolve host: " + error.message();
    }
    if (std::chrono::steady_clock::now() + pause > deadline) break;
    std::this_thread::sleep_for(pause);
    pause = std::min(pause * 2, Milliseconds{1000});
  }
  throw ProtocolError("cannot connect to fsi-server at " + host + ":" + std::to_string(port) +
                          " within " + seconds_text(give_up_after) + " (" + last_problem + ")",
                      "--server " + host + ":" + std::to_string(port),
                      "start fsi-server first (it prints its port), check host, port and "
                      "firewall, or raise --connect-timeout");
}

void Channel::send(MessageType type, std::span<const std::byte> payload) {
  const auto header = encode_header(type, payload, impl_->options.major, impl_->options.minor);
  const std::array<asio::const_buffer, 2> buffers{asio::buffer(header.data(), header.size()),
                                                  asio::buffer(payload.data(), payload.size())};
  boost::system::error_code error;
  asio::write(impl_->socket, buffers, error);
  if (error) {
    throw ProtocolError("cannot send " + name(type) + " to " + impl_->peer + ": " + error.message(),
                        "connection to " + impl_->peer,
                        "the other program ended; see its output for the reason");
  }
}

Frame Channel::receive(std::optional<Milliseconds> timeout, const std::string& waiting_for) {
  Impl& impl = *impl_;
  const auto started = std::chrono::steady_clock::now();
  impl.read_exactly(impl.header_bytes, timeout, waiting_for, "frame header");
  Frame frame;
  frame.header = decode_header(impl.header_bytes, impl.options.max_payload, impl.options.major);
  impl.peer_major = frame.header.major;
  impl.peer_minor = frame.header.minor;
  frame.payload.resize(frame.header.payload_length);
  std::optional<Milliseconds> left = timeout;
  if (timeout) {
    const auto spent =
        std::chrono::duration_cast<Milliseconds>(std::chrono::steady_clock::now() - started);
    left = std::max(*timeout - spent, Milliseconds{1});
  }
  impl.read_exactly(frame.payload, left, waiting_for,
                    (name(frame.header.type) + " payload").c_str());
  verify_crc(impl.header_bytes, frame.header, frame.payload);
  return frame;
}

Message Channel::receive_message(std::optional<Milliseconds> timeout,
                                 const std::string& waiting_for) {
  Frame frame = receive(timeout, waiting_for);
  return decode(frame.header.type, frame.payload);
}

void Channel::throw_unexpected(const std::string& expected, const Message& got) const {
  if (const auto* error = std::get_if<ErrorMessage>(&got)) {
    throw ProtocolError("peer reported: " + error->text,
                        "connection to " + impl_->peer + " (while waiting for " + expected + ")");
  }
  throw ProtocolError("expected " + expected + " but received " + name(type_of(got)),
                      "connection to " + impl_->peer,
                      "use matching fsi-server and fsi-client releases");
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
std::uint16_t Channel::peer_minor() const {
  return impl_->peer_minor;
}

void Channel::close() {
  boost::system::error_code ignored;
  impl_->socket.shutdown(tcp::socket::shutdown_both, ignored);
  impl_->socket.close(ignored);
}

struct Listener::Impl {
  asio::io_context context;
  tcp::acceptor acceptor{context};
  ChannelOptions options;
  std::string address;
};

Listener::Listener(const std::string& address, std::uint16_t port, const ChannelOptions& options)
    : impl_(std::make_unique<Impl>()) {
  impl_->options = options;
  impl_->address = address;
  boost::system::error_code error;
  const auto ip = asio::ip::make_address(address, error);
  if (error) {
    throw fsi::Error("'" + address + "' is not an IP address", "--listen",
                     "give an address such as 127.0.0.1 or 0.0.0.0");
  }
  const tcp::endpoint endpoint(ip, port);
  impl_->acceptor.open(endpoint.protocol(), error);
  if (!error) impl_->acceptor.set_option(tcp::acceptor::reuse_address(true), error);
  if (!error) impl_->acceptor.bind(endpoint, error);
  if (!error) impl_->acceptor.listen(asio::socket_base::max_listen_connections, error);
  if (error) {
    throw fsi::Error(
        "cannot listen on " + address + ":" + std::to_string(port) + ": " + error.message(),
        "--listen/--port",
        error == asio::error::address_in_use
            ? "another program uses the port; choose another with --port (0 lets "
              "the system choose)"
            : "choose an address of this host and a free port");
  }
}

Listener::Listener(Listener&&) noexcept = default;
Listener::~Listener() = default;

std::uint16_t Listener::port() const {
  return impl_->acceptor.local_endpoint().port();
}
std::string Listener::address() const {
  return impl_->address;
}

Channel Listener::accept(std::optional<Milliseconds> timeout) {
  auto impl = std::make_unique<Channel::Impl>();
  impl->options = impl_->options;
  bool done = false;
  boost::system::error_code error;
  // The channel's socket lives in its own context; accept into a socket of the listener's context
  // and move the native handle over.
  tcp::socket socket(impl_->context);
  impl_->acceptor.async_accept(socket, [&](const boost::system::error_code& e) {
    error = e;
    done = true;
  });
  const bool in_time = run_until(impl_->context, done, timeout, [&] {
    boost::system::error_code ignored;
    impl_->acceptor.cancel(ignored);
  });
  if (!in_time) {
    throw ProtocolError("no fsi-client connected within " + seconds_text(*timeout),
                        "listening on " + impl_->address + ":" + std::to_string(port()),
                        "start the client (mpirun -np N fsi-client --server HOST:" +
                            std::to_string(port()) + ") or raise --accept-timeout");
  }
  if (error) {
    throw ProtocolError("accepting a connection failed: " + error.message(),
                        "listening on " + impl_->address + ":" + std::to_string(port()));
  }
  const auto protocol = socket.local_endpoint().protocol();
  impl->socket.assign(protocol, socket.release());
  impl->configure();
  return Channel(std::move(impl));
}

}  // namespace fsi::protocol
