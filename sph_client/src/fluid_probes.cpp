#include "fluid_probes.hpp"

#include <string>

#include "atom.h"
#include "fix_property_global.h"
#include "force.h"
#include "fsi/common/error.hpp"
#include "lammps.h"
#include "modify.h"
#include "pair_sph.h"
// LIGGGHTS' kernels: each header defines its functions, and again read with SPH_KERNEL_CLASS
// names them in one SPHKernel(id, name, value, derivative, cutoff) line (LIGGGHTS' own
// sph_kernels.h does this through a generated header Debian does not ship).
#include "sph_kernel_cubicspline.h"
#include "sph_kernel_cubicspline2D.h"
#include "sph_kernel_spiky.h"
#include "sph_kernel_spiky2D.h"
#include "sph_kernel_wendland.h"
#include "sph_kernel_wendland2D.h"

namespace fsi::client {
namespace {

struct LiggghtsKernel {
  int id;
  const char* name;
  double (*value)(double s, double h, double hinv);
  double (*cutoff)();
};

constexpr LiggghtsKernel kLiggghtsKernels[] = {
#define SPH_KERNEL_CLASS
#define SPHKernel(kernel_id, style, value, derivative, cutoff) \
  {kernel_id, #style, SPH_KERNEL_NS::value, SPH_KERNEL_NS::cutoff},
#include "sph_kernel_cubicspline.h"
#include "sph_kernel_cubicspline2D.h"
#include "sph_kernel_spiky.h"
#include "sph_kernel_spiky2D.h"
#include "sph_kernel_wendland.h"
#include "sph_kernel_wendland2D.h"
#undef SPHKernel
#undef SPH_KERNEL_CLASS
};

const LiggghtsKernel& pair_kernel(LAMMPS_NS::LAMMPS& lammps) {
  auto* pair = dynamic_cast<LAMMPS_NS::PairSph*>(lammps.force->pair);
  if (!pair) {
    throw Error("the LIGGGHTS scripts define no SPH pair style, which the probes interpolate with",
                "probe set-up", "use pair_style sph/artVisc/tensCorr KERNEL h ... in script 1");
  }
  for (const LiggghtsKernel& kernel : kLiggghtsKernels) {
    if (kernel.id == pair->sph_kernel_id()) return kernel;
  }
  throw Error("the SPH pair style uses kernel id " + std::to_string(pair->sph_kernel_id()) +
                  ", which fsi-client does not know",
              "probe set-up", "use one of LIGGGHTS 3.8's kernels (docs/user-guide.md, \"Probes\")");
}

// LIGGGHTS' SPH takes the smoothing length per atom type from `fix property/global sl`.
double smoothing_length_of(LAMMPS_NS::LAMMPS& lammps, int atom_type) {
  const int types = lammps.atom->ntypes;
  auto* fix = dynamic_cast<LAMMPS_NS::FixPropertyGlobal*>(lammps.modify->find_fix_property(
      "sl", "property/global", "peratomtype", types, 0, "fsi-client probes", false));
  if (!fix || atom_type < 1 || atom_type > types) {
    throw Error("no smoothing length for atom type " + std::to_string(atom_type) +
                    " in the LIGGGHTS scripts",
                "probe set-up", "define fix ID all property/global sl peratomtype h in script 1");
  }
  return fix->compute_vector(atom_type - 1);
}

double mass_of(const LAMMPS_NS::Atom& atom, int i) {
  return atom.rmass ? atom.rmass[i] : atom.mass[atom.type[i]];
}

}  // namespace

FluidProbes::FluidProbes(LAMMPS_NS::LAMMPS& lammps, MPI_Comm communicator, probes::ProbeSet probes,
                         int fluid_atom_type)
    : lammps_(lammps), communicator_(communicator), probes_(std::move(probes)) {
  const LiggghtsKernel& kernel = pair_kernel(lammps_);
  smoothing_length_ = smoothing_length_of(lammps_, fluid_atom_type);
  const double h = smoothing_length_;
  if (!(h > 0.0)) {
    throw Error("the smoothing length of the LIGGGHTS scripts is " + std::to_string(h),
                "probe set-up", "give fix property/global sl a positive value");
  }
  kernel_name_ = kernel.name;
  kernel_.support = kernel.cutoff() * h;
  kernel_.value = [value = kernel.value, h](double distance) {
    return value(distance / h, h, 1.0 / h);
  };
}

const probes::Partials& FluidProbes::partials(const probes::WallSamples& wall) {
  ScopedTimer timer(evaluating_);
  const LAMMPS_NS::Atom& atom = *lammps_.atom;
  const int dimension = probes_.context().dimension;
  const auto owned = static_cast<std::size_t>(atom.nlocal);
  const auto all = owned + static_cast<std::size_t>(atom.nghost);
  const auto per_particle = static_cast<std::size_t>(dimension);
  positions_.resize(all * per_particle);
  velocities_.resize(owned * per_particle);
  density_.resize(owned);
  pressure_.resize(owned);
  mass_.resize(owned);
  for (std::size_t i = 0; i < all; ++i) {
    for (std::size_t k = 0; k < per_particle; ++k)
      positions_[i * per_particle + k] = atom.x[i][k];
  }
  for (std::size_t i = 0; i < owned; ++i) {
    const int index = static_cast<int>(i);
    for (std::size_t k = 0; k < per_particle; ++k)
      velocities_[i * per_particle + k] = atom.v[i][k];
    density_[i] = atom.rho[i];
    pressure_[i] = atom.p[i];
    mass_[i] = mass_of(atom, index);
  }
  const probes::ParticleSet particles{owned, positions_, velocities_, density_, pressure_, mass_};
  partials_ = probes_.partials(particles, kernel_, wall);
  return partials_;
}

}  // namespace fsi::client
