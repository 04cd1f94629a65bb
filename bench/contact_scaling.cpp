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
#include <limits>
#include <vector>

#include "contact_test_support.hpp"
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

using Fluid = fsi::contact::test_support::ParticleCloud;

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
      const double jittered_x = x + jitter();
      fluid.add(jittered_x, y + jitter(), 1e-3, -1e-3);
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
  double seconds = 0.0;  // fastest of the repetitions
  ContactDiagnostics diagnostics;
  std::size_t particles = 0;
  std::size_t segments = 0;
};

struct Case {
  const char* label;
  Fluid fluid;
  BoundaryMesh2D mesh;
  WallContact2D contact;
  std::vector<double> vertex_forces;
  Measurement result;
};

Case make_case(const char* label, int lines, double spacing, double resolution) {
  Case c{label, fluid_block(spacing), walls(lines), WallContact2D(settings(resolution)), {}, {}};
  c.vertex_forces.resize(c.mesh.positions.size());
  c.result.particles = c.fluid.x.size() / 3;
  c.result.segments = c.mesh.segment_count();
  c.result.seconds = std::numeric_limits<double>::infinity();
  return c;
}

// Evaluates every case once per round, round after round, and keeps each case's fastest time:
// the work is deterministic, so slower evaluations measure interference from the rest of the
// machine, and interleaving the cases spreads slow phases of this VM over all of them.
void measure(std::vector<Case>& cases, int rounds) {
  for (int round = 0; round < rounds + 2; ++round) {  // two warm-up rounds
    for (Case& c : cases) {
      // One untimed evaluation first, so that every case is timed with its own data in cache
      // (otherwise the case after the largest one pays for the cache misses).
      c.contact.compute(c.mesh, c.fluid.arrays(), c.vertex_forces);
      const auto start = std::chrono::steady_clock::now();
      c.result.diagnostics = c.contact.compute(c.mesh, c.fluid.arrays(), c.vertex_forces);
      const double seconds =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      if (round >= 2) c.result.seconds = std::min(c.result.seconds, seconds);
    }
  }
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
      "fsi::contact::WallContact2D, one core, fastest of %d evaluations; h = %g m, "
      "spacing %g m, 3 Gauss points\n\n",
      repeat, kH, kSpacing);
  std::printf("%-28s %8s %8s %9s %11s %10s %9s %8s %8s\n", "case", "particles", "segments",
              "samples", "candidates", "in range", "ms", "ns/cand", "ns/pair");
  const double rc = 2.0 * kH;
  std::vector<Case> scaling;
  scaling.push_back(make_case("base (4 walls, res r_c)", 4, kSpacing, rc));
  scaling.push_back(make_case("2x boundary elements", 8, kSpacing, rc));
  scaling.push_back(make_case("4x boundary elements", 16, kSpacing, rc));
  scaling.push_back(make_case("2x particles (same box)", 4, kSpacing / std::sqrt(2.0), rc));
  scaling.push_back(make_case("4x particles (same box)", 4, kSpacing / 2.0, rc));
  measure(scaling, repeat);
  for (const Case& c : scaling)
    print(c.label, c.result);
  const double base = scaling[0].result.seconds;
  std::printf(
      "\ntime ratios: 2x elements %.3f, 4x elements %.3f; 2x particles %.3f, 4x particles "
      "%.3f (linear: 2 and 4)\n",
      scaling[1].result.seconds / base, scaling[2].result.seconds / base,
      scaling[3].result.seconds / base, scaling[4].result.seconds / base);

  std::printf("\nspeed vs accuracy: refinement resolution (pieces shorter than it)\n");
  std::printf("%-28s %8s %8s %9s %11s %10s %9s %8s %8s\n", "case", "particles", "segments",
              "samples", "candidates", "in range", "ms", "ns/cand", "ns/pair");
  std::vector<Case> resolutions;
  const char* labels[] = {"resolution r_c", "resolution r_c/2", "resolution r_c/4",
                          "resolution r_c/8", "resolution r_c/16"};
  for (int k = 0; k < 5; ++k)
    resolutions.push_back(make_case(labels[k], 4, kSpacing, rc / static_cast<double>(1 << k)));
  measure(resolutions, repeat);
  for (const Case& c : resolutions) {
    print(c.label, c.result);
    std::printf("%-28s time / (resolution r_c) = %.2f\n", "",
                c.result.seconds / resolutions[0].result.seconds);
  }
  return 0;
}
