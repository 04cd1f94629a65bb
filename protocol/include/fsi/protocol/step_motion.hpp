#pragma once
// The boundary's motion over one structure step as the fluid side evaluates it between the
// step's ends (multi-rate coupling, issue 15 item 1; docs/theory.md, "Multi-rate coupling").
//
// The structure's implicit Runge-Kutta step (Radau IIA, Lobatto IIIA) computes its stage values
// at the collocation nodes t0 + c_i h. The fluid side receives, for every moving vertex, its
// position x_i and velocity u_i at the nodes theta_i in {0} u {c_i} (distinct, ascending, the
// last c_s = 1: the end of the step), and evaluates in between the Hermite interpolant
//   p(theta) = sum_i H_i(theta) x_i + h sum_i K_i(theta) u_i,
//   H_i = (1 - 2 l_i'(theta_i) (theta - theta_i)) l_i^2,   K_i = (theta - theta_i) l_i^2,
// with l_i the Lagrange basis of the nodes: p takes the stage positions at the nodes and its
// time derivative takes the stage velocities there (both exactly: the weights are 1 and 0 in
// floating point at a node), and the velocity the fluid sees is the derivative of the position
// it sees. Vertex positions of rotating bodies are not linear in the generalised coordinates,
// so the structure's own collocation polynomial cannot be sent as vertex data; its stage values
// can, and between them the interpolant is as accurate as the stages (stage order s: local error
// O(h^(s+1)), measured in mbd's tests).

#include <span>
#include <vector>

namespace fsi::protocol {

// Weights of the nodes' values and velocities at one theta in [0, 1].
struct StepMotionWeights {
  std::vector<double> position_of_position;  // H_i(theta)
  std::vector<double> position_of_velocity;  // h K_i(theta)
  std::vector<double> velocity_of_position;  // H_i'(theta) / h
  std::vector<double> velocity_of_velocity;  // K_i'(theta)
};

// The weights at `theta` for `nodes` (distinct, ascending, in [0, 1], at most 8) of a step of
// `step_size`. Throws fsi::Error for nodes that break these rules, a theta outside [0, 1] or a
// step size that is not positive.
StepMotionWeights step_motion_weights(std::span<const double> nodes, double step_size,
                                      double theta);

// Evaluates the interpolant: `values` are the nodes' positions node-major (node i's block of
// `width` values at i * width), `rates` their velocities alike; writes `width` positions and
// velocities at the weights' theta.
void evaluate_step_motion(const StepMotionWeights& weights, std::span<const double> values,
                          std::span<const double> rates, std::size_t width,
                          std::span<double> positions_out, std::span<double> velocities_out);

}  // namespace fsi::protocol
