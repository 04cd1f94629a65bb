#pragma once
// Initial assembly: from a user's approximate configuration to one that satisfies the
// constraints, before step 0 (what Chrono's DoAssembly and Adams' initial conditions analysis
// do). Positions are corrected by Gauss-Newton on the position-level rows, C(q, t) = 0, each step
// the smallest change of the free coordinates in the mass metric,
//
//     minimise  dq^T M dq  subject to  G dq = -C        (least squares when G dq = -C has none),
//
// then the velocities by the same projection onto the velocity-level equations (G v + C_t = 0 of
// position rows, G v = g(t) of velocity rows), which is linear in v: one step.
//
// Why the mass matrix as metric: it makes the correction independent of the units (an identity
// metric would weigh a metre against a radian, and change its answer when lengths are given in
// mm), it moves heavy bodies less than light ones (what "the user's configuration, nearly" means
// physically), and on velocity level it is the minimum change of kinetic energy, the velocity
// jump a perfectly plastic impulse through the joints would cause. It is constant for every
// element of this engine, so the metric does not change between iterations.
//
// Driving coordinates stay exactly as given, in position and velocity: they are removed from
// the unknowns (columns of G dropped), so a crank angle given by the user is kept to the bit.
//
// When the loop cannot be closed (links too short, a driving coordinate that contradicts a
// constraint), the iteration ends at the configuration of least |C| and the assembly throws
// fsi::Error naming every constraint element whose residual stays, with its gap, and the sum of
// the gaps: the distance by which the loop misses.

#include <Eigen/Dense>

#include <string>
#include <vector>

#include "fsi/mbd/model.hpp"

namespace fsi::mbd {

struct AssemblyOptions {
  // Converged when every row satisfies |C_k| <= tolerance (1 + |q|_inf) and every velocity
  // equation |rate_k| <= tolerance (1 + |v|_inf), the form Model::check_consistency tests with
  // 1e-12; a few more iterations then polish to round-off.
  double tolerance = 1e-12;
  int max_iterations = 50;
  // Indices in q that keep their given value and velocity (Model::coordinate_index, ...).
  std::vector<int> driving_coordinates;
};

// How far one body was moved: the largest change of any of its coordinates (in that
// coordinate's unit: m, or rad for a planar angle) and of any of its velocities.
struct BodyCorrection {
  BodyId body = kGround;
  std::string name;
  double largest_position_change = 0.0;
  std::string position_coordinate;  // Model::coordinate_description of the largest change
  double largest_velocity_change = 0.0;
  std::string velocity_coordinate;
};

struct AssemblyReport {
  State state;                         // the assembled q and v at the start time; lambda zero
  int iterations = 0;                  // Gauss-Newton steps on position level
  double position_residual = 0.0;      // max |C_k| at the end
  double velocity_residual = 0.0;      // max |G v + C_t|, |G v - g| at the end
  std::vector<BodyCorrection> bodies;  // every body, in model order

  // One line per body plus a summary, for the log.
  std::vector<std::string> lines() const;
};

// Assembles `approximate` (q, v, time; e.g. Model::initial_configuration()). Throws fsi::Error
// for a driving index out of range or given twice, and for a loop that cannot be closed (the
// message names the constraint elements that stay open and by how much).
AssemblyReport assemble(const Model& model, const State& approximate,
                        const AssemblyOptions& options = {});

}  // namespace fsi::mbd
