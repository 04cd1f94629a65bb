// message_list.hpp is the one list of message types: these tests hold every part derived from it
// (enumerators, names, is_known, decode dispatch, the codec, the fuzzers' table and seed corpus)
// to the list, so that a part that stopped following it fails here.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>
#include <string>
#include <type_traits>
#include <vector>

#include "decoders.hpp"
#include "error_text.hpp"
#include "fsi/protocol/frame.hpp"
#include "fsi/protocol/messages.hpp"

namespace fsi::protocol {
namespace {

using namespace test;

struct Listed {
  MessageType type;
  std::string enumerator;
};

// The list as written, read through the same macro the library expands.
const std::vector<Listed>& listed() {
  static const std::vector<Listed> entries{
#define FSI_PROTOCOL_LISTED(enumerator, message, id) {MessageType{id}, #enumerator},
      FSI_PROTOCOL_MESSAGES(FSI_PROTOCOL_LISTED)
#undef FSI_PROTOCOL_LISTED
  };
  return entries;
}

bool is_listed(std::uint16_t id) {
  for (const Listed& entry : listed()) {
    if (static_cast<std::uint16_t>(entry.type) == id) return true;
  }
  return false;
}

TEST(ProtocolMessageList, TheVariantHoldsTheListedTypesInListOrder) {
  ASSERT_EQ(kMessageTypeCount, listed().size());
  std::size_t index = 0;
  for_each_message_type([&]<class T>(std::type_identity<T>) {
    EXPECT_EQ(T::kType, listed()[index].type) << listed()[index].enumerator;
    const Message alternative{T{}};
    EXPECT_EQ(alternative.index(), index) << listed()[index].enumerator;
    EXPECT_EQ(type_of(alternative), T::kType) << listed()[index].enumerator;
    ++index;
  });
  std::set<std::uint16_t> ids;
  for (const Listed& entry : listed())
    ids.insert(static_cast<std::uint16_t>(entry.type));
  EXPECT_EQ(ids.size(), listed().size()) << "two entries share a type id";
}

// Every listed type is known, named after its enumerator, accepted in a frame header and has a
// decoder (which struct it decodes to, the seed test below checks); every id of the 65536 outside
// the list is refused with the existing messages.
TEST(ProtocolMessageList, EveryIdIsKnownExactlyWhenListed) {
  for (const Listed& entry : listed()) {
    EXPECT_TRUE(is_known(entry.type)) << entry.enumerator;
    EXPECT_EQ(name(entry.type), entry.enumerator);
    const auto frame = encode_frame(entry.type, {});
    EXPECT_FALSE(contains(frame_error(frame), "does not define")) << entry.enumerator;
    EXPECT_FALSE(contains(decode_error(entry.type, {}), "does not define")) << entry.enumerator;
  }
  for (std::uint32_t id = 0; id <= 0xFFFF; ++id) {
    if (is_listed(static_cast<std::uint16_t>(id))) continue;
    const auto type = static_cast<MessageType>(id);
    ASSERT_FALSE(is_known(type)) << id;
    char hex[8];
    std::snprintf(hex, sizeof hex, "0x%04x", static_cast<unsigned>(id));
    const std::string unknown = std::string("unknown type ") + hex;
    ASSERT_EQ(name(type), unknown);
    const std::string undefined =
        ", which protocol " + version_text(kMajorVersion, kMinorVersion) + " does not define";
    ASSERT_TRUE(
        contains(decode_error(type, {}), "cannot decode a message of " + unknown + undefined));
    ASSERT_TRUE(contains(frame_error(encode_frame(type, {})), "frame of " + unknown + undefined));
  }
}

// The seeds of the fuzz corpus are one valid message of each type: through the list's decode
// dispatch each comes back as the struct of its type and re-encodes to the same bytes.
std::vector<std::byte> read_bytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  const std::vector<char> chars{std::istreambuf_iterator<char>(in), {}};
  const auto bytes = std::as_bytes(std::span(chars));
  return {bytes.begin(), bytes.end()};
}

std::string file_stem(const std::string& enumerator) {
  std::string stem;
  for (const char c : enumerator) {
    if (std::isupper(static_cast<unsigned char>(c)) && !stem.empty()) stem += '_';
    stem += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  }
  return stem;
}

TEST(ProtocolMessageList, EverySeedFrameDecodesAsItsTypeAndReencodesBytewise) {
  const std::filesystem::path corpus = FSI_PROTOCOL_FUZZ_CORPUS;
  for (const Listed& entry : listed()) {
    const auto path = corpus / "frame" / (file_stem(entry.enumerator) + ".bin");
    const auto bytes = read_bytes(path);
    ASSERT_FALSE(bytes.empty()) << "no seed " << path;
    const Frame frame = decode_frame(bytes);
    EXPECT_EQ(frame.header.type, entry.type) << path;
    const Message message = decode(frame.header.type, frame.payload);
    EXPECT_EQ(type_of(message), entry.type) << path;
    EXPECT_EQ(encode_frame(type_of(message), encode(message)), bytes) << path;
  }
}

TEST(ProtocolMessageList, TheFuzzDecoderTableFollowsTheListAndItsSeedsSelectTheirOwnEntry) {
  const std::filesystem::path corpus = FSI_PROTOCOL_FUZZ_CORPUS;
  ASSERT_EQ(fuzz::kDecoders.size(), listed().size());
  for (std::size_t i = 0; i < listed().size(); ++i) {
    EXPECT_EQ(fuzz::kDecoders[i].type, listed()[i].type) << listed()[i].enumerator;
    const auto path = corpus / "messages" / (file_stem(listed()[i].enumerator) + ".bin");
    const auto bytes = read_bytes(path);
    ASSERT_FALSE(bytes.empty()) << "no seed " << path;
    EXPECT_EQ(std::to_integer<std::size_t>(bytes[0]), i) << path;
    const auto payload = std::span(bytes).subspan(1);
    const auto again = fuzz::kDecoders[i].run(payload);
    EXPECT_TRUE(std::equal(again.begin(), again.end(), payload.begin(), payload.end())) << path;
  }
}

}  // namespace
}  // namespace fsi::protocol
