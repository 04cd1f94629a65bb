#pragma once
// Static equilibrium and small vibrations about it, for models with position-level constraints:
//
//     F(q, v = 0) - G(q)^T lambda = 0,    C(q) = 0
//
// solved by Newton's method with the exact Jacobian of the model (dF/dq, including the bodies'
// elastic stiffness, and d(G^T lambda)/dq) and load stepping: gravity and the point loads are
// raised in equal steps from zero to their full values (force elements and internal forces are
// not scaled). The linearised frequencies are those of M, the stiffness K = -dF/dq + d(G^T
// lambda)/dq at a state, restricted to the motions the constraints allow.

#include <vector>

#include "fsi/mbd/model.hpp"

namespace fsi::mbd {

struct StaticOptions {
  int load_steps = 10;
  int max_iterations = 25;  // Newton iterations per load step
  // Converged when |dq|_inf <= tolerance (1 + |q|_inf) and |dlambda|_inf <= tolerance (1 +
  // |lambda|_inf), or when dq is at round-off (16 eps: lambda then changes by the scaled
  // solve's round-off only).
  double tolerance = 1e-10;
};

struct StaticResult {
  State state;  // v = 0, t = the start's time, lambda the constraint multipliers
  int newton_iterations = 0;
};

// Starts from `start` (q and lambda; e.g. Model::initial_state()). The model's gravity and point
// loads are scaled during the solve and restored afterwards (also when it throws). Throws
// fsi::Error for velocity-level constraints and when Newton does not converge in a load step
// (naming the load factor and the last increment).
StaticResult solve_static(Model& model, const State& start, const StaticOptions& options = {});

// The lowest `count` natural frequencies [Hz] of the undamped linearisation about `state`
// (normally an equilibrium): the generalised eigenproblem K x = omega^2 M x on the null space of
// the constraint Jacobian G, with K symmetrised (the non-conservative part of follower loads is
// left out). Ascending; an unstable mode (omega^2 < 0) is returned as -sqrt(-omega^2) / (2 pi).
// Velocity-level constraints restrict the velocities and are included in G.
std::vector<double> natural_frequencies(const ConstrainedSystem& system, const State& state,
                                        int count);

}  // namespace fsi::mbd
