// Token files, HMAC-SHA256 tags and the opening handshake of both sides (docs/protocol.md §5,
// "Authentication", and §6).
#include "fsi/protocol/auth.hpp"

#include <openssl/crypto.h>
#include <openssl/err.h>
#include <openssl/evp.h>
#include <openssl/hmac.h>
#include <openssl/rand.h>
#include <sys/stat.h>

#include <algorithm>
#include <cctype>
#include <cstring>
#include <fstream>
#include <iterator>
#include <string_view>
#include <variant>

#include "fsi/common/error.hpp"

namespace fsi::protocol {
namespace {

constexpr std::size_t kMaximumTokenBytes = 4096;
constexpr std::string_view kClientLabel = "fsi-client";
constexpr std::string_view kServerLabel = "fsi-server";

std::string openssl_problem() {
  const unsigned long code = ERR_get_error();
  if (code == 0) return "no detail from OpenSSL";
  char text[256];
  ERR_error_string_n(code, text, sizeof text);
  return text;
}

AuthBytes tag(const Token& token, std::string_view label, const AuthBytes& first,
              const AuthBytes& second) {
  std::vector<std::uint8_t> message;
  message.reserve(label.size() + first.size() + second.size());
  message.insert(message.end(), label.begin(), label.end());
  message.insert(message.end(), first.begin(), first.end());
  message.insert(message.end(), second.begin(), second.end());
  return hmac_sha256(token.secret(), message);
}

// Sends the peer an Error AuthenticationFailed (if the connection still works), closes the
// channel, and throws the same text locally.
[[noreturn]] void refuse(Channel& channel, ErrorCode code, const std::string& fault,
                         const std::string& fix) {
  const std::string where = "handshake with " + channel.peer_description();
  try {
    channel.send(ErrorMessage{code, fault + "; how to fix: " + fix});
  } catch (const std::exception&) {
    // The peer may be gone already; the local error says everything.
  }
  channel.close();
  throw fsi::Error(fault, where, fix);
}

[[noreturn]] void unexpected(Channel& channel, const char* expected, const Message& received) {
  const std::string where =
      "connection to " + channel.peer_description() + ", while waiting for " + expected;
  if (const auto* error = std::get_if<ErrorMessage>(&received)) {
    throw PeerReportedError(error->code, error->text, where);
  }
  throw ProtocolError(
      std::string("expected ") + expected + " but received " + name(type_of(received)), where,
      "use matching releases of fsi-server and fsi-client");
}

}  // namespace

Token::Token(std::vector<std::uint8_t> secret, std::string file)
    : secret_(std::move(secret)), file_(std::move(file)) {}
Token::Token(const Token& other) = default;
Token& Token::operator=(const Token& other) {
  if (this != &other) {
    OPENSSL_cleanse(secret_.data(), secret_.size());
    secret_ = other.secret_;
    file_ = other.file_;
  }
  return *this;
}
Token::~Token() {
  OPENSSL_cleanse(secret_.data(), secret_.size());
}

Token read_token_file(const std::string& path, const std::string& option) {
  const std::string where = option + " " + path;
  struct stat status {};
  if (::stat(path.c_str(), &status) != 0) {
    throw fsi::Error("cannot read token file " + path + ": " + std::strerror(errno), where,
                     "create it with `openssl rand -hex 32 > " + path + " && chmod 600 " + path +
                         "` and give the same file (or a copy) to fsi-server and fsi-client");
  }
  if (!S_ISREG(status.st_mode)) {
    throw fsi::Error("token file " + path + " is not a regular file", where,
                     "name a file that holds the token");
  }
  if ((status.st_mode & (S_IRWXG | S_IRWXO)) != 0) {
    char mode[8];
    std::snprintf(mode, sizeof mode, "%03o", static_cast<unsigned>(status.st_mode & 0777));
    throw fsi::Error("token file " + path + " is accessible to other users (mode " + mode +
                         "); a token others can read authenticates nobody",
                     where, "run `chmod 600 " + path + "`");
  }
  std::ifstream in(path, std::ios::binary);
  std::vector<std::uint8_t> secret((std::istreambuf_iterator<char>(in)),
                                   std::istreambuf_iterator<char>());
  if (!in.eof() && in.fail()) {
    throw fsi::Error("cannot read token file " + path, where, "check the file's permissions");
  }
  while (!secret.empty() && std::isspace(secret.back()))
    secret.pop_back();
  if (secret.size() < kMinimumTokenBytes || secret.size() > kMaximumTokenBytes) {
    const std::size_t size = secret.size();
    OPENSSL_cleanse(secret.data(), secret.size());
    throw fsi::Error("token file " + path + " holds " + std::to_string(size) +
                         " bytes (without trailing white space); a token has " +
                         std::to_string(kMinimumTokenBytes) + " to " +
                         std::to_string(kMaximumTokenBytes) + " bytes",
                     where, "write a fresh token with `openssl rand -hex 32 > " + path + "`");
  }
  return Token(std::move(secret), path);
}

AuthBytes hmac_sha256(std::span<const std::uint8_t> key, std::span<const std::uint8_t> message) {
  AuthBytes digest{};
  unsigned int length = 0;
  // An empty key is legal for HMAC; OpenSSL wants a non-null pointer for it.
  static const std::uint8_t kEmpty = 0;
  const std::uint8_t* key_data = key.empty() ? &kEmpty : key.data();
  if (HMAC(EVP_sha256(), key_data, static_cast<int>(key.size()), message.data(), message.size(),
           digest.data(), &length) == nullptr ||
      length != digest.size()) {
    throw fsi::Error("HMAC-SHA256 failed: " + openssl_problem(), "OpenSSL",
                     "check the OpenSSL installation (libssl3)");
  }
  return digest;
}

AuthBytes random_nonce() {
  AuthBytes nonce{};
  if (RAND_bytes(nonce.data(), static_cast<int>(nonce.size())) != 1) {
    throw fsi::Error("the system's random number generator failed: " + openssl_problem(),
                     "OpenSSL RAND_bytes", "check that /dev/urandom or getrandom() works");
  }
  return nonce;
}

bool tags_equal(const AuthBytes& a, const AuthBytes& b) {
  return CRYPTO_memcmp(a.data(), b.data(), a.size()) == 0;
}

AuthBytes client_tag(const Token& token, const AuthBytes& server_nonce,
                     const AuthBytes& client_nonce) {
  return tag(token, kClientLabel, server_nonce, client_nonce);
}

AuthBytes server_tag(const Token& token, const AuthBytes& client_nonce,
                     const AuthBytes& server_nonce) {
  return tag(token, kServerLabel, client_nonce, server_nonce);
}

ServerHandshakeResult accept_client(Channel& channel, const ServerHandshake& handshake) {
  ServerHandshakeResult result;
  // The Hello layout is the same in every protocol version, so a mismatch is always readable.
  result.hello = channel.expect<Hello>(handshake.timeout);
  const std::string client =
      "fsi-client " + result.hello.software_version + " at " + channel.peer_description();
  const VersionCheck version =
      check_peer_version(Role::Server, channel.peer_major(), channel.peer_minor());
  if (!version.compatible) {
    refuse(channel, ErrorCode::VersionMismatch, "refused " + client + ": " + version.message,
           "use matching fsi-server and fsi-client releases");
  }
  result.agreed_minor = version.agreed_minor;
  const std::uint32_t offered = kCapabilityHeartbeat | handshake.session_capabilities |
                                (handshake.token ? kCapabilityAuthentication : 0u);
  result.capabilities = result.hello.capabilities & offered;

  if (handshake.token) {
    const Token& token = *handshake.token;
    if ((result.hello.capabilities & kCapabilityAuthentication) == 0) {
      refuse(channel, ErrorCode::AuthenticationFailed,
             "refused " + client +
                 ": it presented no token (started without --token-file, or a release older "
                 "than protocol 1.1), and this fsi-server requires one (--token-file " +
                 token.file() + ")",
             "start fsi-client with --token-file naming a copy of the server's token file");
    }
    AuthChallenge challenge;
    challenge.server_nonce = random_nonce();
    channel.send(challenge);
    const Message answer = channel.receive_message(handshake.timeout, "AuthResponse");
    const auto* response = std::get_if<AuthResponse>(&answer);
    if (response == nullptr) unexpected(channel, "AuthResponse", answer);
    const AuthBytes expected = client_tag(token, challenge.server_nonce, response->client_nonce);
    if (!tags_equal(expected, response->client_tag)) {
      refuse(channel, ErrorCode::AuthenticationFailed,
             "refused " + client +
                 ": authentication failed, its token differs from this "
                 "fsi-server's (--token-file " +
                 token.file() + ")",
             "give fsi-server and fsi-client the same token file (or identical copies)");
    }
    channel.send(AuthProof{server_tag(token, response->client_nonce, challenge.server_nonce)});
  }

  Welcome welcome;
  welcome.accepted_minor = result.agreed_minor;
  welcome.capabilities = result.capabilities;
  welcome.software_version = handshake.software_version;
  welcome.run_name = handshake.run_name;
  channel.send(welcome);
  return result;
}

ClientHandshakeResult open_session(Channel& channel, const ClientHandshake& handshake) {
  Hello hello = handshake.hello;
  hello.capabilities = kCapabilityHeartbeat | handshake.session_capabilities |
                       (handshake.token ? kCapabilityAuthentication : 0u);
  channel.send(hello);
  const std::string server = "fsi-server at " + channel.peer_description();
  Message answer = channel.receive_message(handshake.timeout, "the server's answer to Hello");

  if (handshake.token) {
    const Token& token = *handshake.token;
    if (std::holds_alternative<Welcome>(answer)) {
      refuse(channel, ErrorCode::AuthenticationFailed,
             "refused " + server +
                 ": it did not authenticate itself (it runs without --token-file, or is a "
                 "release older than protocol 1.1), and this fsi-client has a token "
                 "(--token-file " +
                 token.file() + ")",
             "start fsi-server with --token-file naming a copy of the same token file");
    }
    const auto* challenge = std::get_if<AuthChallenge>(&answer);
    if (challenge == nullptr) unexpected(channel, "AuthChallenge", answer);
    AuthResponse response;
    response.client_nonce = random_nonce();
    response.client_tag = client_tag(token, challenge->server_nonce, response.client_nonce);
    const AuthBytes server_nonce = challenge->server_nonce;
    channel.send(response);
    answer = channel.receive_message(handshake.timeout, "AuthProof");
    const auto* proof = std::get_if<AuthProof>(&answer);
    if (proof == nullptr) unexpected(channel, "AuthProof", answer);
    if (!tags_equal(proof->server_tag, server_tag(token, response.client_nonce, server_nonce))) {
      refuse(channel, ErrorCode::AuthenticationFailed,
             "refused " + server +
                 ": authentication failed, it does not hold this fsi-client's token "
                 "(--token-file " +
                 token.file() + "); it may not be the server you meant",
             "check the server's address, and give fsi-server and fsi-client the same token "
             "file");
    }
    answer = channel.receive_message(handshake.timeout, "Welcome");
  }
  auto* welcome = std::get_if<Welcome>(&answer);
  if (welcome == nullptr) unexpected(channel, "Welcome", answer);
  ClientHandshakeResult result;
  result.welcome = std::move(*welcome);
  result.capabilities = result.welcome.capabilities & hello.capabilities;
  if (handshake.token && (result.capabilities & kCapabilityAuthentication) == 0) {
    refuse(channel, ErrorCode::AuthenticationFailed,
           "refused " + server + ": its Welcome does not confirm authentication",
           "use matching releases of fsi-server and fsi-client");
  }
  return result;
}

}  // namespace fsi::protocol
