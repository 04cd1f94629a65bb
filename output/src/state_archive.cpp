#include "fsi/output/state_archive.hpp"

#include <bit>
#include <cstring>

#include "fsi/common/error.hpp"

namespace fsi::output {

// The archive stores the host's bytes; every machine we build on is little-endian.
static_assert(std::endian::native == std::endian::little, "the state archive is little-endian");

namespace {

enum Tag : std::uint8_t {
  kSection = 'S',
  kUnsigned = 'u',
  kDouble = 'd',
  kBool = 'b',
  kText = 't',
  kVector = 'v',
};

const char* tag_name(std::uint8_t tag) {
  switch (tag) {
    case kSection:
      return "a section";
    case kUnsigned:
      return "an integer";
    case kDouble:
      return "a number";
    case kBool:
      return "a flag";
    case kText:
      return "a text";
    case kVector:
      return "a vector";
    default:
      return "an unknown value";
  }
}

}  // namespace

void StateWriter::raw(const void* data, std::size_t size) {
  bytes_.append(static_cast<const char*>(data), size);
}

void StateWriter::section(std::string_view name) {
  bytes_.push_back(static_cast<char>(kSection));
  const std::uint64_t size = name.size();
  raw(&size, sizeof size);
  bytes_.append(name);
}

void StateWriter::put(std::uint64_t value) {
  bytes_.push_back(static_cast<char>(kUnsigned));
  raw(&value, sizeof value);
}

void StateWriter::put(double value) {
  bytes_.push_back(static_cast<char>(kDouble));
  raw(&value, sizeof value);
}

void StateWriter::put(bool value) {
  bytes_.push_back(static_cast<char>(kBool));
  bytes_.push_back(value ? 1 : 0);
}

void StateWriter::put(std::string_view text) {
  bytes_.push_back(static_cast<char>(kText));
  const std::uint64_t size = text.size();
  raw(&size, sizeof size);
  bytes_.append(text);
}

void StateWriter::put(const std::vector<double>& values) {
  bytes_.push_back(static_cast<char>(kVector));
  const std::uint64_t size = values.size();
  raw(&size, sizeof size);
  if (size > 0) raw(values.data(), values.size() * sizeof(double));
}

void StateWriter::put(const Eigen::VectorXd& values) {
  bytes_.push_back(static_cast<char>(kVector));
  const std::uint64_t size = static_cast<std::uint64_t>(values.size());
  raw(&size, sizeof size);
  if (size > 0) raw(values.data(), static_cast<std::size_t>(values.size()) * sizeof(double));
}

StateReader::StateReader(std::string_view bytes, std::string source)
    : bytes_(bytes), source_(std::move(source)) {}

void StateReader::cut_short(std::string_view what) const {
  throw Error("the state ends inside " + std::string(what) + " of section '" + section_ + "'",
              source_, "the checkpoint file is cut short: resume from an older checkpoint");
}

void StateReader::raw(void* data, std::size_t size, std::string_view what) {
  if (bytes_.size() - offset_ < size) cut_short(what);
  std::memcpy(data, bytes_.data() + offset_, size);
  offset_ += size;
}

std::uint8_t StateReader::tag(std::string_view what) {
  std::uint8_t value = 0;
  raw(&value, 1, what);
  return value;
}

void StateReader::section(std::string_view name) {
  const std::uint8_t found = tag(std::string("section '") + std::string(name) + "'");
  std::string read;
  if (found == kSection) {
    std::uint64_t size = 0;
    raw(&size, sizeof size, "a section name");
    if (size > bytes_.size() - offset_) size = bytes_.size() - offset_;
    read.assign(bytes_.data() + offset_, size);
    offset_ += size;
  }
  if (found != kSection || read != name) {
    throw Error("expected the section '" + std::string(name) + "', found " +
                    (found == kSection ? "the section '" + read + "'" : tag_name(found)) +
                    " (after section '" + section_ + "')",
                source_,
                "the checkpoint was written by another release or for another scene: resume "
                "with the same scene and release, or start the run afresh");
  }
  section_ = read;
}

namespace {
[[noreturn]] void wrong_tag(std::uint8_t found, std::uint8_t expected, std::string_view what,
                            const std::string& section, const std::string& source) {
  throw Error("expected " + std::string(tag_name(expected)) + " for " + std::string(what) +
                  " in section '" + section + "', found " + tag_name(found),
              source,
              "the checkpoint was written by another release or for another scene: resume with "
              "the same scene and release, or start the run afresh");
}
}  // namespace

std::uint64_t StateReader::u64(std::string_view what) {
  if (const auto found = tag(what); found != kUnsigned)
    wrong_tag(found, kUnsigned, what, section_, source_);
  std::uint64_t value = 0;
  raw(&value, sizeof value, what);
  return value;
}

std::uint64_t StateReader::count(std::string_view what) {
  const std::uint64_t value = u64(what);
  if (value > bytes_.size() - offset_) cut_short(what);
  return value;
}

double StateReader::f64(std::string_view what) {
  if (const auto found = tag(what); found != kDouble)
    wrong_tag(found, kDouble, what, section_, source_);
  double value = 0.0;
  raw(&value, sizeof value, what);
  return value;
}

bool StateReader::boolean(std::string_view what) {
  if (const auto found = tag(what); found != kBool)
    wrong_tag(found, kBool, what, section_, source_);
  std::uint8_t value = 0;
  raw(&value, 1, what);
  return value != 0;
}

std::string StateReader::text(std::string_view what) {
  if (const auto found = tag(what); found != kText)
    wrong_tag(found, kText, what, section_, source_);
  std::uint64_t size = 0;
  raw(&size, sizeof size, what);
  if (size > bytes_.size() - offset_) cut_short(what);
  std::string value(bytes_.data() + offset_, size);
  offset_ += size;
  return value;
}

std::vector<double> StateReader::doubles(std::string_view what) {
  if (const auto found = tag(what); found != kVector)
    wrong_tag(found, kVector, what, section_, source_);
  std::uint64_t size = 0;
  raw(&size, sizeof size, what);
  if (size > (bytes_.size() - offset_) / sizeof(double)) cut_short(what);
  std::vector<double> values(size);
  if (size > 0) raw(values.data(), size * sizeof(double), what);
  return values;
}

Eigen::VectorXd StateReader::vector(std::string_view what, Eigen::Index size) {
  const std::vector<double> values = doubles(what);
  if (values.size() != static_cast<std::size_t>(size)) {
    throw Error(std::string(what) + " in section '" + section_ + "' has " +
                    std::to_string(values.size()) + " values, the scene has " +
                    std::to_string(size),
                source_,
                "the checkpoint was written for another scene: resume with the scene that wrote "
                "it (run.json names it), or start the run afresh");
  }
  return Eigen::Map<const Eigen::VectorXd>(values.data(), size);
}

void StateReader::finish() const {
  if (offset_ != bytes_.size()) {
    throw Error(std::to_string(bytes_.size() - offset_) +
                    " bytes after the last value of section '" + section_ + "'",
                source_,
                "the checkpoint was written by another release: resume with the release that "
                "wrote it, or start the run afresh");
  }
}

}  // namespace fsi::output
