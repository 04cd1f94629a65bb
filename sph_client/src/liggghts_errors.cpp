// Replaces LIGGGHTS' Error::one and Error::all in fsi-client (liggghts_errors.hpp says why).
// libliggghts calls both through its procedure linkage table (every call site, checked with
// objdump on Debian's libliggghts.so.3.8.0), so the definitions of the executable take their
// place for the whole library, as a program's own operator new does for libstdc++.
#include <mpi.h>

#include <cstdio>

#include "error.h"
#include "liggghts_errors.hpp"

namespace {

std::string error_line(const char* prefix, const char* text, const char* file, int line) {
  char buffer[1024];
  std::snprintf(buffer, sizeof buffer, "%s%s (%s:%d)", prefix, text, file, line);
  return buffer;
}

}  // namespace

void LAMMPS_NS::Error::one(const char* file, int line, const char* text) {
  int rank = 0;
  MPI_Comm_rank(world, &rank);
  char prefix[64];
  std::snprintf(prefix, sizeof prefix, "ERROR on proc %d: ", rank);
  const std::string message = error_line(prefix, text, file, line);
  // The screen is fsi-client's capture of LIGGGHTS' output: it logs and keeps the line.
  if (screen) std::fprintf(screen, "%s\n", message.c_str());
  if (logfile) std::fprintf(logfile, "%s\n", message.c_str());
  throw fsi::client::LiggghtsError(message, false);
}

void LAMMPS_NS::Error::all(const char* file, int line, const char* text) {
  const std::string message = error_line("ERROR: ", text, file, line);
  int rank = 0;
  MPI_Comm_rank(world, &rank);
  // Every rank raises it: the line once, as LIGGGHTS prints it (the exception carries it on every
  // rank, also when a rank raises it alone).
  if (rank == 0 && screen) std::fprintf(screen, "%s\n", message.c_str());
  if (logfile) std::fprintf(logfile, "%s\n", message.c_str());
  throw fsi::client::LiggghtsError(message, true);
}
