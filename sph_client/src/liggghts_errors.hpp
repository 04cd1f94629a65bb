#pragma once
// LIGGGHTS ends the process on an error: Error::one (an error one rank sees) calls MPI_Abort,
// Error::all (one every rank sees) calls MPI_Finalize and exit. Either way rank 0 may die before
// it tells fsi-server why, and the other ranks' messages are lost. fsi-client replaces both
// (liggghts_errors.cpp, linked into fsi-client only): they print LIGGGHTS' own ERROR line as
// before and throw LiggghtsError, which the session reports from whichever rank caught it
// (fault_relay.hpp) before the job ends in one controlled way.

#include <stdexcept>
#include <string>

namespace fsi::client {

class LiggghtsError : public std::runtime_error {
 public:
  // line: LIGGGHTS' text, "ERROR: ... (file:line)" or "ERROR on proc N: ... (file:line)".
  LiggghtsError(const std::string& line, bool every_rank)
      : std::runtime_error(line), every_rank_(every_rank) {}
  // Error::all: every rank raises it (the same script line); Error::one: this rank only.
  bool every_rank() const noexcept { return every_rank_; }

 private:
  bool every_rank_;
};

}  // namespace fsi::client
