#include "fsi/coupling/structure_side.hpp"

#include <spdlog/spdlog.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "fsi/common/error.hpp"
#include "fsi/mbd/readouts.hpp"

namespace fsi::coupling {
namespace {

std::string step_and_time(std::uint64_t step, double time) {
  char text[96];
  std::snprintf(text, sizeof text, "step %llu (t = %.9g s)", static_cast<unsigned long long>(step),
                time);
  return text;
}

// The first non-finite entry of the state, named by body where possible.
std::string non_finite_entry(const mbd::Model& model, const mbd::State& state) {
  for (int b = 0; b < model.body_count(); ++b) {
    try {
      for (const mbd::Coordinate c :
           {mbd::Coordinate::X, mbd::Coordinate::Y, mbd::Coordinate::Angle}) {
        const int i = model.coordinate_index(b, c);
        if (!std::isfinite(state.q(i)) || !std::isfinite(state.v(i))) {
          return "body '" + model.body(b).name + "' coordinate " + std::string(mbd::name(c));
        }
      }
    } catch (const Error&) {
      // not a planar rigid body: named by index below
    }
  }
  for (int i = 0; i < state.q.size(); ++i) {
    if (!std::isfinite(state.q(i)) || !std::isfinite(state.v(i))) {
      return model.coordinate_description(i);
    }
  }
  for (int k = 0; k < model.constraint_count(); ++k) {
    if (!std::isfinite(state.lambda(k))) return "multiplier of " + model.constraint_description(k);
  }
  return "the state";
}

bool finite(const mbd::State& state) {
  return state.q.allFinite() && state.v.allFinite() && state.lambda.allFinite();
}

}  // namespace

int advance_in_substeps(const std::function<void(mbd::State&, double)>& take_step,
                        mbd::State& state, double step_size, int max_substeps,
                        const std::string& held, std::string* whole_step_failure) {
  const mbd::State start = state;
  std::string tried;
  if (whole_step_failure) whole_step_failure->clear();
  for (int substeps = 1;; substeps *= 2) {
    try {
      for (int k = 0; k < substeps; ++k)
        take_step(state, step_size / substeps);
      return substeps;
    } catch (const Error& failure) {
      state = start;
      if (substeps == 1 && whole_step_failure) *whole_step_failure = failure.fault();
      tried += (tried.empty() ? std::string() : std::string(", ")) + std::to_string(substeps);
      if (2 * substeps > max_substeps) {
        throw Error(std::string(failure.fault()) + " (the step failed as " + tried + " substeps" +
                        held + "; the limit is " + std::to_string(max_substeps) + ")",
                    std::string(failure.location()), std::string(failure.remedy()));
      }
    }
  }
}

std::string constraint_drift_warning(std::optional<double> drift, mbd::ConstraintForm form) {
  if (!drift || !(*drift > kConstraintDriftWarning)) return {};
  char text[160];
  std::snprintf(text, sizeof text,
                "the position constraints ended %.3g off (m or rad; more than %g): the joints "
                "and drives did not hold",
                *drift, kConstraintDriftWarning);
  return std::string(text) +
         (form == mbd::ConstraintForm::Index2
              ? "; with constraint_form = \"index2\" the positions follow the rates, so a "
                "drive whose rate is not the derivative of its position, or a long run, carries "
                "them off: check the rates, or use constraint_form = \"index3\" "
                "(docs/theory.md, \"Index-2 form of the constraints\")"
              : "; check the Newton tolerance (SolverOptions.Newton.relative_tolerance) and "
                "the step size");
}

StructureSide::StructureSide(scene::Scene& scene, scene::IntegrationMethod method, bool coupled)
    : scene_(scene),
      method_(method),
      held_(coupled ? " with the fluid forces held" : ""),
      state_(scene.model.initial_state()),
      integrator_(scene.solver.integrator_options()),
      crossing_(scene, state_),
      works_(scene.sensors.size(), 0.0) {
  for (const std::string& pair : crossing_.excluded_pairs()) {
    spdlog::info(
        "mesh crossing check: the meshes of {} (they touch or cross at t = 0; a Contact block "
        "between them would act)",
        pair);
  }
  const scene::SolverSettings& solver = scene.solver;
  if (method == scene::IntegrationMethod::AdaptiveRadau) {
    adaptive_ = std::make_unique<mbd::AdaptiveRadau>(
        solver.integrator_options(),
        mbd::AdaptiveOptions{.relative_tolerance = solver.relative_tolerance,
                             .absolute_tolerance = solver.absolute_tolerance,
                             .initial_step = solver.step_size,
                             .max_step = solver.max_step});
  } else if (method == scene::IntegrationMethod::Ida) {
    ida_ = std::make_unique<mbd::IdaIntegrator>(
        mbd::IdaOptions{.relative_tolerance = solver.relative_tolerance,
                        .absolute_tolerance = solver.absolute_tolerance,
                        .max_step = solver.max_step});
  }
  // The work sensors' powers, integrated by the integrator over each of its own steps.
  mbd::Integrand works = work_integrand();
  step_work_.setZero(works.size);
  if (adaptive_) {
    adaptive_->set_integrand(std::move(works));
  } else if (ida_) {
    ida_->set_integrand(std::move(works));
  } else {
    integrator_.set_integrand(std::move(works));
  }
}

void StructureSide::integrate_to(double end_time, double step_size) {
  switch (method_) {
    case scene::IntegrationMethod::FixedStep: {
      std::string why;
      const double start = state_.time;
      // With work sensors, every step's integral, the failed attempts' included: the last
      // `substeps` are the step's (without them nothing is kept: no allocation per step).
      const bool integrates = step_work_.size() > 0;
      std::vector<Eigen::VectorXd> pieces;
      const int substeps = advance_in_substeps(
          [this, &pieces, integrates](mbd::State& state, double h) {
            integrator_.step(scene_.model, state, h);
            if (integrates) pieces.push_back(integrator_.last_step_integral());
          },
          state_, step_size, kMaxStructureSubsteps, held_, &why);
      if (integrates) {
        step_work_.setZero();
        for (std::size_t k = pieces.size() - static_cast<std::size_t>(substeps); k < pieces.size();
             ++k)
          step_work_ += pieces[k];
      }
      if (substeps > 1) {
        if (substepped_steps_ == 0) {
          spdlog::warn(
              "t = {:.9g} s: the multibody Newton iteration failed on the whole step of {:g} s "
              "and converged in {} substeps of {:g} s{} (later such steps are counted in "
              "run.json, newton.substepped_steps); the whole step's failure: {}",
              start, step_size, substeps, step_size / substeps, held_, why);
        }
        ++substepped_steps_;
      }
      return;
    }
    case scene::IntegrationMethod::AdaptiveRadau:
      adaptive_->advance(scene_.model, state_, end_time);
      step_work_ = adaptive_->last_advance_integral();
      return;
    case scene::IntegrationMethod::Ida:
      ida_->advance(scene_.model, state_, end_time);
      step_work_ = ida_->last_advance_integral();
      return;
  }
}

mbd::IntegratorStatistics StructureSide::statistics() const {
  mbd::IntegratorStatistics totals;
  switch (method_) {
    case scene::IntegrationMethod::FixedStep:
      totals = integrator_.statistics();
      totals.substepped_steps = substepped_steps_;
      return totals;
    case scene::IntegrationMethod::AdaptiveRadau: {
      const mbd::AdaptiveStatistics& adaptive = adaptive_->statistics();
      totals.steps = adaptive.accepted;
      totals.newton_iterations = adaptive.newton_iterations;
      totals.jacobian_evaluations = adaptive.jacobian_evaluations;
      totals.factorisations = adaptive.factorisations;
      totals.retries = adaptive.rejected;
      return totals;
    }
    case scene::IntegrationMethod::Ida: {
      const mbd::IdaStatistics ida = ida_->statistics();
      totals.steps = ida.steps;
      totals.newton_iterations = ida.newton_iterations;
      totals.jacobian_evaluations = ida.jacobian_evaluations;
      totals.factorisations = ida.jacobian_evaluations;  // one dense LU per Jacobian
      totals.retries = ida.error_test_failures + ida.convergence_failures;
      return totals;
    }
  }
  return totals;
}

mbd::Integrand StructureSide::work_integrand() const {
  std::vector<int> elements;
  for (const scene::SensorSpec& sensor : scene_.sensors) {
    if (sensor.type == scene::SensorType::Work) elements.push_back(sensor.force_element);
  }
  if (elements.empty()) return {};
  const mbd::Model& model = scene_.model;
  return {static_cast<int>(elements.size()),
          [&model, elements](const mbd::State& state, Eigen::VectorXd& powers) {
            for (std::size_t k = 0; k < elements.size(); ++k)
              powers(static_cast<Eigen::Index>(k)) =
                  mbd::force_element_power(model, state, elements[k]);
          }};
}

void StructureSide::advance(std::uint64_t step, double step_size) {
  const bool multi_rate = scene_.solver.substeps > 1;
  StepStart start;
  if (multi_rate) {
    start.time = state_.time;
    boundary_state(start.positions, start.velocities);
    trim_to_dynamic(start.positions, start.velocities);
  }
  // A model without bodies (a static 3D container) has nothing to integrate.
  if (scene_.model.coordinate_count() > 0) {
    try {
      integrate_to(static_cast<double>(step) * step_size, step_size);
    } catch (const Error& failure) {
      throw Error(failure.fault(),
                  step_and_time(step, state_.time) + ", " + std::string(failure.location()),
                  failure.remedy());
    }
    if (!finite(state_)) {
      throw Error("the multibody state is not finite: " + non_finite_entry(scene_.model, state_),
                  step_and_time(step, static_cast<double>(step) * step_size),
                  "check the scene's forces and constraints for that element");
    }
  }
  state_.time = static_cast<double>(step) * step_size;
  if (step_work_.size() > 0) {
    Eigen::Index k = 0;
    for (std::size_t s = 0; s < scene_.sensors.size(); ++s) {
      if (scene_.sensors[s].type == scene::SensorType::Work) works_[s] += step_work_(k++);
    }
  }
  if (multi_rate) record_step_motion(start, step_size);
  try {
    crossing_.check(state_);
  } catch (const Error& crossing) {
    throw Error(crossing.fault(),
                step_and_time(step, state_.time) + ", " + std::string(crossing.location()),
                crossing.remedy());
  }
}

void StructureSide::trim_to_dynamic(std::vector<double>& positions,
                                    std::vector<double>& velocities) const {
  const std::size_t dynamic_values =
      static_cast<std::size_t>(scene_.dimension) * scene_.boundary.dynamic_vertex_count;
  positions.resize(dynamic_values);
  velocities.resize(dynamic_values);
}

void StructureSide::record_step_motion(const StepStart& start, double step_size) {
  StepMotionData& motion = step_motion_;
  motion.nodes.clear();
  motion.positions.clear();
  motion.velocities.clear();
  const mbd::StepStages& stages = integrator_.last_step_stages();
  // The stages cover the whole step unless it was taken in Newton substeps or split at a
  // release (their start then lies inside it): then the step's two ends only (cubic Hermite).
  const bool whole_step =
      scene_.model.coordinate_count() > 0 && method_ == scene::IntegrationMethod::FixedStep &&
      stages.step_size == step_size && stages.start_time == start.time && stages.nodes.size() >= 2;
  if (!whole_step && two_node_steps_++ == 0 && scene_.model.coordinate_count() > 0) {
    spdlog::info(
        "t = {:.9g} s: the structure step was taken in Newton substeps or split at a release; "
        "the fluid's walls follow its two ends (cubic Hermite) instead of its stages (later "
        "such steps likewise, not logged)",
        state_.time);
  }
  const std::vector<double> theta = whole_step ? stages.nodes : std::vector<double>{0.0, 1.0};
  std::vector<double> positions, velocities;
  for (std::size_t i = 0; i < theta.size(); ++i) {
    if (i == 0) {
      positions = start.positions;
      velocities = start.velocities;
    } else if (i + 1 == theta.size()) {
      // The end exactly as boundary_motion() gives it.
      boundary_state(positions, velocities);
      trim_to_dynamic(positions, velocities);
    } else {
      const mbd::State node{start.time + theta[i] * step_size, stages.positions[i],
                            stages.velocities[i], state_.lambda};
      scene::boundary_state(scene_.boundary, scene_.model, node, positions, velocities);
      trim_to_dynamic(positions, velocities);
    }
    motion.nodes.push_back(theta[i]);
    motion.positions.insert(motion.positions.end(), positions.begin(), positions.end());
    motion.velocities.insert(motion.velocities.end(), velocities.begin(), velocities.end());
  }
}

BoundaryMotion StructureSide::boundary_motion(std::uint64_t step, double step_size) const {
  BoundaryMotion motion;
  motion.step = step;
  motion.time = state_.time;
  motion.time_step = step_size;
  boundary_state(motion.positions, motion.velocities);
  const std::size_t dynamic_values =
      static_cast<std::size_t>(scene_.dimension) * scene_.boundary.dynamic_vertex_count;
  motion.positions.resize(dynamic_values);
  motion.velocities.resize(dynamic_values);
  if (scene_.solver.substeps > 1 && step > 0) {
    motion.substeps = static_cast<std::uint32_t>(scene_.solver.substeps);
    motion.nodes = step_motion_.nodes;
    motion.node_positions = step_motion_.positions;
    motion.node_velocities = step_motion_.velocities;
  }
  // The probes are evaluated after the steps that are multiples of the sensor interval.
  if (!scene_.attached_probes.empty() &&
      step % static_cast<std::uint64_t>(scene_.output.sensor_every_steps) == 0) {
    const std::vector<probes::ProbeDefinition> placed = scene::placed_probes(scene_, state_);
    for (std::size_t k = 0; k < placed.size(); ++k) {
      motion.probe_placements.push_back(
          {static_cast<std::uint32_t>(scene_.attached_probes[k].probe), placed[k].parameters});
    }
  }
  return motion;
}

void StructureSide::boundary_state(std::vector<double>& positions,
                                   std::vector<double>& velocities) const {
  scene::boundary_state(scene_.boundary, scene_.model, state_, positions, velocities);
}

void StructureSide::apply_vertex_forces(std::span<const double> forces, std::uint64_t step) {
  const auto dimension = static_cast<std::size_t>(scene_.dimension);
  const std::size_t dynamic_values = dimension * scene_.boundary.dynamic_vertex_count;
  if (forces.size() != dynamic_values) {
    throw Error("Forces carry " + std::to_string(forces.size() / dimension) +
                    " vertices, the mesh has " +
                    std::to_string(scene_.boundary.dynamic_vertex_count) + " dynamic ones",
                "step " + std::to_string(step), "use matching fsi-server and fsi-client releases");
  }
  for (double f : forces) {
    if (!std::isfinite(f)) {
      throw Error("the fluid forces of step " + std::to_string(step) + " are not finite",
                  "fluid side",
                  "reduce the time step or the contact stiffness k (see the thesis' §6.2 rules)");
    }
  }
  // One load per marker: in 2D every vertex is a marker (the ground ones carry none), in 3D
  // only the dynamic vertices are.
  loads_.assign(dimension * static_cast<std::size_t>(scene_.model.marker_count()), 0.0);
  std::copy(forces.begin(), forces.end(), loads_.begin());
  scene_.model.set_point_loads(loads_);
}

std::vector<double> StructureSide::sensor_readout(
    const std::array<double, 3>& total_fluid_force) const {
  return readout(state_, total_fluid_force);
}

std::vector<double> StructureSide::initial_sensor_readout(
    const std::array<double, 3>& total_fluid_force) const {
  // initial_state() solves the multipliers with the point loads now set on the model.
  return readout(scene_.model.initial_state(), total_fluid_force);
}

std::vector<double> StructureSide::readout(const mbd::State& state,
                                           const std::array<double, 3>& total_fluid_force) const {
  std::vector<double> values;
  values.reserve(scene_.sensors.size());
  for (std::size_t k = 0; k < scene_.sensors.size(); ++k) {
    const scene::SensorSpec& sensor = scene_.sensors[k];
    switch (sensor.type) {
      case scene::SensorType::TotalFluidForce:
        values.push_back(total_fluid_force[static_cast<std::size_t>(sensor.axis)]);
        break;
      case scene::SensorType::Work:
        values.push_back(works_[k]);
        break;
      default:
        values.push_back(scene::structure_sensor_value(scene_.model, sensor, state));
    }
  }
  return values;
}

void StructureSide::save_state(output::StateWriter& out) {
  if (method_ != scene::IntegrationMethod::FixedStep) {
    throw Error("a checkpoint of an error-controlled integration (adaptive Radau IIA or IDA)",
                "structure side", "checkpoints are taken in coupled runs (fixed step) only");
  }
  out.section("structure");
  out.put(state_.time);
  out.put(state_.q);
  out.put(state_.v);
  out.put(state_.lambda);
  out.put(loads_);
  out.put(step_motion_.nodes);
  out.put(step_motion_.positions);
  out.put(step_motion_.velocities);
  out.put(two_node_steps_);
  out.put(substepped_steps_);
  out.put(works_);
  const mbd::IntegratorStatistics& totals = integrator_.statistics();
  for (std::uint64_t value : {totals.steps, totals.newton_iterations, totals.jacobian_evaluations,
                              totals.factorisations, totals.retries})
    out.put(value);
  integrator_.reset();
}

void StructureSide::restore_state(output::StateReader& in) {
  in.section("structure");
  const auto n = static_cast<Eigen::Index>(scene_.model.coordinate_count());
  const auto m = static_cast<Eigen::Index>(scene_.model.constraint_count());
  state_.time = in.f64("time");
  state_.q = in.vector("coordinates q", n);
  state_.v = in.vector("velocities v", n);
  state_.lambda = in.vector("multipliers", m);
  loads_ = in.doubles("point loads");
  const std::size_t markers = static_cast<std::size_t>(scene_.dimension) *
                              static_cast<std::size_t>(scene_.model.marker_count());
  if (!loads_.empty() && loads_.size() != markers) {
    throw Error("the checkpoint holds " + std::to_string(loads_.size()) +
                    " point load values, the scene's markers take " + std::to_string(markers),
                "structure state", "resume with the scene that wrote the checkpoint");
  }
  if (!loads_.empty()) scene_.model.set_point_loads(loads_);
  step_motion_.nodes = in.doubles("step nodes");
  step_motion_.positions = in.doubles("step node positions");
  step_motion_.velocities = in.doubles("step node velocities");
  two_node_steps_ = in.u64("two-node steps");
  substepped_steps_ = in.u64("substepped steps");
  works_ = in.doubles("work sensors' sums");
  if (works_.size() != scene_.sensors.size()) {
    throw Error("the checkpoint holds " + std::to_string(works_.size()) +
                    " sensors' work sums, the scene has " + std::to_string(scene_.sensors.size()) +
                    " sensors",
                "structure state", "resume with the scene that wrote the checkpoint");
  }
  mbd::IntegratorStatistics totals;
  totals.steps = in.u64("integrator steps");
  totals.newton_iterations = in.u64("Newton iterations");
  totals.jacobian_evaluations = in.u64("Jacobians");
  totals.factorisations = in.u64("factorisations");
  totals.retries = in.u64("retries");
  integrator_.set_statistics(totals);
  integrator_.reset();
}

std::optional<double> StructureSide::position_constraint_drift() const {
  if (!finite(state_)) return std::nullopt;
  return mbd::position_constraint_drift(scene_.model, state_);
}

std::optional<double> StructureSide::velocity_constraint_drift() const {
  if (!finite(state_)) return std::nullopt;
  return mbd::velocity_constraint_drift(scene_.model, state_);
}

}  // namespace fsi::coupling
