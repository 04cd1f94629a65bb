// MPI ping-pong between ranks 0 and 1: the latency and the bandwidth of one message, the two
// numbers of the communication term in bench/cost_model.py (docs/performance.md, "Cost model").
//
//   mpirun -np 2 build/bin/bench_mpi_pingpong [--repeats 2000] [--json]
//
// For each message size from 8 bytes to 512 KiB (factors of 4), rank 0 sends, rank 1 sends back,
// `repeats` times after a warm-up; the one-way time is half the round trip. A least-squares line
// through the one-way times gives latency + bytes / bandwidth. Not pass/fail; the machine should be
// idle.
#include <mpi.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

namespace {

struct Sample {
  double bytes = 0.0;
  double seconds = 0.0;  // one way
};

double one_way_seconds(std::vector<char>& buffer, int repeats, int rank) {
  const int size = static_cast<int>(buffer.size());
  MPI_Barrier(MPI_COMM_WORLD);
  const double start = MPI_Wtime();
  for (int i = 0; i < repeats; ++i) {
    if (rank == 0) {
      MPI_Send(buffer.data(), size, MPI_CHAR, 1, 0, MPI_COMM_WORLD);
      MPI_Recv(buffer.data(), size, MPI_CHAR, 1, 0, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    } else if (rank == 1) {
      MPI_Recv(buffer.data(), size, MPI_CHAR, 0, 0, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
      MPI_Send(buffer.data(), size, MPI_CHAR, 0, 0, MPI_COMM_WORLD);
    }
  }
  return (MPI_Wtime() - start) / (2.0 * repeats);
}

}  // namespace

int main(int argc, char** argv) {
  MPI_Init(&argc, &argv);
  int rank = 0;
  int ranks = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &ranks);
  int repeats = 2000;
  bool json = false;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--repeats") == 0 && i + 1 < argc) {
      repeats = std::atoi(argv[++i]);
    } else if (std::strcmp(argv[i], "--json") == 0) {
      json = true;
    } else {
      if (rank == 0)
        std::fprintf(stderr,
                     "bench_mpi_pingpong: unknown argument '%s'; usage: mpirun -np 2 "
                     "bench_mpi_pingpong [--repeats N] [--json]\n",
                     argv[i]);
      MPI_Finalize();
      return 2;
    }
  }
  if (ranks < 2 || repeats < 1) {
    if (rank == 0)
      std::fprintf(stderr, "bench_mpi_pingpong: needs 2 ranks (mpirun -np 2) and --repeats >= 1\n");
    MPI_Finalize();
    return 2;
  }
  std::vector<Sample> samples;
  for (std::size_t bytes = 8; bytes <= (std::size_t{1} << 20); bytes *= 4) {
    std::vector<char> buffer(bytes, 'x');
    const int count = bytes > (std::size_t{1} << 16) ? std::max(1, repeats / 20) : repeats;
    one_way_seconds(buffer, std::max(1, count / 10), rank);  // warm-up
    samples.push_back({static_cast<double>(bytes), one_way_seconds(buffer, count, rank)});
  }
  if (rank == 0) {
    // Least squares: seconds = latency + bytes * inverse_bandwidth.
    double sx = 0.0, sy = 0.0, sxx = 0.0, sxy = 0.0;
    for (const Sample& sample : samples) {
      sx += sample.bytes;
      sy += sample.seconds;
      sxx += sample.bytes * sample.bytes;
      sxy += sample.bytes * sample.seconds;
    }
    const double n = static_cast<double>(samples.size());
    const double inverse_bandwidth = (n * sxy - sx * sy) / (n * sxx - sx * sx);
    // The latency is the smallest message's time: the line's intercept is dominated by the
    // large messages' scatter.
    const double latency = samples.front().seconds;
    if (json) {
      std::printf("{\"latency_s\": %.6e, \"bandwidth_bytes_per_s\": %.6e, \"samples\": [", latency,
                  1.0 / inverse_bandwidth);
      for (std::size_t i = 0; i < samples.size(); ++i)
        std::printf("%s[%.0f, %.6e]", i ? ", " : "", samples[i].bytes, samples[i].seconds);
      std::printf("]}\n");
    } else {
      std::printf("%12s %14s\n", "bytes", "one way [us]");
      for (const Sample& sample : samples)
        std::printf("%12.0f %14.3f\n", sample.bytes, 1e6 * sample.seconds);
      std::printf("latency %.3f us, bandwidth %.3f GB/s\n", 1e6 * latency,
                  1e-9 / inverse_bandwidth);
    }
  }
  MPI_Finalize();
  return 0;
}
