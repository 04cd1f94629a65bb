// Microbenchmarks of the hot paths of one coupled step (Google Benchmark):
// the contact core on a tank-like configuration, the Radau IIA step of the static tank's model,
// and encoding/decoding of the per-step messages.
#include <benchmark/benchmark.h>

#include <random>

#include "fsi/contact/wall_contact.hpp"
#include "fsi/mbd/integrator.hpp"
#include "fsi/mbd/model.hpp"
#include "fsi/protocol/messages.hpp"

namespace {

// Particles on a lattice in a 0.05 m wide box, walls and bottom as 3 segments.
void BM_ContactTank(benchmark::State& state) {
  const double h = 0.05 / static_cast<double>(state.range(0));  // smoothing length
  const double d = h / 1.9;
  std::vector<double> x, v, f;
  for (double y = h; y < 0.031; y += d) {
    for (double px = h; px < 0.05 - h; px += d) {
      x.insert(x.end(), {px, y, 0.0});
      v.insert(v.end(), {0.0, 0.0, 0.0});
    }
  }
  f.assign(x.size(), 0.0);
  fsi::contact::ContactSettings settings;
  settings.law = {17500.0, 1000.0, 2 * h, 2 * h};
  settings.refinement_resolution = 2 * h;
  fsi::contact::BoundaryMesh2D mesh{
      {0, 0.1, 0, 0, 0.05, 0, 0.05, 0.1}, std::vector<double>(8, 0.0), {0, 1, 1, 2, 2, 3}};
  fsi::contact::ParticleArrays particles;
  particles.count = x.size() / 3;
  particles.positions = x.data();
  particles.velocities = v.data();
  particles.forces = f.data();
  std::vector<double> vertex_forces(8);
  fsi::contact::WallContact2D contact(settings);
  for (auto _ : state) {
    benchmark::DoNotOptimize(contact.compute(mesh, particles, vertex_forces));
  }
  state.counters["particles"] = static_cast<double>(particles.count);
}
BENCHMARK(BM_ContactTank)->Arg(31)->Arg(81)->Unit(benchmark::kMicrosecond);

void BM_RadauStepStaticTank(benchmark::State& state) {
  fsi::mbd::Model model;
  model.set_gravity({0.0, -9.81});
  for (const char* name : {"bottom", "piston"}) {
    fsi::mbd::RigidBody2DSpec spec;
    spec.name = name;
    spec.mass = 0.1;
    spec.inertia = 2e-5;
    const auto body = model.add_rigid_body(spec);
    for (int k = 0; k < 4; ++k)
      model.add_marker(body, {0.01 * k, 0.001});
  }
  model.add_coordinate_constraint(0, fsi::mbd::Coordinate::X);
  model.add_coordinate_constraint(0, fsi::mbd::Coordinate::Y);
  model.add_coordinate_constraint(0, fsi::mbd::Coordinate::Angle);
  model.add_coordinate_constraint(1, fsi::mbd::Coordinate::X);
  model.add_coordinate_constraint(1, fsi::mbd::Coordinate::Angle);
  model.add_velocity_constraint(1, fsi::mbd::Coordinate::Y, 0.0);
  fsi::mbd::RadauIIA integrator(static_cast<int>(state.range(0)));
  fsi::mbd::State s = model.initial_state();
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> load(-1.0, 1.0);
  std::vector<double> loads(16);
  for (auto _ : state) {
    for (double& value : loads)
      value = load(rng);
    model.set_point_loads(loads);
    integrator.step(model, s, 5e-6);
  }
}
BENCHMARK(BM_RadauStepStaticTank)->Arg(1)->Arg(3)->Unit(benchmark::kMicrosecond);

void BM_StepMessageRoundTrip(benchmark::State& state) {
  fsi::protocol::Step step;
  step.step = 1;
  step.time = 2.5e-6;
  step.time_step = 2.5e-6;
  step.positions.assign(static_cast<std::size_t>(2 * state.range(0)), 0.5);
  step.velocities = step.positions;
  for (auto _ : state) {
    const auto payload = fsi::protocol::encode(step);
    benchmark::DoNotOptimize(fsi::protocol::decode(fsi::protocol::MessageType::Step, payload));
  }
  state.SetItemsProcessed(state.iterations() * state.range(0) * 4);
}
BENCHMARK(BM_StepMessageRoundTrip)->Arg(8)->Arg(10000);

}  // namespace

BENCHMARK_MAIN();
