// The sparse path of the Newton matrix (Eigen SparseLU) against the dense one: the same steps
// to round-off on a rigid chain with revolute joints and on the car axis problem, and the
// automatic choice by size.
#include <gtest/gtest.h>

#include <cstdio>
#include <limits>

#include "fsi/mbd/integrator.hpp"
#include "reference_problems.hpp"

namespace fsi::mbd {
namespace {

State run(const Model& model, LinearSolver solver, int steps, double h, int threshold = 300) {
  RadauIIA radau({.stages = 3,
                  .newton = {.relative_tolerance = 1e-12,
                             .max_iterations = 20,
                             .max_modified_newton_steps = 0,
                             .linear_solver = solver,
                             .sparse_threshold = threshold}});
  State state = model.initial_state();
  for (int i = 0; i < steps; ++i)
    radau.step(model, state, h);
  return state;
}

struct Difference {
  double q, v, lambda;  // max relative differences
  double lambda_absolute, lambda_floor;
};
// The multipliers are printed, not asserted: on the index-3 system they carry the rounding of
// the position rows amplified by M / h^2 (docs/theory.md), and two factorisations round
// differently (measured: car axis 1.7e-10 N, below the floor; chain of 20 bars 1.1e-8 N, 2.5x the
// single-body floor, the root joint carrying all 20 bars).
// lambda_floor: the round-off floor of the multipliers on the index-3 system,
// 100 eps max(M) |q| / h^2, which Newton's convergence test grants them (docs/theory.md).
Difference relative_difference(const Model& model, const State& a, const State& b, double h) {
  const double lambda = (a.lambda - b.lambda).lpNorm<Eigen::Infinity>();
  return {(a.q - b.q).lpNorm<Eigen::Infinity>() / a.q.lpNorm<Eigen::Infinity>(),
          (a.v - b.v).lpNorm<Eigen::Infinity>() / a.v.lpNorm<Eigen::Infinity>(),
          lambda / a.lambda.lpNorm<Eigen::Infinity>(), lambda,
          100.0 * std::numeric_limits<double>::epsilon() * model.mass_matrix().maxCoeff() *
              a.q.lpNorm<Eigen::Infinity>() / (h * h)};
}

TEST(MbdSparseNewton, ChainOf20BarsSameAsDenseToRoundOff) {
  const Model chain = reference::rigid_chain(20);  // Newton matrix 3 x (2 x 60 + 40) = 480
  const State dense = run(chain, LinearSolver::Dense, 20, 1e-3);
  const State sparse = run(chain, LinearSolver::Sparse, 20, 1e-3);
  const Difference d = relative_difference(chain, dense, sparse, 1e-3);
  std::printf(
      "chain of 20 bars, 20 steps of 1 ms: max relative difference sparse - dense: q %.1e, "
      "v %.1e, lambda %.1e (%.1e N, floor %.1e N; the bars moved up to %.3f m)\n",
      d.q, d.v, d.lambda, d.lambda_absolute, d.lambda_floor,
      (dense.q - chain.initial_state().q).lpNorm<Eigen::Infinity>());
  EXPECT_LT(d.q, 1e-13);
  EXPECT_LT(d.v, 1e-11);
}

TEST(MbdSparseNewton, CarAxisSameAsDenseToRoundOff) {
  const auto problem = reference::car_axis::make();
  const State dense = run(problem.model, LinearSolver::Dense, 2000, 1e-4);
  const State sparse = run(problem.model, LinearSolver::Sparse, 2000, 1e-4);
  const Difference d = relative_difference(problem.model, dense, sparse, 1e-4);
  std::printf(
      "car axis, 2000 steps of 1e-4: max relative difference sparse - dense: q %.1e, "
      "v %.1e, lambda %.1e (%.1e N, floor %.1e N)\n",
      d.q, d.v, d.lambda, d.lambda_absolute, d.lambda_floor);
  EXPECT_LT(d.q, 1e-13);
  EXPECT_LT(d.v, 1e-11);
}

TEST(MbdSparseNewton, AutomaticChoiceFollowsTheThreshold) {
  const Model chain = reference::rigid_chain(3);  // Newton matrix 3 x (18 + 6) = 72
  const State dense = run(chain, LinearSolver::Dense, 10, 1e-3);
  // Both automatic runs give the dense (threshold above) or the sparse (below) result.
  const State automatic_dense = run(chain, LinearSolver::Automatic, 10, 1e-3, 73);
  const State automatic_sparse = run(chain, LinearSolver::Automatic, 10, 1e-3, 72);
  const State sparse = run(chain, LinearSolver::Sparse, 10, 1e-3);
  EXPECT_EQ(automatic_dense.q, dense.q);
  EXPECT_EQ(automatic_sparse.q, sparse.q);
}

}  // namespace
}  // namespace fsi::mbd
