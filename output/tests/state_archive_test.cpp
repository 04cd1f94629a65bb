#include "fsi/output/state_archive.hpp"

#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "fsi/common/error.hpp"

namespace fsi::output {
namespace {

std::string written() {
  StateWriter writer;
  writer.section("structure");
  writer.put(std::uint64_t{123456789012345});
  writer.put(-0.0);
  writer.put(std::numeric_limits<double>::denorm_min());
  writer.put(true);
  writer.put(std::string_view("text with\0zero", 14));
  writer.section("audit");
  writer.put(std::vector<double>{1.0 / 3.0, -2.5e-300});
  Eigen::VectorXd q(3);
  q << 0.1, 0.2, 0.3;
  writer.put(q);
  writer.put(std::vector<double>{});
  return writer.bytes();
}

TEST(StateArchive, ReadsBackBitForBit) {
  const std::string bytes = written();
  StateReader reader(bytes, "test");
  reader.section("structure");
  EXPECT_EQ(reader.u64("steps"), 123456789012345u);
  const double zero = reader.f64("negative zero");
  EXPECT_EQ(std::bit_cast<std::uint64_t>(zero), std::bit_cast<std::uint64_t>(-0.0));
  EXPECT_EQ(reader.f64("tiny"), std::numeric_limits<double>::denorm_min());
  EXPECT_TRUE(reader.boolean("flag"));
  EXPECT_EQ(reader.text("name"), std::string("text with\0zero", 14));
  reader.section("audit");
  const std::vector<double> values = reader.doubles("forces");
  ASSERT_EQ(values.size(), 2u);
  EXPECT_EQ(values[0], 1.0 / 3.0);
  EXPECT_EQ(values[1], -2.5e-300);
  const Eigen::VectorXd q = reader.vector("q", 3);
  EXPECT_EQ(q[2], 0.3);
  EXPECT_TRUE(reader.doubles("empty").empty());
  EXPECT_NO_THROW(reader.finish());
}

void expect_error(const std::function<void()>& action, const std::string& text) {
  try {
    action();
    FAIL() << "no error; expected one saying: " << text;
  } catch (const fsi::Error& error) {
    EXPECT_NE(std::string(error.what()).find(text), std::string::npos) << error.what();
  }
}

TEST(StateArchive, AnotherLayoutIsRefusedByName) {
  const std::string bytes = written();
  {
    StateReader reader(bytes, "server.state of step-000000010");
    expect_error([&] { reader.section("session"); },
                 "expected the section 'session', found the section 'structure'");
  }
  {
    StateReader reader(bytes, "server.state");
    reader.section("structure");
    expect_error([&] { reader.f64("time"); },
                 "expected a number for time in section "
                 "'structure', found an integer");
  }
  {
    StateReader reader(bytes, "server.state");
    reader.section("structure");
    reader.u64("a");
    reader.f64("b");
    reader.f64("c");
    reader.boolean("d");
    reader.text("e");
    reader.section("audit");
    reader.doubles("f");
    expect_error([&] { reader.vector("q", 5); },
                 "q in section 'audit' has 3 values, the scene "
                 "has 5");
  }
  {
    StateReader reader(bytes, "server.state");
    reader.section("structure");
    expect_error([&] { reader.finish(); }, "bytes after the last value of section 'structure'");
  }
}

TEST(StateArchive, ACutShortStateIsRefused) {
  const std::string bytes = written();
  const std::string cut = bytes.substr(0, bytes.size() - 12);
  StateReader reader(cut, "server.state");
  reader.section("structure");
  reader.u64("a");
  reader.f64("b");
  reader.f64("c");
  reader.boolean("d");
  reader.text("e");
  reader.section("audit");
  reader.doubles("f");
  expect_error([&] { reader.vector("q", 3); }, "the state ends inside q of section 'audit'");
}

}  // namespace
}  // namespace fsi::output
