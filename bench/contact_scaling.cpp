// Cost of the 2D SPH–wall contact core (fsi::contact::WallContact2D) at the thesis resolution:
// ns per candidate pair, and how the time grows when the number of boundary elements or of
// particles doubles (thesis §5.5.2: linear in both). Not a pass/fail test.
//
//   build/bin/bench_contact_scaling [--repeat 30]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "fsi/contact/wall_contact.hpp"

namespace {

using fsi::contact::BoundaryMesh2D;
using fsi::contact::ContactDiagnostics;
using fsi::contact::ContactSettings;
using fsi::contact::ParticleArrays;
using fsi::contact::WallContact2D;

constexpr double kH = 0.000614;        // thesis static tank smoothing length
constexpr double kSpacing = 0.000323;  // and particle spacing
constexpr double kWidth = 0.05;
constexpr double kHeight = 0.03;

struct Fluid {
  std::vector<double> x, v, f;
  ParticleArrays arrays() {
    ParticleArrays a;
    a.count = x.size() / 3;
    a.positions = x.data();
    a.velocities = v.data();
    a.forces = f.data();
    return a;
  }
};

// A block of particles on a lattice with the given spacing, slightly jittered.
Fluid fluid_block(double spacing) {
  Fluid fluid;
  unsigned state = 12345;
  auto jitter = [&] {
    state = state * 1103515245u + 12345u;
    return 0.05 * spacing * (static_cast<double>(state >> 8) / 16777216.0 - 0.5);
  };
  for (double y = 0.5 * spacing; y < kHeight; y += spacing) {
    for (double x = 0.5 * spacing; x < kWidth; x += spacing) {
      fluid.x.insert(fluid.x.end(), {x + jitter(), y + jitter(), 0.0});
      fluid.v.insert(fluid.v.end(), {1e-3, -1e-3, 0.0});
      fluid.f.insert(fluid.f.end(), {0.0, 0.0, 0.0});
    }
  }
  return fluid;
}

// `lines` horizontal walls across the fluid, each made of segments of length 2h.
BoundaryMesh2D walls(int lines) {
  BoundaryMesh2D mesh;
  const int segments = static_cast<int>(std::round(kWidth / (2.0 * kH)));
  for (int line = 0; line < lines; ++line) {
    const double y = kHeight * (line + 0.5) / lines;
    const auto first = static_cast<std::uint32_t>(mesh.vertex_count());
    for (int k = 0; k <= segments; ++k) {
      mesh.positions.insert(mesh.positions.end(), {kWidth * k / segments, y});
      mesh.velocities.insert(mesh.velocities.end(), {0.0, 0.0});
    }
    for (int k = 0; k < segments; ++k)
      mesh.segments.insert(mesh.segments.end(), {first + k, first + k + 1});
  }
  return mesh;
}

ContactSettings settings(double resolution) {
  ContactSettings s;
  s.law.repulsion_scale = 17500.0;
  s.law.viscous_scale = 1628.0;
  s.law.cutoff = 2.0 * kH;
  s.law.equilibrium_distance = 2.0 * kH;
  s.gauss_points = 3;
  s.refinement_resolution = resolution;
  return s;
}

struct Measurement {
  double seconds;  // median of the repetitions
  ContactDiagnostics diagnostics;
  std::size_t particles;
  std::size_t segments;
};

Measurement measure(int lines, double spacing, double resolution, int repeat) {
  Fluid fluid = fluid_block(spacing);
  const BoundaryMesh2D mesh = walls(lines);
  std::vector<double> vertex_forces(mesh.positions.size());
  WallContact2D contact(settings(resolution));
  std::vector<double> times;
  Measurement m{};
  for (int r = 0; r < repeat + 2; ++r) {  // two warm-up evaluations
    const auto start = std::chrono::steady_clock::now();
    m.diagnostics = contact.compute(mesh, fluid.arrays(), vertex_forces);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (r >= 2) times.push_back(seconds);
  }
  std::nth_element(times.begin(), times.begin() + times.size() / 2, times.end());
  m.seconds = times[times.size() / 2];
  m.particles = fluid.x.size() / 3;
  m.segments = mesh.segment_count();
  return m;
}

void print(const char* label, const Measurement& m) {
  const auto& d = m.diagnostics;
  std::printf("%-28s %8zu %8zu %9zu %11zu %10zu %9.3f %8.2f %8.2f\n", label, m.particles,
              m.segments, d.sampling_points, d.candidate_pairs, d.pair_count, m.seconds * 1e3,
              m.seconds * 1e9 / static_cast<double>(d.candidate_pairs),
              m.seconds * 1e9 / static_cast<double>(d.pair_count));
}

}  // namespace

int main(int argc, char** argv) {
  int repeat = 30;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--repeat") == 0 && i + 1 < argc) {
      repeat = std::max(1, std::atoi(argv[++i]));
    } else {
      std::fprintf(stderr, "usage: %s [--repeat N]\n", argv[0]);
      return 2;
    }
  }
  std::printf(
      "fsi::contact::WallContact2D, one core, median of %d evaluations; h = %g m, "
      "spacing %g m, 3 Gauss points\n\n",
      repeat, kH, kSpacing);
  std::printf("%-28s %8s %8s %9s %11s %10s %9s %8s %8s\n", "case", "particles", "segments",
              "samples", "candidates", "in range", "ms", "ns/cand", "ns/pair");
  const double rc = 2.0 * kH;
  const Measurement base = measure(4, kSpacing, rc, repeat);
  print("base (4 walls, res r_c)", base);
  const Measurement walls2 = measure(8, kSpacing, rc, repeat);
  print("2x boundary elements", walls2);
  const Measurement walls4 = measure(16, kSpacing, rc, repeat);
  print("4x boundary elements", walls4);
  const Measurement particles2 = measure(4, kSpacing / std::sqrt(2.0), rc, repeat);
  print("2x particles (same box)", particles2);
  const Measurement particles4 = measure(4, kSpacing / 2.0, rc, repeat);
  print("4x particles (same box)", particles4);
  std::printf(
      "\ntime ratios: 2x elements %.3f, 4x elements %.3f; 2x particles %.3f, 4x particles "
      "%.3f (linear: 2 and 4)\n",
      walls2.seconds / base.seconds, walls4.seconds / base.seconds,
      particles2.seconds / base.seconds, particles4.seconds / base.seconds);

  std::printf("\nspeed vs accuracy: refinement resolution (pieces shorter than it)\n");
  std::printf("%-28s %8s %8s %9s %11s %10s %9s %8s %8s\n", "case", "particles", "segments",
              "samples", "candidates", "in range", "ms", "ns/cand", "ns/pair");
  for (int divisor : {1, 2, 4, 8, 16}) {
    char label[64];
    std::snprintf(label, sizeof label, "resolution r_c/%d", divisor);
    const Measurement m = measure(4, kSpacing, rc / divisor, repeat);
    print(label, m);
    std::printf("%-28s time / (r_c case) = %.2f\n", "", m.seconds / base.seconds);
  }
  return 0;
}
