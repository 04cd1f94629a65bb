// Step time of Radau IIA (3 stages) against model size: a rigid pendulum chain of N bars
// (reference_problems.hpp) and an ANCF cantilever of N elements under gravity (also with two
// loaded face markers per element), N = 10 ... 1000,
// with the dense LU and with the automatic choice (Eigen SparseLU from
// NewtonOptions::sparse_threshold unknowns). Prints a markdown table per model with the time per
// step (best of 3 runs of `steps` steps), the Newton work, and the growth exponent
// log(t2/t1)/log(N2/N1) between neighbouring sizes: about 1 is linear. The dense LU column
// stops at N = 100 (O(size^3): 0.5 s per step there). Not pass/fail
// (docs/performance.md). Usage: bench_mbd_scaling [max_size]
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <string>
#include <vector>

#include "fsi/mbd/integrator.hpp"
#include "fsi/mbd/model.hpp"
#include "reference_problems.hpp"

namespace {

using namespace fsi::mbd;

Model cantilever(int elements) {
  Model model;
  model.set_gravity({0.0, -9.81});
  AncfBeamSpec beam;  // steel, 2 m, 0.1 m x 0.1 m (the cantilever of the acceptance tests)
  beam.name = "beam";
  beam.start = {0.0, 0.0};
  beam.end = {2.0, 0.0};
  beam.element_count = elements;
  beam.axial_stiffness = 2.07e11 * 0.01;
  beam.bending_stiffness = 2.07e11 * 1e-4 / 12.0;
  beam.mass_per_length = 7800.0 * 0.01;
  const BodyId id = model.add_ancf_beam(beam);
  model.add_beam_clamp(id, 0);
  return model;
}

// The cantilever with two face markers per element (eta = +-5 cm alternating) under a load, as
// in a coupled run (the fluid's vertex forces).
Model loaded_cantilever(int elements) {
  Model model = cantilever(elements);
  const int markers = 2 * elements;
  for (int k = 0; k < markers; ++k)
    model.add_marker(0, {(k + 0.5) * 2.0 / markers, k % 2 == 0 ? 0.05 : -0.05});
  model.set_point_loads(std::vector<double>(2 * markers, -1.0));
  return model;
}

struct Row {
  double milliseconds_per_step = 0.0;
  int unknowns = 0;
  double iterations_per_step = 0.0;
  std::uint64_t factorisations = 0;
};

Row measure(const std::function<Model(int)>& make, int size, LinearSolver solver, int steps,
            double step_size) {
  Row best;
  best.milliseconds_per_step = 1e300;
  for (int run = 0; run < 3; ++run) {
    const Model model = make(size);
    State state = model.initial_state();
    RadauOptions options;
    options.stages = 3;
    options.newton.linear_solver = solver;
    RadauIIA integrator(options);
    const auto start = std::chrono::steady_clock::now();
    for (int k = 0; k < steps; ++k)
      integrator.step(model, state, step_size);
    const double ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
            .count() /
        steps;
    if (ms < best.milliseconds_per_step) {
      best.milliseconds_per_step = ms;
      best.unknowns = 3 * (2 * model.coordinate_count() + model.constraint_count());
      const auto& stats = integrator.statistics();
      best.iterations_per_step = static_cast<double>(stats.newton_iterations) / steps;
      best.factorisations = stats.factorisations;
    }
  }
  return best;
}

void table(const char* title, const std::function<Model(int)>& make, double step_size,
           int max_size) {
  std::printf("\n### %s (Radau IIA 3, h = %g s, best of 3 runs of 10 steps)\n\n", title, step_size);
  std::printf(
      "| N | Newton unknowns | dense LU [ms/step] | automatic [ms/step] | solver | growth "
      "exponent (automatic) | Newton iterations/step | factorisations |\n"
      "|---|---|---|---|---|---|---|---|\n");
  double previous_time = 0.0;
  int previous_size = 0;
  for (int size : {10, 20, 50, 100, 200, 400, 1000}) {
    if (size > max_size) break;
    const Row automatic = measure(make, size, LinearSolver::Automatic, 10, step_size);
    const bool dense_affordable = size <= 100;
    const Row dense =
        dense_affordable ? measure(make, size, LinearSolver::Dense, 10, step_size) : Row{};
    char growth[32] = "–";
    if (previous_size > 0) {
      std::snprintf(growth, sizeof growth, "%.2f",
                    std::log(automatic.milliseconds_per_step / previous_time) /
                        std::log(static_cast<double>(size) / previous_size));
    }
    char dense_text[32] = "not run";
    if (dense_affordable)
      std::snprintf(dense_text, sizeof dense_text, "%.3f", dense.milliseconds_per_step);
    std::printf("| %d | %d | %s | %.3f | %s | %s | %.1f | %llu |\n", size, automatic.unknowns,
                dense_text, automatic.milliseconds_per_step,
                automatic.unknowns >= NewtonOptions{}.sparse_threshold ? "SparseLU" : "dense LU",
                growth, automatic.iterations_per_step,
                static_cast<unsigned long long>(automatic.factorisations));
    std::fflush(stdout);
    previous_time = automatic.milliseconds_per_step;
    previous_size = size;
  }
}

}  // namespace

int main(int argc, char** argv) {
  const int max_size = argc > 1 ? std::atoi(argv[1]) : 1000;
  table("Rigid chain of N bars (3 coordinates, 2 joint rows each)", reference::rigid_chain, 1e-3,
        max_size);
  table("ANCF cantilever of N elements (4 coordinates per node, clamp 3 rows)", cantilever, 1e-4,
        max_size);
  table("ANCF cantilever of N elements with 2N loaded face markers", loaded_cantilever, 1e-4,
        max_size);
  return 0;
}
