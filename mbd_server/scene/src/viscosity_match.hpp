#pragma once
// The physics check `viscosity_match` (docs/user-guide.md, "Physics checks"; docs/theory.md,
// "Viscosity"): the wall friction t of `fix ... fsi/sph` against the viscosity the fluid really
// has, the artificial viscosity alpha of LIGGGHTS' pair style as the scripts set it. Internal to
// fsi::scene; physics_checks() runs it.

#include <vector>

#include "fsi/contact/force_law.hpp"
#include "fsi/scene/physics_checks.hpp"
#include "fsi/scene/scene.hpp"

namespace fsi::scene {

// The viscosity a wall of friction t holds without slip: nu = t r_v / rho0, r_v the friction's
// range (`cutoff_visc`, default the cutoff). Measured in 2D (docs/theory.md, "Viscosity"): a
// Poiseuille flow with that t is held without slip 0.85-0.99 d inside the drawn walls at 20-80
// particles across; the moment rule (fluid_parameters.hpp, moment_wall_friction) holds it at them.
// Applied in 3D unmeasured.
double wall_viscosity(const fsi::contact::ForceLaw& law, double density);

void check_viscosity_match(const Scene& scene, std::vector<Diagnostic>& diagnostics);

}  // namespace fsi::scene
