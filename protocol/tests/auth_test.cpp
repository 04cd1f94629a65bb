#include <gtest/gtest.h>

#include <sys/stat.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <future>
#include <optional>
#include <string>
#include <vector>

#include "error_text.hpp"
#include "fsi/protocol/auth.hpp"

namespace fsi::protocol {
namespace {

using namespace test;

using namespace std::chrono_literals;
namespace fs = std::filesystem;

std::string hex(const AuthBytes& bytes) {
  std::string text;
  char digit[3];
  for (std::uint8_t byte : bytes) {
    std::snprintf(digit, sizeof digit, "%02x", byte);
    text += digit;
  }
  return text;
}

std::vector<std::uint8_t> bytes_of(const std::string& text) {
  return {text.begin(), text.end()};
}

Token token_of(const std::string& secret) {
  return Token(bytes_of(secret), "test.token");
}

// RFC 4231, section 4: test cases 1, 2 and 6 (key longer than the SHA-256 block).
TEST(ProtocolAuth, HmacSha256MatchesRfc4231) {
  EXPECT_EQ(hex(hmac_sha256(std::vector<std::uint8_t>(20, 0x0b), bytes_of("Hi There"))),
            "b0344c61d8db38535ca8afceaf0bf12b881dc200c9833da726e9376c2e32cff7");
  EXPECT_EQ(hex(hmac_sha256(bytes_of("Jefe"), bytes_of("what do ya want for nothing?"))),
            "5bdcc146bf60754e6a042426089575c75a003f089d2739839dec58b964ec3843");
  EXPECT_EQ(hex(hmac_sha256(std::vector<std::uint8_t>(131, 0xaa),
                            bytes_of("Test Using Larger Than Block-Size Key - Hash Key First"))),
            "60e431591ee0b67f0d8a26aacbf5b77f8e0bc6213728c5140546040f0ee37f54");
}

TEST(ProtocolAuth, TagsFollowTheSpecAndDifferByRole) {
  const Token token = token_of("0123456789abcdef0123");
  AuthBytes a{}, b{};
  a.fill(0x11);
  b.fill(0x22);
  // docs/protocol.md: HMAC(token, "fsi-client" | server nonce | client nonce).
  std::vector<std::uint8_t> message = bytes_of("fsi-client");
  message.insert(message.end(), a.begin(), a.end());
  message.insert(message.end(), b.begin(), b.end());
  EXPECT_EQ(client_tag(token, a, b), hmac_sha256(token.secret(), message));
  // A tag cannot be reflected: the server's tag over the same nonces differs.
  EXPECT_NE(client_tag(token, a, b), server_tag(token, a, b));
  EXPECT_NE(client_tag(token, a, b), client_tag(token, b, a));
  EXPECT_NE(client_tag(token, a, b), client_tag(token_of("0123456789abcdef0124"), a, b));
}

TEST(ProtocolAuth, NoncesAreFreshAndTagsCompare) {
  const AuthBytes first = random_nonce();
  const AuthBytes second = random_nonce();
  EXPECT_NE(first, second);
  EXPECT_NE(first, AuthBytes{});
  EXPECT_TRUE(tags_equal(first, first));
  AuthBytes changed = first;
  changed[31] ^= 1;
  EXPECT_FALSE(tags_equal(first, changed));
  changed = first;
  changed[0] ^= 0x80;
  EXPECT_FALSE(tags_equal(first, changed));
}

class TokenFile : public ::testing::Test {
 protected:
  void SetUp() override {
    directory_ = fs::temp_directory_path() /
                 ("fsi_token_test_" + std::to_string(::getpid()) + "_" +
                  ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(directory_);
  }
  void TearDown() override { fs::remove_all(directory_); }
  std::string write(const std::string& content, unsigned mode) {
    const std::string path = (directory_ / "token").string();
    std::ofstream(path, std::ios::binary) << content;
    ::chmod(path.c_str(), mode);
    return path;
  }
  static std::string error_of(const std::string& path) {
    try {
      read_token_file(path);
    } catch (const fsi::Error& error) {
      return error.what();
    }
    return "(accepted)";
  }
  fs::path directory_;
};

TEST_F(TokenFile, TrailingWhiteSpaceIsNotPartOfTheToken) {
  const std::string path = write("0123456789abcdef0123\n", 0600);
  const Token token = read_token_file(path);
  EXPECT_EQ(std::vector<std::uint8_t>(token.secret().begin(), token.secret().end()),
            bytes_of("0123456789abcdef0123"));
  EXPECT_EQ(token.file(), path);
}

TEST_F(TokenFile, FilesOthersCanReadAreRefused) {
  const std::string text = error_of(write("0123456789abcdef0123\n", 0644));
  EXPECT_TRUE(contains(text, "accessible to other users (mode 644)")) << text;
  EXPECT_TRUE(contains(text, "chmod 600")) << text;
}

TEST_F(TokenFile, ShortAndMissingTokensAreRefused) {
  std::string text = error_of(write("short\n", 0600));
  EXPECT_TRUE(contains(text, "holds 5 bytes")) << text;
  EXPECT_TRUE(contains(text, "openssl rand -hex 32")) << text;
  text = error_of((directory_ / "absent").string());
  EXPECT_TRUE(contains(text, "cannot read token file")) << text;
  EXPECT_TRUE(contains(text, "--token-file")) << text;
}

struct Outcome {
  std::string server;  // error text, or "ok <capabilities>"
  std::string client;
};

ChannelOptions quick_close() {
  ChannelOptions options;
  options.close_linger = 200ms;
  return options;
}

// The client's opening against the listener's port, in the background: "ok <capabilities> <run
// name>" or the error it ended with.
std::future<std::string> client_opening(std::uint16_t port, std::optional<Token> token,
                                        std::uint32_t session_capabilities = kNoCapabilities) {
  return std::async(
      std::launch::async, [port, token = std::move(token), session_capabilities]() -> std::string {
        Channel channel = Channel::connect("127.0.0.1", port, 5s, quick_close());
        ClientHandshake handshake;
        handshake.token = token;
        handshake.hello = Hello{"test", "host", 1, 0};
        handshake.timeout = 5s;
        handshake.session_capabilities = session_capabilities;
        try {
          const auto result = open_session(channel, handshake);
          channel.close();
          return "ok " + std::to_string(result.capabilities) + " " + result.welcome.run_name;
        } catch (const fsi::Error& error) {
          return error.what();
        }
      });
}

// Runs both openings over loopback, each side with its own optional token.
Outcome handshake(std::optional<Token> server_token, std::optional<Token> client_token,
                  std::uint32_t server_session = kNoCapabilities,
                  std::uint32_t client_session = kNoCapabilities) {
  Listener listener("127.0.0.1", 0, quick_close());
  auto client = client_opening(listener.port(), std::move(client_token), client_session);
  Outcome outcome;
  Channel channel = listener.accept(5s);
  ServerHandshake handshake;
  handshake.token = server_token;
  handshake.software_version = "test";
  handshake.run_name = "run";
  handshake.timeout = 5s;
  handshake.session_capabilities = server_session;
  try {
    const auto result = accept_client(channel, handshake);
    outcome.server = "ok " + std::to_string(result.capabilities);
    // A client that refuses the Welcome tells why.
    try {
      channel.expect<Ready>(2s);
    } catch (const fsi::Error& error) {
      outcome.server += std::string(" / ") + error.what();
    }
    channel.close();
  } catch (const fsi::Error& error) {
    outcome.server = error.what();
  }
  outcome.client = client.get();
  return outcome;
}

TEST(ProtocolAuthHandshake, SameTokenAuthenticatesBothSides) {
  const Outcome outcome =
      handshake(token_of("the same secret token"), token_of("the same secret token"));
  const std::string both = std::to_string(kCapabilityAuthentication | kCapabilityHeartbeat);
  EXPECT_TRUE(contains(outcome.server, "ok " + both)) << outcome.server;
  EXPECT_EQ(outcome.client, "ok " + both + " run");
}

TEST(ProtocolAuthHandshake, NoTokenOnEitherSideAgreesOnHeartbeatOnly) {
  const Outcome outcome = handshake(std::nullopt, std::nullopt);
  EXPECT_TRUE(contains(outcome.server, "ok " + std::to_string(kCapabilityHeartbeat)))
      << outcome.server;
  EXPECT_EQ(outcome.client, "ok " + std::to_string(kCapabilityHeartbeat) + " run");
}

TEST(ProtocolAuthHandshake, SessionCapabilitiesAreAgreedOnlyWhenBothSidesOfferThem) {
  const std::string with_settling = std::to_string(kCapabilityHeartbeat | kCapabilitySettling);
  const Outcome both =
      handshake(std::nullopt, std::nullopt, kCapabilitySettling, kCapabilitySettling);
  EXPECT_TRUE(contains(both.server, "ok " + with_settling)) << both.server;
  EXPECT_EQ(both.client, "ok " + with_settling + " run");
  // A peer of protocol 1.1 knows no settling: the other side then does without it.
  const std::string heartbeat_only = std::to_string(kCapabilityHeartbeat);
  const Outcome old_client = handshake(std::nullopt, std::nullopt, kCapabilitySettling);
  EXPECT_TRUE(contains(old_client.server, "ok " + heartbeat_only)) << old_client.server;
  EXPECT_EQ(old_client.client, "ok " + heartbeat_only + " run");
  const Outcome old_server =
      handshake(std::nullopt, std::nullopt, kNoCapabilities, kCapabilitySettling);
  EXPECT_TRUE(contains(old_server.server, "ok " + heartbeat_only)) << old_server.server;
  EXPECT_EQ(old_server.client, "ok " + heartbeat_only + " run");
}

TEST(ProtocolAuthHandshake, ProbesAreAgreedOnlyWhenBothSidesOfferThem) {
  const std::uint32_t current = kCapabilitySettling | kCapabilityProbes;
  const Outcome both = handshake(std::nullopt, std::nullopt, current, current);
  EXPECT_EQ(both.client, "ok " + std::to_string(kCapabilityHeartbeat | current) + " run");
  // A client of protocol 1.2 offers settling only: the session has no probes, and the server
  // sees which bit is missing (TcpFluidSide then refuses a scene with probes by name).
  const std::string without_probes = std::to_string(kCapabilityHeartbeat | kCapabilitySettling);
  const Outcome old_client = handshake(std::nullopt, std::nullopt, current, kCapabilitySettling);
  EXPECT_TRUE(contains(old_client.server, "ok " + without_probes)) << old_client.server;
  EXPECT_EQ(old_client.client, "ok " + without_probes + " run");
}

TEST(ProtocolAuthHandshake, WrongClientTokenIsRefusedByTheServer) {
  const Outcome outcome =
      handshake(token_of("the server's secret token"), token_of("another secret token!"));
  EXPECT_TRUE(contains(outcome.server, "authentication failed, its token differs"))
      << outcome.server;
  EXPECT_TRUE(contains(outcome.client, "[AuthenticationFailed]")) << outcome.client;
  EXPECT_TRUE(contains(outcome.client, "token differs")) << outcome.client;
}

TEST(ProtocolAuthHandshake, ClientWithoutTokenIsRefusedByAServerWithOne) {
  const Outcome outcome = handshake(token_of("the server's secret token"), std::nullopt);
  EXPECT_TRUE(contains(outcome.server, "presented no token")) << outcome.server;
  EXPECT_TRUE(contains(outcome.client, "[AuthenticationFailed]")) << outcome.client;
}

TEST(ProtocolAuthHandshake, ServerWithoutTokenIsRefusedByAClientWithOne) {
  const Outcome outcome = handshake(std::nullopt, token_of("the client's secret token"));
  EXPECT_TRUE(contains(outcome.client, "did not authenticate itself")) << outcome.client;
  EXPECT_TRUE(contains(outcome.server, "[AuthenticationFailed]")) << outcome.server;
}

// An impostor that does not know the token skips the check of the client's tag and answers with
// a proof made from its own guess: the client must refuse it before any Welcome or set-up.
TEST(ProtocolAuthHandshake, ServerWithWrongTokenIsRefusedByTheClient) {
  Listener listener("127.0.0.1", 0, quick_close());
  auto client = client_opening(listener.port(), token_of("the client's secret token"));
  Channel channel = listener.accept(5s);
  channel.expect<Hello>(5s);
  AuthChallenge challenge{random_nonce()};
  channel.send(challenge);
  const auto response = channel.expect<AuthResponse>(5s);
  const Token guess = token_of("an impostor's guess at it");
  channel.send(AuthProof{server_tag(guess, response.client_nonce, challenge.server_nonce)});
  channel.send(Welcome{1, kCapabilityAuthentication | kCapabilityHeartbeat, "impostor", "run"});
  std::string at_server;
  try {
    channel.expect<Ready>(5s);
  } catch (const PeerReportedError& error) {
    at_server = error.what();
  }
  channel.close();
  const std::string at_client = client.get();
  EXPECT_TRUE(contains(at_client, "authentication failed, it does not hold")) << at_client;
  EXPECT_TRUE(contains(at_server, "[AuthenticationFailed]")) << at_server;
}

}  // namespace
}  // namespace fsi::protocol
