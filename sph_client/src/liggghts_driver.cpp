#include "liggghts_driver.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <numeric>
#include <stdexcept>

#include "atom.h"
#include "atom_vec.h"
#include "comm.h"
#include "domain.h"
#include "fix.h"
#include "input.h"
#include "integrate.h"
#include "lammps.h"
#include "memory.h"
#include "modify.h"
#include "output.h"
#include "timer.h"
#include "update.h"
#include "variable.h"

#include "command_policy.hpp"
#include "fsi/common/error.hpp"
#include "fsi/contact/script_text.hpp"

namespace fsi::client {
namespace {

std::string format_double(double value) {
  char text[40];
  std::snprintf(text, sizeof text, "%.17g", value);
  return text;
}

}  // namespace

LiggghtsDriver::LiggghtsDriver(MPI_Comm communicator, const DriverOptions& options,
                               std::shared_ptr<contact::CouplingBoundary> boundary)
    : communicator_(communicator), options_(options), boundary_(std::move(boundary)) {
  MPI_Comm_rank(communicator_, &rank_);
  capture_ = std::make_unique<OutputCapture>(options.echo_output && rank_ == 0);
  std::vector<std::string> arguments{"fsi-client", "-screen", "none", "-log",
                                     options.log_file.empty() ? "none" : options.log_file};
  std::vector<char*> argv;
  for (std::string& argument : arguments)
    argv.push_back(argument.data());
  lammps_ = new LAMMPS_NS::LAMMPS(static_cast<int>(argv.size()), argv.data(), communicator_);
  // LIGGGHTS prints to `screen`; ours keeps the lines and forwards errors to stderr.
  lammps_->screen = capture_->stream();
}

LiggghtsDriver::~LiggghtsDriver() {
  // The fix list holds our fix, which refers to the boundary: delete LIGGGHTS first.
  lammps_->screen = nullptr;
  delete lammps_;
}

void LiggghtsDriver::define_variables(
    std::span<const std::pair<std::string, std::string>> variables) {
  for (const auto& [name, value] : variables) {
    const bool plain = !value.empty() && value.find_first_of(" \t\"'#$") == std::string::npos;
    position_ = {"LIGGGHTS variables from the scene", 0, "variable " + name};
    command("variable " + name + " string " + (plain ? value : "\"" + value + "\""));
  }
}

void LiggghtsDriver::command(const std::string& line) {
  if (stepping_) end_steps();
  position_.command = line;
  lammps_->input->one(line.c_str());
}

std::vector<std::string> LiggghtsDriver::substituted_words(const std::string& line) {
  // Input::substitute aborts the job on an unknown variable: check first and fail softly.
  for (const std::string& name : contact::referenced_variables(line)) {
    std::vector<char> buffer(name.begin(), name.end());
    buffer.push_back('\0');
    if (lammps_->input->variable->find(buffer.data()) < 0) {
      throw Error(
          "LIGGGHTS variable '" + name + "' is not defined",
          position_.script + ":" + std::to_string(position_.line),
          "define it in the scene's LIGGGHTS_SPH_parameters block or earlier in the script");
    }
  }
  int capacity = static_cast<int>(line.size()) + 1;
  int work_capacity = capacity;
  auto* text = static_cast<char*>(lammps_->memory->smalloc(capacity, "fsi:line"));
  auto* work = static_cast<char*>(lammps_->memory->smalloc(work_capacity, "fsi:work"));
  std::memcpy(text, line.c_str(), line.size() + 1);
  lammps_->input->substitute(text, work, capacity, work_capacity, 0);
  std::vector<std::string> words = contact::command_words(text);
  lammps_->memory->sfree(text);
  lammps_->memory->sfree(work);
  return words;
}

void LiggghtsDriver::run_script(const std::string& name, const std::string& text,
                                const std::function<void()>& after_create_box) {
  for (const contact::ScriptCommand& command : contact::script_commands(text)) {
    const int first_line = command.line;
    const std::string& code = command.code;
    const std::vector<std::string>& raw = command.words;
    position_ = {name, first_line, code};
    if (contact::is_fix_fsi_sph_command(raw)) {
      const std::vector<std::string> words = substituted_words(code);
      try {
        contact::add_fix_fsi_sph(*lammps_, words, boundary_);
      } catch (const std::invalid_argument& bad) {
        throw Error(bad.what(), name + ":" + std::to_string(first_line),
                    "correct the fix line; docs/fix_fsi_sph.md lists every keyword");
      }
      ++fsi_fix_count_;
    } else {
      if (!options_.allow_unsafe_commands) {
        if (const auto why = refused_command(substituted_words(code))) {
          throw Error("LIGGGHTS command refused: " + *why, name + ":" + std::to_string(first_line),
                      "remove it from the script, or start fsi-client with "
                      "--allow-unsafe-commands if you trust the scene's author");
        }
      }
      if (raw.front() == "processors") script_chose_grid_ = true;
      if (raw.front() == "create_box" && !script_chose_grid_ && automatic_grid_) {
        const ProcessorGrid& grid = *automatic_grid_;
        lammps_->input->one(("processors " + std::to_string(grid[0]) + " " +
                             std::to_string(grid[1]) + " " + std::to_string(grid[2]))
                                .c_str());
      }
      lammps_->input->one(code.c_str());
      if (raw.front() == "create_box" && after_create_box) after_create_box();
    }
  }
  // Ghost atoms must carry this step's pressure when the pair forces are computed (see
  // ensure_ghost_sync_last); the sync has to follow every fix the script defined.
  if (lammps_->domain->box_exist) contact::ensure_ghost_sync_last(*lammps_);
}

void LiggghtsDriver::insert_particles(const ParticleBlock& particles) {
  const auto& domain = *lammps_->domain;
  const int dimension = particles.dimension;
  if (domain.box_exist == 0) {
    throw Error("the particles of the fluid region cannot be created: no simulation box",
                "LIGGGHTS script 1", "create the box (region + create_box) in script 1");
  }
  if (dimension != domain.dimension) {
    throw Error("the scene is " + std::to_string(dimension) + "D but LIGGGHTS runs in " +
                    std::to_string(domain.dimension) + "D",
                "LIGGGHTS script 1", "make 'dimension' in script 1 match the scene");
  }
  if (particles.atom_type < 1 || particles.atom_type > lammps_->atom->ntypes) {
    throw Error("fluid particles use atom type " + std::to_string(particles.atom_type) +
                    " but the box has " + std::to_string(lammps_->atom->ntypes) + " type(s)",
                "LIGGGHTS script 1", "create_box with enough atom types");
  }
  const std::size_t count = particles.positions.size() / static_cast<std::size_t>(dimension);
  if (!particles.densities.empty() && particles.densities.size() != count) {
    throw Error("the server sent " + std::to_string(particles.densities.size()) +
                    " initial densities for " + std::to_string(count) + " particles",
                "particle insertion", "use matching fsi-server and fsi-client releases");
  }
  // A particle outside the box would silently be dropped: refuse the whole set instead.
  for (std::size_t i = 0; i < count; ++i) {
    for (int k = 0; k < dimension; ++k) {
      const double c = particles.positions[i * dimension + k];
      if (!(c >= domain.boxlo[k] && c <= domain.boxhi[k])) {
        throw Error("fluid particle " + std::to_string(i) + " at " + format_double(c) +
                        " (coordinate " + std::to_string(k) + ") lies outside the LIGGGHTS box [" +
                        format_double(domain.boxlo[k]) + ", " + format_double(domain.boxhi[k]) +
                        "]",
                    "LIGGGHTS script 1", "enlarge the box in script 1 or move the fluid region");
      }
    }
  }
  if (dimension == 2 && !(0.0 >= domain.boxlo[2] && 0.0 < domain.boxhi[2])) {
    throw Error("the 2D box does not contain z = 0", "LIGGGHTS script 1",
                "give the box a z-range around 0 (ARCHITECTURE.md §3)");
  }

  auto& atom = *lammps_->atom;
  const auto& comm = *lammps_->comm;
  for (std::size_t i = 0; i < count; ++i) {
    double coordinate[3] = {0.0, 0.0, 0.0};
    for (int k = 0; k < dimension; ++k)
      coordinate[k] = particles.positions[i * dimension + k];
    bool mine = true;
    for (int k = 0; k < 3 && mine; ++k) {
      const bool last_along_k = comm.myloc[k] == comm.procgrid[k] - 1;
      const bool upper_closed = last_along_k && coordinate[k] == domain.subhi[k];
      mine = coordinate[k] >= domain.sublo[k] && (coordinate[k] < domain.subhi[k] || upper_closed);
    }
    if (!mine) continue;
    atom.avec->create_atom(particles.atom_type, coordinate);
    const int n = atom.nlocal - 1;
    for (int k = 0; k < dimension; ++k)
      atom.v[n][k] = particles.velocities[i * dimension + k];
    if (atom.rho) {
      atom.rho[n] = particles.densities.empty() ? particles.density : particles.densities[i];
    }
    for (int j = 0; j < lammps_->modify->nfix; ++j) {
      LAMMPS_NS::Fix* fix = lammps_->modify->fix[j];
      if (fix->create_attribute) {
        fix->pre_set_arrays();
        fix->set_arrays(n);
      }
    }
  }
  const auto before = static_cast<long long>(atom.natoms);
  long long local = atom.nlocal;
  long long total = 0;
  MPI_Allreduce(&local, &total, 1, MPI_LONG_LONG, MPI_SUM, communicator_);
  atom.natoms = total;
  if (total - before != static_cast<long long>(count)) {
    throw Error("created " + std::to_string(total - before) + " of " + std::to_string(count) +
                    " fluid particles",
                "particle insertion", "report this with the scene and scripts (a bug)");
  }
  atom.tag_extend();
  if (atom.map_style) {
    atom.nghost = 0;
    atom.map_init();
    atom.map_set();
  }
  command("mass " + std::to_string(particles.atom_type) + " " + format_double(particles.mass));
}

void LiggghtsDriver::set_time_step(double time_step) {
  command("timestep " + format_double(time_step));
}

double LiggghtsDriver::time_step() const {
  return lammps_->update->dt;
}

std::int64_t LiggghtsDriver::current_step() const {
  return static_cast<std::int64_t>(lammps_->update->ntimestep);
}

void LiggghtsDriver::run_with_setup(std::uint64_t steps) {
  command("run " + std::to_string(steps));
}

void LiggghtsDriver::run_continued(std::uint64_t steps) {
  command("run " + std::to_string(steps) + " pre no post no");
}

void LiggghtsDriver::step() {
  LAMMPS_NS::Update& update = *lammps_->update;
  if (update.first_update == 0) {  // no run with set-up yet: LIGGGHTS' own run sets up
    run_continued(1);
    return;
  }
  if (stepping_ && update.ntimestep >= update.laststep) end_steps();
  if (!stepping_) begin_steps();
  update.integrate->run(1);
}

void LiggghtsDriver::begin_steps() {
  // Far ahead, so that output->next stays a thermo or dump step of the scripts; a run that
  // reaches it begins anew.
  constexpr LAMMPS_NS::bigint kHorizon = 100'000'000;
  LAMMPS_NS::Update& update = *lammps_->update;
  update.whichflag = 1;
  update.nsteps = static_cast<int>(kHorizon);
  update.firststep = update.ntimestep;
  update.laststep = update.ntimestep + kHorizon;
  update.beginstep = update.firststep;
  update.endstep = update.laststep;
  lammps_->output->init();
  lammps_->output->setup(0);
  lammps_->timer->init();
  position_.command = "coupled steps from LIGGGHTS step " + std::to_string(update.ntimestep);
  stepping_ = true;
}

void LiggghtsDriver::end_steps() {
  stepping_ = false;
  LAMMPS_NS::Update& update = *lammps_->update;
  update.integrate->cleanup();
  update.whichflag = 0;
  update.firststep = update.laststep = 0;
  update.beginstep = update.endstep = 0;
}

namespace {

constexpr const char* kDragFixId = "fsi_settling_drag";

// Unit vector along -g (up), or zero without gravity.
std::array<double, 3> upward(const std::array<double, 3>& gravity) {
  const double magnitude = std::hypot(gravity[0], gravity[1], gravity[2]);
  if (!(magnitude > 0.0)) return {0.0, 0.0, 0.0};
  return {-gravity[0] / magnitude, -gravity[1] / magnitude, -gravity[2] / magnitude};
}

double mass_of(const LAMMPS_NS::Atom& atom, int i) {
  return atom.rmass ? atom.rmass[i] : atom.mass[atom.type[i]];
}

}  // namespace

FluidExtent LiggghtsDriver::fluid_extent(const std::array<double, 3>& gravity) const {
  const auto& atom = *lammps_->atom;
  const std::array<double, 3> up = upward(gravity);
  double bounds[2] = {std::numeric_limits<double>::infinity(),
                      std::numeric_limits<double>::infinity()};   // lowest, -highest
  double sums[3] = {static_cast<double>(atom.nlocal), 0.0, 0.0};  // count, mass, density
  for (int i = 0; i < atom.nlocal; ++i) {
    const double height = up[0] * atom.x[i][0] + up[1] * atom.x[i][1] + up[2] * atom.x[i][2];
    bounds[0] = std::min(bounds[0], height);
    bounds[1] = std::min(bounds[1], -height);
    sums[1] += mass_of(atom, i);
    sums[2] += atom.rho ? atom.rho[i] : 0.0;
  }
  double global_bounds[2], global_sums[3];
  MPI_Allreduce(bounds, global_bounds, 2, MPI_DOUBLE, MPI_MIN, communicator_);
  MPI_Allreduce(sums, global_sums, 3, MPI_DOUBLE, MPI_SUM, communicator_);
  FluidExtent extent;
  extent.count = static_cast<std::uint64_t>(std::llround(global_sums[0]));
  if (extent.count == 0) return extent;
  extent.height = -global_bounds[1] - global_bounds[0];
  extent.mean_mass = global_sums[1] / global_sums[0];
  extent.mean_density = global_sums[2] / global_sums[0];
  return extent;
}

FluidEnergies LiggghtsDriver::fluid_energies(const std::array<double, 3>& gravity) const {
  const auto& atom = *lammps_->atom;
  const std::array<double, 3> up = upward(gravity);
  const double g = std::hypot(gravity[0], gravity[1], gravity[2]);
  double lowest = std::numeric_limits<double>::infinity();
  for (int i = 0; i < atom.nlocal; ++i)
    lowest = std::min(lowest, up[0] * atom.x[i][0] + up[1] * atom.x[i][1] + up[2] * atom.x[i][2]);
  double global_lowest = 0.0;
  MPI_Allreduce(&lowest, &global_lowest, 1, MPI_DOUBLE, MPI_MIN, communicator_);
  double sums[3] = {0.0, 0.0, 0.0};  // mass, kinetic, potential
  for (int i = 0; i < atom.nlocal; ++i) {
    const double m = mass_of(atom, i);
    const double* v = atom.v[i];
    const double height =
        up[0] * atom.x[i][0] + up[1] * atom.x[i][1] + up[2] * atom.x[i][2] - global_lowest;
    sums[0] += m;
    sums[1] += 0.5 * m * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    sums[2] += m * g * height;
  }
  double totals[3];
  MPI_Allreduce(sums, totals, 3, MPI_DOUBLE, MPI_SUM, communicator_);
  return {totals[0], totals[1], totals[2]};
}

void LiggghtsDriver::add_velocity_drag(double rate) {
  // fix viscous applies -gamma v; gamma = rate m_type makes the same rate for every type.
  const auto& atom = *lammps_->atom;
  std::vector<double> type_mass(static_cast<std::size_t>(atom.ntypes) + 1, 0.0);
  if (atom.rmass) {
    // Per-particle masses: each type's mean.
    std::vector<double> sums(2 * type_mass.size(), 0.0);
    for (int i = 0; i < atom.nlocal; ++i) {
      sums[2 * atom.type[i]] += atom.rmass[i];
      sums[2 * atom.type[i] + 1] += 1.0;
    }
    std::vector<double> totals(sums.size());
    MPI_Allreduce(sums.data(), totals.data(), static_cast<int>(sums.size()), MPI_DOUBLE, MPI_SUM,
                  communicator_);
    for (std::size_t t = 1; t < type_mass.size(); ++t)
      type_mass[t] = totals[2 * t + 1] > 0.0 ? totals[2 * t] / totals[2 * t + 1] : 0.0;
  } else {
    for (int t = 1; t <= atom.ntypes; ++t)
      type_mass[t] = atom.mass_setflag[t] ? atom.mass[t] : 0.0;
  }
  std::string line = std::string("fix ") + kDragFixId + " all viscous " + format_double(rate);
  for (int t = 1; t <= atom.ntypes; ++t)
    line += " scale " + std::to_string(t) + " " + format_double(type_mass[t]);
  position_ = {"settling drag of the equilibration (fsi-client)", 0, line};
  command(line);
}

void LiggghtsDriver::remove_velocity_drag() {
  position_ = {"settling drag of the equilibration (fsi-client)", 0, "unfix"};
  command(std::string("unfix ") + kDragFixId);
}

std::uint64_t LiggghtsDriver::particle_count() const {
  return static_cast<std::uint64_t>(lammps_->atom->natoms);
}

std::uint64_t LiggghtsDriver::local_particle_count() const {
  return static_cast<std::uint64_t>(lammps_->atom->nlocal);
}

LocalFluidHealth LiggghtsDriver::local_fluid_health() const {
  const auto& atom = *lammps_->atom;
  LocalFluidHealth health;
  for (int i = 0; i < atom.nlocal; ++i) {
    const double* x = atom.x[i];
    const double* v = atom.v[i];
    const double rho = atom.rho ? atom.rho[i] : 0.0;
    const double speed_squared = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
    // One sum catches a NaN or an infinity in any of the seven values.
    if (!std::isfinite(x[0] + x[1] + x[2] + speed_squared + rho)) {
      ++health.non_finite;
      continue;
    }
    health.min_density = std::min(health.min_density, rho);
    health.max_density = std::max(health.max_density, rho);
    health.max_speed_squared = std::max(health.max_speed_squared, speed_squared);
  }
  return health;
}

Snapshot LiggghtsDriver::gather_snapshot(int dimension) const {
  const auto& atom = *lammps_->atom;
  const int local = atom.nlocal;
  std::vector<double> packed;  // id, position, velocity, density, pressure per particle
  const int width = 1 + 2 * dimension + 2;
  packed.reserve(static_cast<std::size_t>(local) * width);
  for (int i = 0; i < local; ++i) {
    packed.push_back(static_cast<double>(atom.tag[i]));
    for (int k = 0; k < dimension; ++k)
      packed.push_back(atom.x[i][k]);
    for (int k = 0; k < dimension; ++k)
      packed.push_back(atom.v[i][k]);
    packed.push_back(atom.rho ? atom.rho[i] : 0.0);
    packed.push_back(atom.p ? atom.p[i] : 0.0);
  }
  int ranks = 1;
  MPI_Comm_size(communicator_, &ranks);
  const int sent = static_cast<int>(packed.size());
  std::vector<int> counts(ranks), offsets(ranks);
  MPI_Gather(&sent, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, communicator_);
  std::vector<double> all;
  if (rank_ == 0) {
    std::exclusive_scan(counts.begin(), counts.end(), offsets.begin(), 0);
    all.resize(static_cast<std::size_t>(offsets.back()) + counts.back());
  }
  MPI_Gatherv(packed.data(), sent, MPI_DOUBLE, all.data(), counts.data(), offsets.data(),
              MPI_DOUBLE, 0, communicator_);
  Snapshot snapshot;
  if (rank_ != 0) return snapshot;
  const std::size_t n = all.size() / width;
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(),
            [&](std::size_t a, std::size_t b) { return all[a * width] < all[b * width]; });
  for (std::size_t j : order) {
    const double* row = all.data() + j * width;
    snapshot.ids.push_back(static_cast<std::uint64_t>(row[0]));
    snapshot.positions.insert(snapshot.positions.end(), row + 1, row + 1 + dimension);
    snapshot.velocities.insert(snapshot.velocities.end(), row + 1 + dimension,
                               row + 1 + 2 * dimension);
    snapshot.density.push_back(row[1 + 2 * dimension]);
    snapshot.pressure.push_back(row[2 + 2 * dimension]);
  }
  return snapshot;
}

}  // namespace fsi::client
