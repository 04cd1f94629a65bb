#pragma once
// The binary state of a program part in a checkpoint (checkpoint_store.hpp): named sections of
// numbers, vectors and strings, little-endian, doubles bit for bit (a resumed run continues from
// exactly the numbers it stopped at). Each part writes one section and reads it back in the same
// order; a reader that meets another section, another size or the end of the data throws
// fsi::Error naming the section and the value, so a checkpoint of another scene or release is
// refused rather than misread.

#include <Eigen/Core>

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace fsi::output {

class StateWriter {
 public:
  // Starts a section; its values follow until the next section.
  void section(std::string_view name);
  void put(std::uint64_t value);
  void put(double value);
  void put(bool value);
  void put(std::string_view text);
  void put(const std::vector<double>& values);
  void put(const Eigen::VectorXd& values);
  const std::string& bytes() const { return bytes_; }

 private:
  void raw(const void* data, std::size_t size);
  std::string bytes_;
};

class StateReader {
 public:
  // `source` names the data in errors ("server.state of checkpoint step-000000100").
  StateReader(std::string_view bytes, std::string source);
  // Throws unless the next section is `name`.
  void section(std::string_view name);
  std::uint64_t u64(std::string_view what);
  // A number of values that follow (each at least one byte): refused when more than the bytes
  // left, so that a damaged count never allocates.
  std::uint64_t count(std::string_view what);
  double f64(std::string_view what);
  bool boolean(std::string_view what);
  std::string text(std::string_view what);
  std::vector<double> doubles(std::string_view what);
  // A vector that must have `size` values (the model's coordinates, ...).
  Eigen::VectorXd vector(std::string_view what, Eigen::Index size);
  // Throws unless every byte was read.
  void finish() const;

 private:
  void raw(void* data, std::size_t size, std::string_view what);
  [[noreturn]] void cut_short(std::string_view what) const;
  std::uint8_t tag(std::string_view what);
  std::string_view bytes_;
  std::size_t offset_ = 0;
  std::string source_;
  std::string section_;
};

}  // namespace fsi::output
