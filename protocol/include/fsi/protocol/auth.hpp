#pragma once
// Shared-token authentication of both peers (protocol 1.1, docs/protocol.md §5 "Authentication"):
// HMAC-SHA256 challenge-response in both directions with 32-byte nonces from OpenSSL's CSPRNG and
// constant-time tag comparison. OpenSSL stays inside src/auth.cpp.
//
// The handshake functions below run the whole opening of a session (Hello, version check,
// authentication, Welcome) on a connected Channel. A refusal sends the peer an Error and closes
// the channel before throwing, so nothing else can be sent after the Error.

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "fsi/protocol/channel.hpp"
#include "fsi/protocol/messages.hpp"

namespace fsi::protocol {

// The secret of a token file. The bytes are wiped when the object goes away.
class Token {
 public:
  Token(std::vector<std::uint8_t> secret, std::string file);
  Token(const Token& other);
  Token& operator=(const Token& other);
  ~Token();
  std::span<const std::uint8_t> secret() const { return secret_; }
  // The file it came from, for messages (never the secret).
  const std::string& file() const { return file_; }

 private:
  std::vector<std::uint8_t> secret_;
  std::string file_;
};

// Shortest secret accepted, in bytes (after trailing white space is removed).
inline constexpr std::size_t kMinimumTokenBytes = 16;

// Reads a token file: its whole content minus trailing white space (so `openssl rand -hex 32 >
// FILE` works). Throws fsi::Error naming the file and option when it cannot be read, is not a
// regular file, is readable or writable by group or others (fix: chmod 600), is shorter than
// kMinimumTokenBytes or longer than 4096 bytes.
Token read_token_file(const std::string& path, const std::string& option = "--token-file");

// HMAC-SHA256 (RFC 2104 with SHA-256).
AuthBytes hmac_sha256(std::span<const std::uint8_t> key, std::span<const std::uint8_t> message);
// 32 bytes from OpenSSL's CSPRNG (RAND_bytes); throws fsi::Error if it fails.
AuthBytes random_nonce();
// Compares in time independent of where the bytes differ (CRYPTO_memcmp).
bool tags_equal(const AuthBytes& a, const AuthBytes& b);
// The tags of docs/protocol.md: HMAC(token, label | first nonce | second nonce) with the 10-byte
// ASCII labels "fsi-client" and "fsi-server".
AuthBytes client_tag(const Token& token, const AuthBytes& server_nonce,
                     const AuthBytes& client_nonce);
AuthBytes server_tag(const Token& token, const AuthBytes& client_nonce,
                     const AuthBytes& server_nonce);

// The server's opening: receives Hello, checks the version, authenticates when it has a token,
// sends Welcome. Capabilities offered: heartbeat, the session's, and authentication when a token
// is given.
struct ServerHandshake {
  std::optional<Token> token;
  std::string software_version;  // goes into Welcome
  std::string run_name;          // goes into Welcome
  Milliseconds timeout{30000};   // for each message of the client
  // Bits of the session that follows, which the caller implements (kCapabilitySettling).
  std::uint32_t session_capabilities = kNoCapabilities;
};
struct ServerHandshakeResult {
  Hello hello;
  std::uint16_t agreed_minor = 0;
  std::uint32_t capabilities = 0;  // agreed (AND of both)
};
// Refusals (another major, no token or a wrong one) send the client an Error (VersionMismatch,
// AuthenticationFailed), close the channel and throw fsi::Error saying why and how to fix it.
ServerHandshakeResult accept_client(Channel& channel, const ServerHandshake& handshake);

struct ClientHandshake {
  std::optional<Token> token;
  Hello hello;  // capabilities are filled in
  Milliseconds timeout{30000};
  // Bits of the session that follows, which the caller implements (kCapabilitySettling).
  std::uint32_t session_capabilities = kNoCapabilities;
};
struct ClientHandshakeResult {
  Welcome welcome;
  std::uint32_t capabilities = 0;  // agreed, as the server stated in Welcome
};
// The client's opening: sends Hello, and with a token answers the server's challenge and checks
// the server's proof before it accepts Welcome. A server without a token (or of protocol 1.0)
// is refused when this side has one; a wrong proof is refused. Refusals send the server an Error
// AuthenticationFailed, close the channel and throw fsi::Error; an Error from the server throws
// PeerReportedError.
ClientHandshakeResult open_session(Channel& channel, const ClientHandshake& handshake);

}  // namespace fsi::protocol
