// The LAMMPS Fix adapter: maps LIGGGHTS' per-atom arrays onto the contact core.
#include <chrono>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "fix.h"
#include "group.h"
#include "lammps.h"
#include "memory.h"
#include "modify.h"
#include "update.h"

#include "fsi/contact/fix_arguments.hpp"
#include "fsi/contact/liggghts_fix.hpp"
#include "fsi/contact/periodic_images.hpp"

namespace fsi::contact {
namespace {

constexpr const char* kStyle = "fsi/sph";

class FixFsiSph : public LAMMPS_NS::Fix {
 public:
  FixFsiSph(LAMMPS_NS::LAMMPS* lammps, int argc, char** argv, const ContactSettings& settings,
            const ContactSettings3D& settings3d, double warn_fraction, bool true_shape,
            std::shared_ptr<CouplingBoundary> boundary)
      : Fix(lammps, argc, argv),
        contact_(settings),
        contact3d_(settings3d),
        warn_distance_(warn_fraction * settings.law.equilibrium_distance),
        true_shape_(true_shape),
        boundary_(std::move(boundary)) {}

  int setmask() override { return LAMMPS_NS::FixConst::POST_FORCE; }

  void init() override {
    if (domain->dimension != boundary_->dimension) {
      throw std::invalid_argument(
          "fix fsi/sph: LIGGGHTS runs in dimension " + std::to_string(domain->dimension) +
          " but the structure's mesh is " + std::to_string(boundary_->dimension) +
          "D; use a script with `dimension " + std::to_string(boundary_->dimension) + "`");
    }
    if (atom->v == nullptr) {
      throw std::invalid_argument("fix fsi/sph: the atom style has no velocities");
    }
  }

  void setup(int vflag) override { post_force(vflag); }

  void post_force(int /*vflag*/) override {
    const auto started = std::chrono::steady_clock::now();
    CouplingBoundary& boundary = *boundary_;
    if (boundary.share_pending) {
      throw std::runtime_error(
          "fix fsi/sph: LIGGGHTS evaluates the wall forces before fsi-client has handed out the "
          "ranks' shares of the boundary (a run command in script 1?): put run commands in "
          "script 2");
    }
    take_share(boundary);
    const int local = atom->nlocal;
    check_coverage(boundary.coverage, local);
    ParticleArrays particles;
    particles.count = static_cast<std::size_t>(local);
    if (local > 0) {
      particles.positions = atom->x[0];
      particles.velocities = atom->v[0];
      particles.forces = atom->f[0];
      particles.group_mask = std::span<const int>(atom->mask, static_cast<std::size_t>(local));
      particles.group_bit = groupbit;
    }
    boundary.vertex_forces.resize(boundary.positions().size());
    // Along a periodic axis the particles meet the walls beyond the periodic boundary through
    // their images (fsi/contact/periodic_images.hpp).
    const Periodicity box = periodicity();
    const double range = contact_.settings().law.range();
    if (box.any() && !periodic_mesh_checked_) {
      // As drawn, at the set-up: the whole mesh's extent, not this rank's share's.
      check_periodic_mesh(
          box, boundary.drawn_bounds.empty() ? boundary.positions() : boundary.drawn_bounds, range);
      periodic_mesh_checked_ = true;
    }
    const ParticleArrays evaluated =
        box.any() ? images_.extend(particles, box, boundary.positions(), range) : particles;
    try {
      boundary.diagnostics = boundary.dimension == 3
                                 ? contact3d_.compute(boundary.mesh3d, evaluated,
                                                      boundary.vertex_forces, &boundary.samples)
                                 : contact_.compute(boundary.mesh, evaluated,
                                                    boundary.vertex_forces, &boundary.samples);
      if (box.any()) images_.fold_forces(particles);
    } catch (const NonFiniteParticle& bad) {
      const std::size_t index = box.any() ? images_.origin(bad.index) : bad.index;
      const double* x = atom->x[index];
      const double* v = atom->v[index];
      char text[320];
      std::snprintf(text, sizeof text,
                    "fix fsi/sph: atom %d has a non-finite position (%g, %g, %g) or velocity "
                    "(%g, %g, %g) at step " BIGINT_FORMAT
                    ": the fluid has blown up; reduce the time step or raise the wall repulsion k",
                    atom->tag[index], x[0], x[1], x[2], v[0], v[1], v[2], update->ntimestep);
      throw std::runtime_error(text);
    }
    ++boundary.evaluations;
    boundary.sampling_points += boundary.diagnostics.sampling_points;
    boundary.sampling_points_generated +=
        boundary.diagnostics.sampling_points - boundary.diagnostics.sampling_points_skipped;
    warn_if_too_close(boundary.diagnostics.closest_distance);
    boundary.seconds_in_fix +=
        std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  }

 private:
  // A new share of the mesh: its pre-refinement (3D options 2, 3) comes with it.
  void take_share(const CouplingBoundary& boundary) {
    if (boundary.share_generation == share_generation_) return;
    share_generation_ = boundary.share_generation;
    if (boundary.dimension == 3) contact3d_.prepare(boundary.pre_refinement);
  }

  // Every particle of the group must lie where this rank's share of the mesh holds every element
  // within its reach (CouplingBoundary::coverage).
  void check_coverage(const CouplingBoundary::Coverage& coverage, int local) const {
    if (!coverage.active) return;
    for (int i = 0; i < local; ++i) {
      if ((atom->mask[i] & groupbit) == 0) continue;
      const double* x = atom->x[i];
      bool inside = true;
      for (int k = 0; k < domain->dimension; ++k)
        inside = inside && x[k] >= coverage.low[k] && x[k] <= coverage.high[k];
      if (inside) continue;
      char text[480];
      std::snprintf(text, sizeof text,
                    "fix fsi/sph: atom %d at (%g, %g, %g) on rank %d is outside (%g, %g, %g) - "
                    "(%g, %g, %g), where this rank's share of the boundary mesh holds every "
                    "element within its reach, at step " BIGINT_FORMAT
                    ": LIGGGHTS has not handed it to its owner; let it re-neighbour as the "
                    "particles move (neigh_modify delay 0 every 1 check yes)",
                    atom->tag[i], x[0], x[1], x[2], comm->me, coverage.low[0], coverage.low[1],
                    coverage.low[2], coverage.high[0], coverage.high[1], coverage.high[2],
                    update->ntimestep);
      throw std::runtime_error(text);
    }
  }

  Periodicity periodicity() const {
    Periodicity box;
    box.dimension = domain->dimension;
    for (int k = 0; k < 3; ++k) {
      box.periodic[k] = domain->periodicity[k] != 0;
      box.low[k] = domain->boxlo[k];
      box.high[k] = domain->boxhi[k];
    }
    return box;
  }

  // A particle closer to a wall than warn_fraction * r0 means the wall repulsion is losing:
  // warn on the rank that sees it, at most once per kWarnEvery steps.
  void warn_if_too_close(double closest) {
    constexpr LAMMPS_NS::bigint kWarnEvery = 1000;
    if (!(closest < warn_distance_)) return;
    if (last_warning_ >= 0 && update->ntimestep - last_warning_ < kWarnEvery) return;
    last_warning_ = update->ntimestep;
    // The true-shape wall derives k from its reference pressure: that is what to raise.
    const char* stiffer = true_shape_ ? "raise the wall's reference pressure (the fix's "
                                        "`pressure`, Fluid.wall_pressure)"
                                      : "raise k";
    // At step 0 nothing has moved yet: the particles start there, a set-up matter (a lattice
    // against a wall off its cell edges, e.g. a slope), not a wall losing to the flow.
    char advice[240];
    if (update->ntimestep == 0) {
      std::snprintf(advice, sizeof advice,
                    "the particles start there (a lattice point close to a wall off its cell "
                    "edges, e.g. a slope; `fsi-server SCENE --check`, fluid_overlap, names it): "
                    "draw the water's region clear of that wall, or let the equilibration push "
                    "them off");
    } else {
      std::snprintf(advice, sizeof advice, "%s or reduce the time step", stiffer);
    }
    char text[560];
    std::snprintf(text, sizeof text,
                  "fix fsi/sph: a particle is %.3g r0 from a wall at LIGGGHTS step " BIGINT_FORMAT
                  " (counted with the equilibration's; warn below %.3g r0): %s; repeats at most "
                  "every %d steps",
                  closest / contact_.settings().law.equilibrium_distance, update->ntimestep,
                  warn_distance_ / contact_.settings().law.equilibrium_distance, advice,
                  static_cast<int>(kWarnEvery));
    error->warning(FLERR, text);
  }

  WallContact2D contact_;
  WallContact3D contact3d_;
  double warn_distance_;
  bool true_shape_;
  LAMMPS_NS::bigint last_warning_ = -1;
  std::shared_ptr<CouplingBoundary> boundary_;
  PeriodicImages images_;
  bool periodic_mesh_checked_ = false;
  std::uint64_t share_generation_ = 0;
};

constexpr const char* kGhostSyncId = "fsi_ghost_sync";

// The density's rate at a set-up: LIGGGHTS' set-up clears drho with the forces, and the
// continuity fix computes it in pre_force only, which a set-up does not call, so the first step
// after every set-up (a `run` with set-up, a new time step, a checkpoint) would leave the density
// unchanged. Measured on the coarse static tank: 0.19 % of the largest speed after 500 steps
// against a run without the set-up; with the rate recomputed here, round-off (1e-13).
constexpr const char* kContinuityStyle = "sph/density/continuity";

class FixGhostSync : public LAMMPS_NS::Fix {
 public:
  FixGhostSync(LAMMPS_NS::LAMMPS* lammps, int argc, char** argv) : Fix(lammps, argc, argv) {}
  int setmask() override { return LAMMPS_NS::FixConst::PRE_FORCE; }
  void setup_pre_force(int vflag) override {
    comm->forward_comm();
    // Last in the fix list (ensure_ghost_sync_last): the ghosts are current for the rate.
    for (int i = 0; i < modify->nfix; ++i) {
      if (std::strcmp(modify->fix[i]->style, kContinuityStyle) == 0)
        modify->fix[i]->pre_force(vflag);
    }
  }
  void pre_force(int /*vflag*/) override { comm->forward_comm(); }
};

// Appends a constructed fix to the fix list the way Modify::add_fix does for a new ID.
void append_fix(LAMMPS_NS::LAMMPS& lammps, LAMMPS_NS::Fix* fix) {
  LAMMPS_NS::Modify& modify = *lammps.modify;
  if (modify.nfix == modify.maxfix) {
    constexpr int kGrowth = 4;
    modify.maxfix += kGrowth;
    modify.fix = static_cast<LAMMPS_NS::Fix**>(
        lammps.memory->srealloc(modify.fix, modify.maxfix * sizeof(LAMMPS_NS::Fix*), "modify:fix"));
    lammps.memory->grow(modify.fmask, modify.maxfix, "modify:fmask");
  }
  const int slot = modify.nfix;
  modify.fix[slot] = fix;
  modify.fmask[slot] = fix->setmask();
  ++modify.nfix;
  fix->post_create_pre_restart();
  fix->post_create();
}

}  // namespace

void CouplingBoundary::assign(int mesh_dimension, std::vector<double> vertex_positions,
                              std::vector<double> vertex_velocities,
                              std::vector<std::uint32_t> elements) {
  if (mesh_dimension != 2 && mesh_dimension != 3) {
    throw std::invalid_argument("mesh dimension must be 2 or 3, got " +
                                std::to_string(mesh_dimension));
  }
  dimension = mesh_dimension;
  mesh = BoundaryMesh2D{};
  mesh3d = BoundaryMesh3D{};
  if (dimension == 3) {
    mesh3d.positions = std::move(vertex_positions);
    mesh3d.velocities = std::move(vertex_velocities);
    mesh3d.triangles = std::move(elements);
    mesh3d.validate();
  } else {
    mesh.positions = std::move(vertex_positions);
    mesh.velocities = std::move(vertex_velocities);
    mesh.segments = std::move(elements);
    mesh.validate();
  }
}

void ensure_ghost_sync_last(LAMMPS_NS::LAMMPS& lammps) {
  LAMMPS_NS::Modify& modify = *lammps.modify;
  const int slot = modify.find_fix(kGhostSyncId);
  if (slot >= 0 && slot == modify.nfix - 1) return;
  if (slot >= 0) modify.delete_fix(kGhostSyncId);
  if (lammps.group->find("all") < 0 || lammps.domain->box_exist == 0) {
    throw std::invalid_argument("fsi/ghost_sync needs the simulation box; create it in script 1");
  }
  std::string words[] = {kGhostSyncId, "all", "fsi/ghost_sync"};
  char* argv[] = {words[0].data(), words[1].data(), words[2].data()};
  append_fix(lammps, new FixGhostSync(&lammps, 3, argv));
}

bool is_fix_fsi_sph_command(std::span<const std::string> words) {
  return words.size() >= 4 && words[0] == "fix" && words[3] == kStyle;
}

void add_fix_fsi_sph(LAMMPS_NS::LAMMPS& lammps, std::span<const std::string> words,
                     std::shared_ptr<CouplingBoundary> boundary) {
  if (!is_fix_fsi_sph_command(words)) {
    throw std::invalid_argument("not a 'fix ID group fsi/sph ...' command");
  }
  if (!boundary) throw std::invalid_argument("fix fsi/sph: no coupling boundary attached");
  const FixFsiSphArguments arguments =
      parse_fix_fsi_sph_arguments(words.subspan(4), lammps.domain->dimension);
  ContactSettings settings;
  settings.law = arguments.law;
  settings.gauss_points = arguments.gauss_points;
  settings.refinement_resolution = boundary->refinement_resolution;
  settings.validate();
  ContactSettings3D settings3d;
  settings3d.law = arguments.law;
  settings3d.quadrature_points = arguments.triangle_points;
  settings3d.refinement_option = boundary->refinement_option;
  settings3d.refinement_resolution = boundary->refinement_resolution;
  settings3d.validate();
  if (boundary->dimension == 3) {
    boundary->mesh3d.validate();
  } else {
    boundary->mesh.validate();
  }
  boundary->law = settings.law;

  // Checks LIGGGHTS would make with error->all(), which ends the process: fail softly instead.
  if (lammps.domain->box_exist == 0) {
    throw std::invalid_argument(
        "fix fsi/sph: define the simulation box (create_box) before the fix");
  }
  if (lammps.group->find(words[2].c_str()) < 0) {
    throw std::invalid_argument("fix fsi/sph: group '" + words[2] + "' does not exist");
  }

  // LAMMPS' Fix constructor wants argv without the leading "fix".
  std::vector<std::string> arguments_text(words.begin() + 1, words.end());
  std::vector<char*> argv;
  for (std::string& word : arguments_text)
    argv.push_back(word.data());
  const int argc = static_cast<int>(argv.size());

  LAMMPS_NS::Modify& modify = *lammps.modify;
  int slot = modify.find_fix(words[1].c_str());
  if (slot >= 0) {
    if (std::strcmp(modify.fix[slot]->style, kStyle) != 0) {
      throw std::invalid_argument("fix fsi/sph: fix ID '" + words[1] + "' is already used by a '" +
                                  modify.fix[slot]->style + "' fix; choose another ID");
    }
    modify.fix[slot]->pre_delete(true);
    delete modify.fix[slot];
    modify.fix[slot] = nullptr;
    modify.fix[slot] =
        new FixFsiSph(&lammps, argc, argv.data(), settings, settings3d, arguments.warn_fraction,
                      arguments.uses_true_shape, std::move(boundary));
    modify.fmask[slot] = modify.fix[slot]->setmask();
    modify.fix[slot]->post_create_pre_restart();
    modify.fix[slot]->post_create();
    return;
  }
  append_fix(lammps, new FixFsiSph(&lammps, argc, argv.data(), settings, settings3d,
                                   arguments.warn_fraction, arguments.uses_true_shape,
                                   std::move(boundary)));
}

}  // namespace fsi::contact
