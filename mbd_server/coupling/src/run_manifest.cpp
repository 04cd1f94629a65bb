#include "fsi/coupling/run_manifest.hpp"

#include <algorithm>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "fsi/common/error.hpp"
#include "fsi/common/version.hpp"
#include "fsi/output/atomic_file.hpp"
#include "fsi/protocol/frame.hpp"

namespace fsi::coupling {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

std::uint64_t fnv1a(const std::string& text) {
  std::uint64_t hash = 1469598103934665603ull;
  for (unsigned char c : text) {
    hash ^= c;
    hash *= 1099511628211ull;
  }
  return hash;
}

std::string hex(std::uint64_t value) {
  char text[24];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(value));
  return text;
}

json optional_number(const std::optional<double>& value) {
  return value ? json(*value) : json(nullptr);
}

json scene_entry(const scene::Scene& scene) {
  std::ifstream scene_file(scene.file);
  std::stringstream scene_text;
  scene_text << scene_file.rdbuf();
  return {{"file", fs::absolute(scene.file).string()}, {"fnv1a64", hex(fnv1a(scene_text.str()))}};
}

json model_entry(const scene::Scene& scene, RunMode mode) {
  json bodies = json::array();
  const mbd::Model& model = scene.model;
  for (int b = 0; b < model.body_count(); ++b) {
    json body = {
        {"name", model.body_name(b)}, {"type", model.body_kind(b)}, {"mass", model.body_mass(b)}};
    if (model.body_kind(b) == "rigid_body_2d") body["inertia"] = model.body(b).inertia;
    if (model.is_beam(b)) body["elements"] = model.beam(b).element_count;
    if (model.body_kind(b) == "ancf_cable") body["elements"] = model.cable(b).element_count;
    bodies.push_back(body);
  }
  // One component per dimension: scene.gravity holds all three (z = 0 in 2D).
  json gravity = json::array();
  for (int k = 0; k < scene.dimension; ++k)
    gravity.push_back(scene.gravity[static_cast<std::size_t>(k)]);
  return {{"gravity", gravity},
          {"bodies", bodies},
          {"constraints", model.constraint_count()},
          {"integrator", scene.solver.integrator_description(mode == RunMode::Coupled)}};
}

json mesh_entry(const scene::Scene& scene) {
  return {{"vertices", scene.boundary.vertex_count},
          {"dynamic_vertices", scene.boundary.dynamic_vertex_count},
          {scene.dimension == 3 ? "triangles" : "segments", scene.boundary.element_count()},
          {"refinement_resolution", scene.boundary.refinement_resolution}};
}

// Each wavemaker's waves (scene.hpp, PaddleWave): what was asked, what linear theory made of it,
// and every component of the paddle's motion, so that a script rebuilds the motion and the
// target sea from the run alone (examples/wave_flume/spectrum.py).
json wavemakers_entry(const scene::Scene& scene) {
  json wavemakers = json::array();
  for (const scene::PlacedWavemaker& placed : scene.wavemakers) {
    const scene::PaddleWave& wave = placed.wave;
    json omega = json::array(), height = json::array(), half_stroke = json::array(),
         phase = json::array();
    for (const scene::WaveComponent& component : wave.components) {
      omega.push_back(component.omega);
      height.push_back(component.height);
      half_stroke.push_back(component.half_stroke);
      phase.push_back(component.phase);
    }
    const bool irregular = wave.spectrum != "regular";
    wavemakers.push_back(
        {{"name", placed.name.empty() ? json(nullptr) : json(placed.name)},
         {"body", placed.body},
         {"kind", wave.flap() ? "flap" : "piston"},
         {"hinge_depth", wave.flap() ? json(wave.hinge_depth) : json(nullptr)},
         {"spectrum", wave.spectrum},
         {"height", wave.height},
         {"period", wave.period},
         {"depth", wave.depth},
         {"peak_enhancement", irregular ? json(wave.peak_enhancement) : json(nullptr)},
         {"wavelength", wave.wavelength},
         {"stroke", wave.stroke},
         {"largest_offset", wave.largest_offset},
         {"ramp_time", wave.ramp_time},
         {"repeat_period", wave.repeat_period},
         {"components",
          {{"omega", omega}, {"height", height}, {"half_stroke", half_stroke}, {"phase", phase}}}});
  }
  return wavemakers;
}

json fluid_entry(const scene::Scene& scene, const FluidRecord& fluid) {
  return {{"particle_count", fluid.particle_count ? fluid.particle_count : scene.fluid.count()},
          {"generated_particles", scene.fluid.count()},
          {"particle_mass", scene.fluid.mass},
          {"density", scene.fluid.density},
          {"spacing", scene.fluid.spacing}};
}

json protocol_entry(const std::optional<FluidRecord>& fluid) {
  if (!fluid) return nullptr;
  const std::uint32_t capabilities = fluid->peer ? fluid->peer->capabilities : 0;
  return {{"major", protocol::kMajorVersion},
          {"minor", protocol::kMinorVersion},
          {"capabilities", capabilities},
          {"authenticated", fluid->peer && fluid->peer->authenticated}};
}

json client_entry(const std::optional<FluidRecord>& fluid) {
  if (!fluid || !fluid->peer) return nullptr;
  return {{"software_version", fluid->peer->software_version},
          {"host", fluid->peer->host},
          {"mpi_ranks", fluid->peer->mpi_ranks},
          {"liggghts_version", fluid->liggghts_version}};
}

json timings_entry(const RunRecord& record) {
  const FluidRecord* fluid = record.fluid ? &*record.fluid : nullptr;
  auto of_fluid = [&](double FluidRecord::*seconds) {
    return fluid ? json(fluid->*seconds) : json(nullptr);
  };
  // What the server waited for beyond the client's own computing.
  const json communication =
      fluid ? json(std::max(0.0, fluid->seconds_round_trip - fluid->seconds_liggghts -
                                     fluid->seconds_contact))
            : json(nullptr);
  return {{"total", record.seconds_total},
          {"setup_and_equilibration", record.seconds_setup_and_equilibration},
          {"client_setup", of_fluid(&FluidRecord::seconds_client_setup)},
          {"client_equilibration", of_fluid(&FluidRecord::seconds_client_equilibration)},
          {"coupled_phase", fluid ? json(record.seconds_stepping) : json(nullptr)},
          {"stepping", record.seconds_stepping},
          {"mbd", record.seconds_mbd},
          {"liggghts", of_fluid(&FluidRecord::seconds_liggghts)},
          {"contact_fix", of_fluid(&FluidRecord::seconds_contact)},
          {"communication", communication},
          {"client_mpi_communication", of_fluid(&FluidRecord::seconds_client_communication)},
          {"output", record.seconds_output}};
}

json checks_entry(const RunRecord& record) {
  json checks = {{"max_action_reaction_relative", nullptr},
                 {"closest_approach_over_r0", nullptr},
                 {"particles_initial", nullptr},
                 {"particles_final", nullptr},
                 {"snapshots_checked", nullptr},
                 {"max_density_deviation_at_snapshots", nullptr},
                 {"max_particle_speed_at_snapshots", nullptr},
                 {"speed_of_sound", nullptr},
                 {"max_particle_speed_over_speed_of_sound_at_snapshots", nullptr},
                 {"max_particle_pairs_at_snapshots", nullptr},
                 {"closest_particle_pair_over_spacing_at_snapshots", nullptr},
                 {"closest_particle_pair_place", nullptr},
                 {"closest_particle_pair_time", nullptr},
                 {"position_constraint_drift", optional_number(record.position_constraint_drift)},
                 {"velocity_constraint_drift", optional_number(record.velocity_constraint_drift)}};
  if (!record.fluid) return checks;
  const FluidRecord& fluid = *record.fluid;
  const bool health = fluid.snapshots_checked > 0;
  checks["max_action_reaction_relative"] = fluid.max_action_reaction;
  checks["closest_approach_over_r0"] = optional_number(fluid.closest_approach_over_r0);
  checks["particles_initial"] = fluid.particles_initial;
  checks["particles_final"] = fluid.particles_final;
  checks["snapshots_checked"] = fluid.snapshots_checked;
  checks["max_density_deviation_at_snapshots"] =
      health ? json(fluid.max_density_deviation) : json(nullptr);
  checks["max_particle_speed_at_snapshots"] =
      health ? json(fluid.max_particle_speed) : json(nullptr);
  checks["speed_of_sound"] = optional_number(fluid.speed_of_sound);
  checks["max_particle_speed_over_speed_of_sound_at_snapshots"] =
      health && fluid.speed_of_sound ? json(fluid.max_particle_speed / *fluid.speed_of_sound)
                                     : json(nullptr);
  // Particle pairs closer than d/2 (particle_pairs.hpp): the most in one snapshot, and the
  // closest pair over all of them (null: none).
  if (health) {
    checks["max_particle_pairs_at_snapshots"] = fluid.max_close_pairs;
    if (fluid.closest_pair_over_spacing) {
      checks["closest_particle_pair_over_spacing_at_snapshots"] = *fluid.closest_pair_over_spacing;
      checks["closest_particle_pair_place"] = fluid.closest_pair_where;
      checks["closest_particle_pair_time"] = fluid.closest_pair_time;
    }
  }
  return checks;
}

json health_entry(const RunRecord& record) {
  if (!record.health) return nullptr;
  const HealthSummary& health = *record.health;
  const HealthRecord& worst = health.record;
  const FluidRecord* fluid = record.fluid ? &*record.fluid : nullptr;
  const bool reported = worst.steps_checked > 0;
  json mach = nullptr;
  if (reported && fluid && fluid->speed_of_sound && *fluid->speed_of_sound > 0.0)
    mach = worst.max_particle_speed / *fluid->speed_of_sound;
  return {
      {"limits",
       {{"max_density_deviation", health.limits.max_density_deviation},
        {"warn_density_deviation", health.limits.warn_density_deviation},
        {"max_mach", health.limits.max_mach},
        {"warn_mach", health.limits.warn_mach},
        {"min_wall_distance", health.limits.min_wall_distance},
        {"max_coupling_energy_growth", health.limits.max_coupling_energy_growth},
        {"allowed_lost_particles", health.allowed_lost_particles}}},
      {"steps_checked", worst.steps_checked},
      {"max_density_deviation", reported ? json(worst.max_density_deviation) : json(nullptr)},
      {"max_density_deviation_step",
       reported ? json(worst.max_density_deviation_step) : json(nullptr)},
      {"max_particle_speed", reported ? json(worst.max_particle_speed) : json(nullptr)},
      {"max_particle_speed_step", reported ? json(worst.max_particle_speed_step) : json(nullptr)},
      {"max_mach", mach},
      {"particles_lost", worst.particles_lost},
      {"failed_check", worst.failed_check ? json(*worst.failed_check) : json(nullptr)},
      {"warnings", worst.warnings}};
}

json energy_audit_entry(const std::optional<EnergyAuditSummary>& audit) {
  if (!audit) return nullptr;
  const EnergyTotals& totals = audit->totals;
  json bodies = json::array();
  for (const EnergyAudit::Part& part : audit->bodies) {
    bodies.push_back(
        {{"name", part.name},
         {"work_fluid_on_structure", part.totals.work_fluid_on_structure},
         {"work_structure_on_fluid", part.totals.work_structure_on_fluid},
         {"coupling_energy", part.totals.coupling_energy},
         {"max_coupling_energy", part.totals.max_coupling_energy},
         {"traffic", part.totals.traffic},
         {"max_coupling_fraction", part.totals.max_coupling_fraction},
         {"injection_warning_step", part.warned_at ? json(*part.warned_at) : json(nullptr)}});
  }
  return {{"work_fluid_on_structure", totals.work_fluid_on_structure},
          {"work_structure_on_fluid", totals.work_structure_on_fluid},
          {"coupling_energy", totals.coupling_energy},
          {"max_coupling_energy", totals.max_coupling_energy},
          {"traffic", totals.traffic},
          {"exchanges", totals.exchanges},
          {"max_coupling_fraction", totals.max_coupling_fraction},
          {"injection_warning_step", audit->warned_at ? json(*audit->warned_at) : json(nullptr)},
          {"stop_step", audit->stopped_at ? json(*audit->stopped_at) : json(nullptr)},
          {"bodies", bodies}};
}

json release_entry(const std::optional<ReleaseCheck>& release) {
  if (!release) return nullptr;
  return {{"settling_drag", release->settling_drag},
          {"column_height", release->column_height},
          {"fluid_mass", release->fluid_mass},
          {"weight", release->weight},
          {"carried_by_structure", release->carried},
          {"weight_fraction", optional_number(release->weight_fraction)},
          {"kinetic_energy", release->kinetic_energy},
          {"potential_energy", release->potential_energy},
          {"kinetic_over_potential", optional_number(release->kinetic_over_potential)},
          {"at_rest", release->at_rest},
          {"warning", release->warning.empty() ? json(nullptr) : json(release->warning)}};
}

}  // namespace

void write_run_manifest(const fs::path& output_dir, const scene::Scene& scene,
                        const RunRecord& record) {
  json manifest;
  manifest["format"] = "fsi-run-manifest";
  manifest["format_version"] = kRunManifestFormatVersion;
  manifest["mode"] = record.mode == RunMode::Coupled ? "coupled" : "mbd-only";
  manifest["program"] = {{"name", "fsi-server"},
                         {"version", std::string(fsi::software_version())},
                         {"git_revision", std::string(fsi::git_revision())},
                         {"command_line", record.command_line}};
  manifest["protocol"] = protocol_entry(record.fluid);
  manifest["client"] = client_entry(record.fluid);
  manifest["started_utc"] = record.started_utc.empty() ? json(nullptr) : json(record.started_utc);
  manifest["scene"] = scene_entry(scene);
  manifest["scene"]["overrides"] = record.overrides;
  manifest["parameters"] = scene::to_json(scene.parameters);
  // With every value of a Fluid block, the derived ones too (Fluid.smoothing_length, ...).
  std::map<std::string, double> flat = scene::flatten_numbers(scene.parameters);
  if (scene.fluid_parameters) {
    for (const scene::FluidValue& value : scene.fluid_parameters->values) {
      if (!value.quantity->key.empty())
        flat["Fluid." + std::string(value.quantity->key)] = value.value;
    }
  }
  manifest["parameters_flat"] = flat;
  manifest["dimension"] = scene.dimension;
  manifest["model"] = model_entry(scene, record.mode);
  manifest["fluid"] = record.fluid ? fluid_entry(scene, *record.fluid) : json(nullptr);
  manifest["mesh"] = mesh_entry(scene);
  manifest["wavemakers"] = wavemakers_entry(scene);
  manifest["time_step"] = scene.solver.step_size;
  manifest["end_time"] = scene.solver.end_time;
  manifest["steps"] = record.steps;
  manifest["snapshots"] = record.snapshots;
  manifest["timings_seconds"] = timings_entry(record);
  manifest["newton"] = {{"steps", record.newton.steps},
                        {"iterations", record.newton.newton_iterations},
                        {"jacobian_evaluations", record.newton.jacobian_evaluations},
                        {"factorisations", record.newton.factorisations},
                        {"substepped_steps", record.newton.substepped_steps}};
  manifest["checks"] = checks_entry(record);
  manifest["release"] = release_entry(record.release);
  manifest["energy_audit"] = energy_audit_entry(record.energy_audit);
  if (record.checkpoints) {
    const CheckpointRecord& c = *record.checkpoints;
    manifest["checkpoints"] = {{"every_steps", c.every_steps},
                               {"every_seconds", c.every_seconds},
                               {"written", c.written},
                               {"last_step", c.last_step ? json(*c.last_step) : json(nullptr)},
                               {"seconds_writing", c.seconds_writing}};
  } else {
    manifest["checkpoints"] = nullptr;
  }
  json resumes = json::array();
  for (const ResumeRecord& resume : record.resumes) {
    resumes.push_back({{"utc", resume.utc},
                       {"step", resume.step},
                       {"checkpoint", resume.checkpoint},
                       {"client_ranks", resume.client_ranks}});
  }
  manifest["resumes"] = resumes;
  manifest["health"] = health_entry(record);
  manifest["warnings"] = record.warnings;
  manifest["status"] = record.status;
  manifest["reason"] = record.reason.empty() ? json(nullptr) : json(record.reason);
  output::write_file_atomically(output_dir / "run.json", manifest.dump(2) + "\n");
}

}  // namespace fsi::coupling
