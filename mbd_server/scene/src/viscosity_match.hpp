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

// LIGGGHTS' sph/artVisc acts on approaching pairs only; in a shear flow that is half of the
// pairs, and the fluid's kinematic viscosity is nu = alpha c h / divisor (2D: 16, 3D: 20).
double artificial_viscosity_divisor(int dimension);

// The viscosity a wall of friction t holds without slip: nu = t r_v / rho0, r_v the friction's
// range (`cutoff_visc`, default the cutoff). Measured in 2D (docs/validation.md, "Channel flows":
// Poiseuille flow at 80 particles across meets the wall 0.13 d outside the mesh with it; twice that
// t, the thesis' eq. 6.4 with h, holds 0.92 d of fluid on the wall, half of it slips 1.3 d);
// applied in 3D unmeasured.
double wall_viscosity(const fsi::contact::ForceLaw& law, double density);

// The moment rule's wall friction for a fluid of nu: t = rho0 nu d^D / M, M the friction's second
// moment (2D: r_v^3 / 6, 3D: pi r_v^4 / 20), d the particle spacing: the wall's total friction in
// a linear shear flow equals the fluid's own stress (docs/theory.md, "Viscosity"). Measured in
// 2D: the channel flows meet it within 0.2 d of the drawn walls, where rho0 nu / r_v holds about
// one spacing of fluid on them; the rule for flows driven by a flux (examples/cylinder).
double moment_wall_friction(double density, double viscosity, double spacing, double range,
                            int dimension);

void check_viscosity_match(const Scene& scene, std::vector<Diagnostic>& diagnostics);

}  // namespace fsi::scene
