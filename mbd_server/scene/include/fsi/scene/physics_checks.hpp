#pragma once
// Physics sanity checks of a built scene: the rules of thumb of thesis §6.2 and one measured limit
// of this code, as diagnostics that state the numbers, the rule, its source and a fix. They never
// stop a run (a scene may have its reasons to break a rule of thumb); `fsi-server --check` prints
// them and a run logs them at start-up. The formulas are in docs/user-guide.md ("Physics checks").
//
// LIGGGHTS_SPH_parameters has no schema (a Fluid block's values are read like its entries,
// through sph_parameter). Declared values are used where the schema has them
// (FluidRegion spacing, density and particle mass, Gravity, SolverOptions.Timeint.step_size,
// VelocityConstraint); everything else is read under the variable names of thesis §5.6 and the
// examples: smoothinglength, cAB, viscosity, SPH_wall_rep, SPH_wall_visc,
// SPH_wall_equilibriumdist, SPH_wall_cutoff (and SPHdensity, particlespacing, SPHparticlemass,
// gravity without a FluidRegion or Gravity block). The wall values k, t, r0, cutoff come from the
// scripts' `fix ... fsi/sph` line when there is one (variables substituted), the gravity check
// reads the scripts' `fix ... gravity`. A check whose inputs are missing is skipped
// with one Info diagnostic saying which inputs.

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "fsi/scene/problem.hpp"
#include "fsi/scene/scene.hpp"

namespace fsi::scene {

enum class Severity { Warning, Info };
std::string_view name(Severity severity);  // "warning", "info"

struct Diagnostic {
  Severity severity = Severity::Warning;
  std::string check;         // one of kPhysicsCheckNames
  SourceLocation location;   // the parameter the finding is about
  std::string message;       // the numbers, the rule and where it comes from
  std::string fix;           // what to change (empty for Info)
  std::string text() const;  // "file:line:column: warning (check): message; fix"
};

// The checks in the order physics_checks reports them.
inline constexpr std::string_view kPhysicsCheckNames[] = {
    "acoustic_time_step",  // dt c / h <= 0.25 (thesis §6.2) and <= 0.125 (measured here)
    "contact_time_step",   // dt <= sqrt(m / k_eff) / 10 for the wall repulsion
    "speed_of_sound",      // c >= 10 x the expected flow speed (thesis §6.2)
    "wall_repulsion",      // k within 2-20 rho0 g h_max (thesis §6.2)
    "kernel_neighbours",   // 30-100 particles within the support radius 2h (thesis §3.1.2)
    "wall_viscosity",      // t within a factor 3 of rho0 nu / r_v (no slip, measured)
    "fluid_overlap",       // fluid box or polygon clear of every mesh by r0 / 2
    "gravity",             // the scripts' fix gravity equals the Gravity block
    "liggghts_scripts",    // every ${variable} defined where used; script 1 has fix fsi/sph
    "viscosity_match",     // the wall's t and the fluid's alpha within a factor 2 (no slip)
};

// Every check over `scene`: warnings for broken rules, infos for checks skipped. Pure: reads the
// scene only.
std::vector<Diagnostic> physics_checks(const Scene& scene);

// Not a rule of thumb but what the run will do: the coupled and the --mbd-only loop take
// round(end_time / step_size) steps, so a step that does not divide end_time ends the run at
// another time. One warning at SolverOptions.end_time saying where it ends and which steps and
// end times fit; empty when the step divides end_time (to 1e-9 relative).
std::vector<Diagnostic> end_time_check(const Scene& scene);

// The structure's integrator and start, for coupled and --mbd-only runs alike: Radau IIA with 1
// stage (implicit Euler) at a fixed step is warned at Timeint.stages with the amplitude an
// oscillation of 10 s, 1 s, ... (down to 4 steps) loses per period at the structure's step; a
// beam or cable whose velocity the Assembly block changed is warned at the block (it starts as
// if struck); empty otherwise.
std::vector<Diagnostic> integrator_check(const Scene& scene);

// The speed of sound c [m/s] the checks use (LIGGGHTS_SPH_parameters.cAB), or nullopt when the
// scene does not give a positive number; the server's progress line compares particle speeds to it.
std::optional<double> speed_of_sound(const Scene& scene);
// The smoothing length h [m] (LIGGGHTS_SPH_parameters.smoothinglength), or nullopt; the health
// checks' advice on the time step states dt c / h with it.
std::optional<double> smoothing_length(const Scene& scene);
// The reach r_c [m] of the thesis' wall law (the `cutoff` of fix fsi/sph, or
// LIGGGHTS_SPH_parameters.SPH_wall_cutoff), or nullopt (also for the true-shape wall, whose reach
// follows from its spacing); the wall-distance check's advice names it when it is short.
std::optional<double> wall_cutoff(const Scene& scene);
// The reference pressure [Pa] of the true-shape wall (the `pressure` of fix fsi/sph, e.g.
// ${SPH_wall_pressure}), or nullopt when the wall is the thesis' law; the wall-distance check's
// advice raises it instead of k, which the true-shape wall derives from it.
std::optional<double> true_shape_pressure(const Scene& scene);

}  // namespace fsi::scene
