// What every libFuzzer target of ours shares; fsi_add_fuzzer() (cmake/FsiFuzz.cmake) puts this
// folder on the include path. Include it from the one source file of a target, which defines
// fsi::fuzz::print_reach. scripts/run-fuzzers reads the "fuzz-reach:" lines that print_reach
// writes when the run ends, to see that the target reached everything it must reach.
#pragma once

#include <cstdio>
#include <cstdlib>
#include <string>

namespace fsi::fuzz {

// Defined by each target: its "fuzz-reach: ..." counts on stderr, printed once at exit.
void print_reach();

// A finding: the message on stderr, then abort(), which libFuzzer reports and keeps the input of.
[[noreturn]] inline void finding(const std::string& message) {
  std::fprintf(stderr, "%s\n", message.c_str());
  std::abort();
}

}  // namespace fsi::fuzz

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  std::atexit(fsi::fuzz::print_reach);
  return 0;
}
