#pragma once
// An in-process fluid side for tests of the session loop: no LIGGGHTS, no TCP. Its forces on the
// dynamic vertices follow a law of the boundary's motion (a constant by default); it can be told
// to fail at a step, and it records every call the loop makes.

#include <cstdint>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "fsi/common/error.hpp"
#include "fsi/coupling/fluid_side.hpp"

namespace fsi::coupling::testing {

class FakeFluidSide final : public FluidSide {
 public:
  using ForceLaw = std::function<std::vector<double>(const BoundaryMotion&)>;

  // Every dynamic vertex feels `per_vertex` (dimension values).
  static ForceLaw constant(std::vector<double> per_vertex) {
    return [per_vertex](const BoundaryMotion& motion) {
      std::vector<double> forces(motion.positions.size());
      for (std::size_t i = 0; i < forces.size(); ++i)
        forces[i] = per_vertex[i % per_vertex.size()];
      return forces;
    };
  }

  FakeFluidSide(int dimension, ForceLaw law) : dimension_(dimension), law_(std::move(law)) {}

  std::optional<std::uint64_t> fail_at_step;  // exchange of this step throws
  bool fail_in_equilibration = false;
  std::uint64_t particle_count = 0;  // 0: as many as the scene generates
  // Reports FluidHealth (protocol 1.3) with every Forces: a fluid at rest at the scene's density,
  // with `non_finite_particles` NaN particles at step `nan_at_step`.
  bool report_health = false;
  std::optional<std::uint64_t> nan_at_step;
  std::uint64_t non_finite_particles = 1;

  // What the loop did.
  int set_up_calls = 0;
  std::size_t set_up_vertex_values = 0;
  int equilibrate_calls = 0;
  std::vector<BoundaryMotion> exchanges;
  std::vector<std::uint64_t> snapshot_steps;
  int finish_calls = 0;
  std::vector<std::string> reported_faults;
  std::vector<bool> faults_during_coupled_steps;

  void set_up(const scene::Scene& scene, const std::vector<double>& positions,
              const std::vector<double>& velocities) override {
    ++set_up_calls;
    set_up_vertex_values = positions.size();
    if (particle_count == 0) particle_count = scene.fluid.count();
    density_ = scene.fluid.density;
    probe_columns_ = 0;
    for (const auto& probe : scene.probes)
      probe_columns_ += probes::columns(probe, scene.dimension).size();
    const auto dynamic_values =
        static_cast<long>(dimension_) * static_cast<long>(scene.boundary.dynamic_vertex_count);
    initial_.positions.assign(positions.begin(), positions.begin() + dynamic_values);
    initial_.velocities.assign(velocities.begin(), velocities.begin() + dynamic_values);
  }

  FluidReady equilibrate() override {
    ++equilibrate_calls;
    if (fail_in_equilibration)
      throw Error("the fake fluid does not settle", "fake fluid side", "nothing to fix");
    FluidReady ready;
    ready.particle_count = particle_count;
    ready.liggghts_version = "fake";
    ready.initial_forces = forces_for(initial_);
    return ready;
  }

  FluidForces exchange(const BoundaryMotion& motion) override {
    exchanges.push_back(motion);
    // A fluid with a memory: the forces lag the boundary's motion by a first-order filter, so
    // that a resume that lost the fluid's state would not continue the same way.
    double sum = 0.0;
    for (double x : motion.positions)
      sum += x;
    memory_ = 0.9 * memory_ + 0.1 * sum;
    if (lose_at_step && motion.step == *lose_at_step) {
      lose_at_step.reset();  // once: the fluid "started again" is healthy
      throw LostFluid("the fake fluid's process is gone at step " + std::to_string(motion.step));
    }
    if (fail_at_step && motion.step == *fail_at_step) {
      throw Error("the fake fluid fails at step " + std::to_string(motion.step), "fake fluid side",
                  "nothing to fix");
    }
    return forces_for(motion);
  }

  ParticleSnapshot snapshot(std::uint64_t step) override {
    snapshot_steps.push_back(step);
    ParticleSnapshot snapshot;
    snapshot.step = step;
    snapshot.time = exchanges.empty() ? 0.0 : exchanges.back().time;
    snapshot.dimension = dimension_;
    snapshot.ids = {1, 2};
    snapshot.positions.assign(2 * static_cast<std::size_t>(dimension_), 0.01);
    snapshot.velocities.assign(2 * static_cast<std::size_t>(dimension_), 0.0);
    snapshot.density = {1000.0, 1000.0};
    snapshot.pressure = {0.0, 0.0};
    return snapshot;
  }

  void finish() override { ++finish_calls; }

  // Checkpoints: the fake fluid's state is its memory, bit for bit.
  bool can_checkpoint() const override { return checkpoints_supported; }
  std::string checkpoint(std::uint64_t step) override {
    checkpoint_steps.push_back(step);
    return std::string(reinterpret_cast<const char*>(&memory_), sizeof memory_);
  }
  FluidReady resume(const scene::Scene& scene, const std::vector<double>& positions,
                    const std::vector<double>& velocities, std::uint64_t step, double time,
                    std::string_view state) override {
    ++resume_calls;
    resumed_at = {step, time};
    set_up(scene, positions, velocities);
    --set_up_calls;
    if (state.size() != sizeof memory_)
      throw Error("the fake fluid's state has the wrong size", "fake fluid side", "none");
    std::copy(state.begin(), state.end(), reinterpret_cast<char*>(&memory_));
    FluidReady ready;
    ready.particle_count = particle_count;
    ready.liggghts_version = "fake";
    return ready;
  }
  bool checkpoints_supported = true;
  // The exchange of this step throws LostFluid once, which peer_lost() recognises.
  std::optional<std::uint64_t> lose_at_step;
  struct LostFluid : std::runtime_error {
    using std::runtime_error::runtime_error;
  };
  bool peer_lost(const std::exception& failure) const override {
    return dynamic_cast<const LostFluid*>(&failure) != nullptr;
  }
  // How much the fluid's memory (a filtered sum of the boundary positions) adds to every force
  // value; 0: a fluid without memory.
  double memory_coupling = 0.0;
  std::vector<std::uint64_t> checkpoint_steps;
  int resume_calls = 0;
  std::pair<std::uint64_t, double> resumed_at{};

  void report_fault(const std::exception& failure, bool during_coupled_steps) noexcept override {
    reported_faults.emplace_back(failure.what());
    faults_during_coupled_steps.push_back(during_coupled_steps);
  }

 private:
  FluidForces forces_for(const BoundaryMotion& motion) const {
    FluidForces result;
    result.forces = law_(motion);
    for (double& f : result.forces)
      f += memory_coupling * memory_;
    for (std::size_t i = 0; i < result.forces.size(); ++i) {
      result.diagnostics.force_on_structure[i % static_cast<std::size_t>(dimension_)] +=
          result.forces[i];
    }
    for (int k = 0; k < 3; ++k)
      result.diagnostics.force_on_fluid[k] = -result.diagnostics.force_on_structure[k];
    result.diagnostics.particle_count = particle_count;
    result.probe_values.assign(probe_columns_, memory_);  // the probes read the memory
    result.diagnostics.closest_approach_over_r0 = 1.0;
    if (report_health) {
      protocol::FluidHealth health;
      health.step = motion.step;
      health.particle_count = particle_count;
      health.non_finite_particles =
          nan_at_step && motion.step == *nan_at_step ? non_finite_particles : 0;
      health.min_density = health.max_density = density_;
      result.health = health;
    }
    return result;
  }

  int dimension_;
  ForceLaw law_;
  BoundaryMotion initial_;  // the dynamic vertices at set-up (step 0)
  double density_ = 0.0;    // the scene's rho0
  double memory_ = 0.0;     // the filtered sum of the boundary positions
  std::size_t probe_columns_ = 0;
};

}  // namespace fsi::coupling::testing
