// libFuzzer target: the parameter language (parser, overrides, evaluator, printing) through the
// public API of parameter_file.hpp. Input: the text of /fuzz/main.scene, optionally followed by
// more files, each after a line "%%% NAME" (NAME relative to /fuzz/); `include` reads only these
// files, from memory (in_memory_files), so no input can make the target read or write anything
// on disk. Every input must either parse, and then print back (to_text) to text that parses to
// the same values, or throw fsi::Error; anything else (a crash, a sanitizer report, another
// exception, a print that does not read back) is a finding.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <map>
#include <string>
#include <string_view>

#include "fsi/common/error.hpp"
#include "fsi/scene/parameter_file.hpp"
#include "fuzz_target.hpp"

namespace {

using namespace fsi::scene;

constexpr std::string_view kFileMarker = "\n%%% ";
constexpr const char* kMainFile = "/fuzz/main.scene";

std::size_t accepted = 0;
std::size_t rejected = 0;
std::size_t with_includes = 0;

// Splits the input into the main text and the named files after it.
std::string split(std::string_view input, std::map<std::string, std::string>& files) {
  std::size_t marker = input.find(kFileMarker);
  const std::string main(input.substr(0, marker));
  while (marker != std::string_view::npos) {
    const std::size_t name_begin = marker + kFileMarker.size();
    const std::size_t name_end = std::min(input.find('\n', name_begin), input.size());
    const std::size_t next = input.find(kFileMarker, name_end);
    const std::size_t text_begin = std::min(name_end + 1, input.size());
    const std::size_t text_end = next == std::string_view::npos ? input.size() : next;
    const std::string name(input.substr(name_begin, name_end - name_begin));
    files["/fuzz/" + name] = std::string(input.substr(text_begin, text_end - text_begin));
    marker = next;
  }
  return main;
}

bool same(double a, double b) {
  return a == b || (std::isnan(a) && std::isnan(b));
}

bool same(const std::vector<double>& a, const std::vector<double>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (!same(a[i], b[i])) return false;
  }
  return true;
}

bool same(const Value& a, const Value& b) {
  if (a.kind != b.kind) return false;
  switch (a.kind) {
    case ValueKind::Number:
      return same(a.number, b.number);
    case ValueKind::String:
      return a.text == b.text;
    case ValueKind::Vector:
      return same(a.vector, b.vector);
    case ValueKind::Matrix:
      if (a.matrix.size() != b.matrix.size()) return false;
      for (std::size_t i = 0; i < a.matrix.size(); ++i) {
        if (!same(a.matrix[i], b.matrix[i])) return false;
      }
      return true;
  }
  return false;
}

// Every parameter of `a` has a parameter of the same path and value in `b`, and vice versa.
bool same(const Block& a, const Block& b) {
  if (a.parameters.size() != b.parameters.size() || a.blocks.size() != b.blocks.size() ||
      a.name != b.name) {
    return false;
  }
  for (std::size_t i = 0; i < a.parameters.size(); ++i) {
    if (a.parameters[i].key != b.parameters[i].key ||
        !same(a.parameters[i].value, b.parameters[i].value)) {
      return false;
    }
  }
  for (std::size_t i = 0; i < a.blocks.size(); ++i) {
    if (!same(a.blocks[i], b.blocks[i])) return false;
  }
  return true;
}

[[noreturn]] void finding(const std::string& what, const std::string& text) {
  fsi::fuzz::finding("scene fuzzer finding: " + what + "\n--- printed text ---\n" + text);
}

}  // namespace

void fsi::fuzz::print_reach() {
  std::fprintf(stderr, "fuzz-reach: scenes accepted=%zu rejected=%zu\n", accepted, rejected);
  std::fprintf(stderr, "fuzz-reach: scenes with-include-files=%zu\n", with_includes);
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::map<std::string, std::string> files;
  const std::string main =
      split(std::string_view(reinterpret_cast<const char*>(data), size), files);
  if (!files.empty()) ++with_includes;
  const IncludeReader read_include = in_memory_files(std::move(files));
  Block root;
  try {
    root = parse_parameter_text(main, kMainFile, {}, read_include);
  } catch (const fsi::Error&) {
    ++rejected;
    return 0;
  }
  ++accepted;
  // The other public views of an accepted tree must not fail either.
  const std::string printed = to_text(root);
  (void)to_json(root).dump();
  (void)flatten_numbers(root);
  // parameter_file.hpp: parsing the printed tree again gives the same values.
  Block again;
  try {
    again = parse_parameter_text(printed, "/fuzz/printed.scene", {}, in_memory_files({}));
  } catch (const fsi::Error& error) {
    finding(std::string("the printed tree does not parse: ") + error.what(), printed);
  }
  if (!same(root, again)) finding("the printed tree parses to other values", printed);
  return 0;
}
