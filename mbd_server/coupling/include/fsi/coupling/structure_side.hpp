#pragma once
// The structure as the coupling loop sees it: the scene's multibody model with its state and
// integrator. It advances one step with the fluid forces of the previous exchange held constant
// (thesis Fig. 4.10), tells where the boundary vertices are, takes the fluid's vertex forces as
// point loads, and reads the scene's sensors. Coupled and --mbd-only runs use the same one; a
// coupled run integrates with the fixed step, an --mbd-only run with the scene's method (fixed
// step, adaptive Radau IIA or IDA, landing on every output step).

#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "fsi/coupling/fluid_side.hpp"
#include "fsi/mbd/adaptive_radau.hpp"
#include "fsi/mbd/ida.hpp"
#include "fsi/mbd/integrator.hpp"
#include "fsi/output/state_archive.hpp"
#include "fsi/scene/mesh_crossing.hpp"
#include "fsi/scene/scene.hpp"

namespace fsi::coupling {

// How many equal substeps the structure may split one coupled step into when its Newton
// iteration fails on the whole step (2, 4, ... up to this), the fluid's forces held as they are.
inline constexpr int kMaxStructureSubsteps = 16;

// Advances `state` by `step_size` with `take_step`, which takes one multibody step of the size
// it is given and throws fsi::Error, leaving the state as it was, when its Newton iteration
// fails. A failed step is taken again from the same start as 2, 4, ... equal substeps, up to
// `max_substeps`; returns the number of substeps used (1: the step as given). When
// `max_substeps` substeps fail too, throws the last failure with the substep counts tried
// (and `held`, what the substeps keep constant: " with the fluid forces held") added, and
// `state` is the start again. `whole_step_failure`, if given, receives why the whole step failed
// (the fault of its Newton iteration; empty when it did not).
int advance_in_substeps(const std::function<void(mbd::State&, double)>& take_step,
                        mbd::State& state, double step_size,
                        int max_substeps = kMaxStructureSubsteps,
                        const std::string& held = " with the fluid forces held",
                        std::string* whole_step_failure = nullptr);

// Position constraints farther off than this at the end of a run [m or rad] are reported (the
// index-3 form holds them to round-off, index 2 drifts by the integration error, 5e-10 m over
// two pendulum periods at h = 1e-2 s).
inline constexpr double kConstraintDriftWarning = 1e-6;

// The warning for a run whose position constraints ended `drift` off, empty when within
// kConstraintDriftWarning (a user's index-2 spin-up with a drive rate wrong for 2 s of 30 ended
// 0.11 rad off its prescribed angle, with nothing said).
std::string constraint_drift_warning(std::optional<double> drift, mbd::ConstraintForm form);

class StructureSide {
 public:
  // Starts from the model's initial state at t = 0. `coupled`: a fluid loads it (messages say
  // its forces are held over a step; --mbd-only has none).
  StructureSide(scene::Scene& scene, scene::IntegrationMethod method, bool coupled = true);

  // Integrates from t(step - 1) to t(step) = step * step_size (the clock does not drift over
  // many steps); an error-controlled method takes the steps its tolerances need in between. The
  // fixed step retries a step whose Newton iteration fails as 2, 4, ... kMaxStructureSubsteps
  // substeps (advance_in_substeps; logged the first time, counted in statistics()). Throws
  // fsi::Error naming the step and time when Newton fails or the state becomes non-finite; the
  // state is then the last good one. Also throws when two meshes without contact between them
  // cross (scene::CrossingWatch; the pairs touching at the start are logged and not watched).
  // Adds each `work` sensor's element power integrated over the step by the integrator itself
  // (fsi/mbd/integrand.hpp: the tableau's quadrature on the stages of each of its steps, IDAS'
  // quadrature).
  void advance(std::uint64_t step, double step_size);

  // The dynamic vertices at the current state, for the fluid, and on a probe step the probes that
  // move with a body. With SolverOptions.Timeint.substeps > 1 (multi-rate coupling; `step` is
  // then the fluid step at the end of the last structure step and `step_size` the fluid's step)
  // also the dynamic vertices at that structure step's nodes: its start and its stages
  // (RadauIIA::last_step_stages), or its two ends when Newton substeps or a release split it.
  BoundaryMotion boundary_motion(std::uint64_t step, double step_size) const;
  // Multi-rate structure steps whose motion had only their two ends (see above).
  std::uint64_t two_node_steps() const { return two_node_steps_; }
  // Every boundary vertex (static ones too), dimension values each.
  void boundary_state(std::vector<double>& positions, std::vector<double>& velocities) const;

  // Forces on the dynamic vertices (dimension values each), held as point loads over the next
  // step. Throws fsi::Error if their count does not match the mesh or one is not finite.
  void apply_vertex_forces(std::span<const double> forces, std::uint64_t step);
  // One load per marker (static 2D vertices carry zero), as applied.
  std::span<const double> vertex_loads() const { return loads_; }

  // The scene's sensors at the current state, in the scene's order. total_fluid_force is the
  // fluid's force on every boundary (walls included), which only the fluid side knows.
  std::vector<double> sensor_readout(const std::array<double, 3>& total_fluid_force) const;
  // The same at t = 0, before the first step, with the multipliers consistent with the loads
  // applied by then (the fluid's forces on the initial configuration); the state the first step
  // starts from keeps its own.
  std::vector<double> initial_sensor_readout(const std::array<double, 3>& total_fluid_force) const;

  // Checkpoints (issue 16; docs/user-guide.md, "Checkpoints and resume"): the state, the point
  // loads held over the next step, the last step's motion, the work sensors' sums and the
  // statistics, bit for bit.
  // save_state also drops the integrator's kept Newton matrix, so that the next step is the same
  // whether this process goes on or a resumed one does. Only the fixed-step method of coupled
  // runs is checkpointed; restore_state throws fsi::Error when the state does not fit the scene.
  void save_state(output::StateWriter& out);
  void restore_state(output::StateReader& in);

  const mbd::State& state() const { return state_; }
  double time() const { return state_.time; }
  // Steps, Newton iterations, Jacobians, factorisations and rejected or retried steps of
  // whichever integrator runs, and the coupled steps taken in substeps.
  mbd::IntegratorStatistics statistics() const;
  // Constraint drift of the current state; none when the state is not finite.
  std::optional<double> position_constraint_drift() const;
  std::optional<double> velocity_constraint_drift() const;

 private:
  void integrate_to(double end_time, double step_size);
  struct StepStart {
    double time = 0.0;
    std::vector<double> positions, velocities;  // dynamic vertices
  };
  void record_step_motion(const StepStart& start, double step_size);
  void trim_to_dynamic(std::vector<double>& positions, std::vector<double>& velocities) const;
  std::vector<double> readout(const mbd::State& state,
                              const std::array<double, 3>& total_fluid_force) const;
  // The power of each `work` sensor's element (scene order) as the integrators' integrand.
  mbd::Integrand work_integrand() const;

  scene::Scene& scene_;
  scene::IntegrationMethod method_;
  std::string held_;  // what a substepped step keeps constant, for messages
  mbd::State state_;
  mbd::RadauIIA integrator_;
  std::unique_ptr<mbd::AdaptiveRadau> adaptive_;
  std::unique_ptr<mbd::IdaIntegrator> ida_;
  std::vector<double> loads_;
  scene::CrossingWatch crossing_;
  std::uint64_t substepped_steps_ = 0;
  // The work_integrand()'s integral over the last integrate_to (empty without work sensors).
  Eigen::VectorXd step_work_;
  // The last structure step's nodes and dynamic vertices there (multi-rate coupling).
  struct StepMotionData {
    std::vector<double> nodes, positions, velocities;
  };
  StepMotionData step_motion_;
  std::uint64_t two_node_steps_ = 0;
  // Per sensor (zero but for `work` sensors): the element's work since t = 0.
  std::vector<double> works_;
};

}  // namespace fsi::coupling
