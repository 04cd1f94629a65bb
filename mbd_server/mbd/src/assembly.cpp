#include "fsi/mbd/assembly.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

#include "fsi/common/error.hpp"
#include "fsi/common/text.hpp"

namespace fsi::mbd {
namespace {

// Two polishing steps after the tolerance is met take a quadratically converging Newton from
// ~1e-12 to round-off, so that the integrator starts on the constraints, not near them.
constexpr int kPolishingSteps = 2;
// A step that lowers |C| by less than this fraction is no progress: the least-squares minimum
// of an open loop has been reached.
constexpr double kStallDecrease = 1e-10;
// Levenberg-Marquardt damping relative to |A|_F^2 after a step that did not lower |C|: from the
// first nonzero value up by factors of ten, back down by a hundred after a success.
constexpr double kFirstDamping = 1e-8;
constexpr double kLargestDamping = 1e8;

// The smallest change of the free coordinates in the mass metric that solves G dq = -r, or
// satisfies it in the least-squares sense when it has no solution (an open loop, a row on a
// driving coordinate). With M_ff = L L^T and y = L^T dq this is the minimum-norm least-squares
// y of (G_f L^-T) y = -r, which a complete orthogonal decomposition gives also when G_f has lost
// rank (a mechanism at a dead point, a redundant row).
class MinimumChange {
 public:
  MinimumChange(const Model& model, std::vector<int> free)
      : coordinates_(model.coordinate_count()), free_(std::move(free)) {
    const Eigen::MatrixXd metric = model.mass_matrix()(free_, free_);
    factor_.compute(metric);
    FSI_ASSERT(factor_.info() == Eigen::Success, "the mass matrix is not positive definite");
  }

  // With relative_damping > 0 the Levenberg-Marquardt step of the same metric,
  // (A^T A + mu I) y = -A^T r with mu = relative_damping |A|_F^2: shorter, turning towards the
  // steepest descent of |C|, for the far-from-linear steps of an open loop (whose least-squares
  // minimum plain Gauss-Newton overshoots where G loses rank).
  Eigen::VectorXd correction(const Eigen::MatrixXd& jacobian, const Eigen::VectorXd& residual,
                             double relative_damping = 0.0) const {
    Eigen::VectorXd change = Eigen::VectorXd::Zero(coordinates_);
    if (free_.empty() || residual.size() == 0) return change;
    const Eigen::MatrixXd scaled_transposed =
        factor_.matrixL().solve(Eigen::MatrixXd(jacobian(Eigen::all, free_).transpose()));
    Eigen::VectorXd scaled_change;
    if (relative_damping > 0.0) {
      Eigen::MatrixXd normal = scaled_transposed * scaled_transposed.transpose();
      normal.diagonal().array() += relative_damping * scaled_transposed.squaredNorm();
      scaled_change = normal.llt().solve(-(scaled_transposed * residual));
    } else {
      const Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> decomposition(
          scaled_transposed.transpose());
      scaled_change = decomposition.solve(-residual);
    }
    const Eigen::VectorXd free_change = factor_.matrixU().solve(scaled_change);
    change(free_) = free_change;
    return change;
  }

 private:
  int coordinates_;
  std::vector<int> free_;
  Eigen::LLT<Eigen::MatrixXd> factor_;
};

std::vector<int> free_coordinates(const Model& model, const std::vector<int>& driving) {
  const int n = model.coordinate_count();
  std::vector<bool> held(static_cast<std::size_t>(n), false);
  for (const int index : driving) {
    if (index < 0 || index >= n) {
      throw Error("driving coordinate index " + std::to_string(index) +
                      " is out of range (the model has " + std::to_string(n) + " coordinates)",
                  "initial assembly", "name a coordinate of the model");
    }
    if (held[static_cast<std::size_t>(index)]) {
      throw Error(model.coordinate_description(index) + " is marked as driving twice",
                  "initial assembly", "name each driving coordinate once");
    }
    held[static_cast<std::size_t>(index)] = true;
  }
  std::vector<int> free;
  for (int i = 0; i < n; ++i) {
    if (!held[static_cast<std::size_t>(i)]) free.push_back(i);
  }
  return free;
}

// "revolute joint 'B' (x)" -> element "revolute joint 'B'", component "x".
std::pair<std::string, std::string> element_and_component(const std::string& description) {
  const auto open = description.rfind(" (");
  if (description.empty() || description.back() != ')' || open == std::string::npos)
    return {description, ""};
  return {description.substr(0, open), description.substr(open + 2, description.size() - open - 3)};
}

// The constraint elements with a row above `limit`: each with the Euclidean norm of all its
// rows' residuals (for point rows the distance between the two points) and the rows; then the
// sum of these gaps.
std::string open_elements(const Model& model, const std::vector<int>& rows,
                          const Eigen::VectorXd& residual, double limit, double& total_gap) {
  struct Open {
    double squared = 0.0;
    bool above = false;
    std::string components;
  };
  std::vector<std::string> order;
  std::map<std::string, Open> elements;
  for (std::size_t k = 0; k < rows.size(); ++k) {
    const auto [element, component] = element_and_component(model.constraint_description(rows[k]));
    const double value = residual(static_cast<Eigen::Index>(k));
    auto [entry, added] = elements.try_emplace(element);
    if (added) order.push_back(element);
    entry->second.squared += value * value;
    entry->second.above = entry->second.above || !(std::abs(value) <= limit);
    if (!component.empty()) {
      entry->second.components +=
          (entry->second.components.empty() ? "" : ", ") + component + ": " + significant(value, 9);
    }
  }
  std::string text;
  total_gap = 0.0;
  for (const std::string& element : order) {
    const Open& open = elements.at(element);
    if (!open.above) continue;
    const double gap = std::sqrt(open.squared);
    total_gap += gap;
    text += "\n  " + element + ": residual " + significant(gap, 9) +
            (open.components.empty() ? "" : " (" + open.components + ")");
  }
  return text;
}

std::vector<int> position_rows(const Model& model) {
  std::vector<int> rows;
  for (int k = 0; k < model.constraint_count(); ++k) {
    if (model.constraint_level(k) == ConstraintLevel::Position) rows.push_back(k);
  }
  return rows;
}

Eigen::VectorXd position_residual(const Model& model, const std::vector<int>& rows, double time,
                                  const Eigen::VectorXd& q, const Eigen::VectorXd& v) {
  Eigen::VectorXd all;
  model.constraint_residual(time, q, v, all);
  return all(rows);
}

// Largest magnitude; zero for an empty vector (a model without rows of that level).
double largest(const Eigen::VectorXd& values) {
  return values.size() == 0 ? 0.0 : values.lpNorm<Eigen::Infinity>();
}

double scaled_tolerance(double tolerance, const Eigen::VectorXd& values) {
  return tolerance * (1.0 + largest(values));
}

const char* const kCannotCloseRemedy =
    "check the lengths and joint points of the named elements (can the mechanism close at "
    "all?), start from a configuration nearer the intended one, and mark no coordinate as "
    "driving that a constraint fixes";

// Gauss-Newton, damped (Levenberg-Marquardt) only where a full step does not lower |C|: returns
// the number of steps.
int assemble_positions(const Model& model, const MinimumChange& metric,
                       const std::vector<int>& rows, const AssemblyOptions& options, State& state) {
  if (rows.empty()) return 0;
  Eigen::VectorXd residual = position_residual(model, rows, state.time, state.q, state.v);
  int steps = 0;
  int polishing = 0;
  double damping = 0.0;
  for (;;) {
    const bool converged = largest(residual) <= scaled_tolerance(options.tolerance, state.q);
    if (converged && polishing == kPolishingSteps) break;
    if (!converged && steps >= options.max_iterations) break;
    Eigen::MatrixXd jacobian;
    model.constraint_jacobian(state.time, state.q, jacobian);
    const Eigen::MatrixXd rows_jacobian = jacobian(rows, Eigen::all);
    bool progress = false;
    for (;;) {
      const Eigen::VectorXd trial_q =
          state.q + metric.correction(rows_jacobian, residual, converged ? 0.0 : damping);
      const Eigen::VectorXd trial = position_residual(model, rows, state.time, trial_q, state.v);
      if (trial.norm() < residual.norm()) {
        progress = trial.norm() < (1.0 - kStallDecrease) * residual.norm() || converged;
        state.q = trial_q;
        residual = trial;
        damping = damping > 100.0 * kFirstDamping ? damping / 100.0 : 0.0;
        break;
      }
      if (converged || damping >= kLargestDamping) break;
      damping = damping == 0.0 ? kFirstDamping : 10.0 * damping;
    }
    if (converged) {
      ++polishing;
      if (!progress) break;
      continue;
    }
    ++steps;
    if (!progress) break;
  }
  if (!(largest(residual) <= scaled_tolerance(options.tolerance, state.q))) {
    double total_gap = 0.0;
    const std::string elements = open_elements(
        model, rows, residual, scaled_tolerance(options.tolerance, state.q), total_gap);
    throw Error("the constraints cannot be closed at t = " + significant(state.time, 9) +
                    ": after " + std::to_string(steps) +
                    " Gauss-Newton steps the least |C| leaves these constraint elements open" +
                    elements + "\n  the loop misses by " + significant(total_gap, 9) +
                    " (sum of the residuals; m for point and distance rows)",
                "initial assembly", kCannotCloseRemedy);
  }
  return steps;
}

// The velocity equations are linear in v: one minimum change, repeated once for round-off.
void assemble_velocities(const Model& model, const MinimumChange& metric,
                         const AssemblyOptions& options, State& state) {
  const int m = model.constraint_count();
  if (m == 0) return;
  Eigen::MatrixXd jacobian;
  model.constraint_jacobian(state.time, state.q, jacobian);
  Eigen::VectorXd rate;
  for (int pass = 0; pass < 2; ++pass) {
    model.constraint_rate(state.time, state.q, state.v, rate);
    if (pass > 0 && largest(rate) <= 1e-3 * options.tolerance) break;
    state.v += metric.correction(jacobian, rate);
  }
  model.constraint_rate(state.time, state.q, state.v, rate);
  if (!(largest(rate) <= scaled_tolerance(options.tolerance, state.v))) {
    std::vector<int> rows(static_cast<std::size_t>(m));
    for (int k = 0; k < m; ++k)
      rows[static_cast<std::size_t>(k)] = k;
    double total = 0.0;
    const std::string elements =
        open_elements(model, rows, rate, scaled_tolerance(options.tolerance, state.v), total);
    throw Error("the velocity equations (G v + dC/dt = 0, G v = g(t)) cannot be met at t = " +
                    significant(state.time, 9) + "; these constraint elements stay violated" +
                    elements,
                "initial assembly",
                "a driving coordinate's velocity contradicts a constraint: give it the velocity "
                "the constraints allow, or do not mark it as driving");
  }
}

std::string local_coordinate(const Model& model, BodyId body, int index) {
  const std::string description = model.coordinate_description(index);
  const std::string prefix = "body '" + model.body_name(body) + "' ";
  return description.rfind(prefix, 0) == 0 ? description.substr(prefix.size()) : description;
}

std::vector<BodyCorrection> body_corrections(const Model& model, const State& approximate,
                                             const State& assembled) {
  std::vector<BodyCorrection> corrections;
  for (BodyId body = 0; body < model.body_count(); ++body) {
    BodyCorrection correction;
    correction.body = body;
    correction.name = model.body_name(body);
    const int first = model.first_coordinate(body);
    const int count = model.body_coordinate_count(body);
    int largest_position = first;
    int largest_velocity = first;
    for (int i = first; i < first + count; ++i) {
      const double position_change = std::abs(assembled.q(i) - approximate.q(i));
      const double velocity_change = std::abs(assembled.v(i) - approximate.v(i));
      if (position_change > correction.largest_position_change) {
        correction.largest_position_change = position_change;
        largest_position = i;
      }
      if (velocity_change > correction.largest_velocity_change) {
        correction.largest_velocity_change = velocity_change;
        largest_velocity = i;
      }
    }
    if (count > 0) {
      correction.position_coordinate = local_coordinate(model, body, largest_position);
      correction.velocity_coordinate = local_coordinate(model, body, largest_velocity);
    }
    corrections.push_back(std::move(correction));
  }
  return corrections;
}

}  // namespace

std::vector<std::string> AssemblyReport::lines() const {
  std::vector<std::string> text;
  text.push_back("initial assembly: " + std::to_string(iterations) +
                 " Gauss-Newton steps, max |C| = " + significant(position_residual, 3) +
                 ", max velocity residual = " + significant(velocity_residual, 3));
  for (const BodyCorrection& body : bodies) {
    const auto change = [](double value, const std::string& coordinate) {
      return value == 0.0 ? std::string("unchanged")
                          : "by " + significant(value, 3) + " (" + coordinate + ")";
    };
    text.push_back("  body '" + body.name + "': position " +
                   change(body.largest_position_change, body.position_coordinate) + ", velocity " +
                   change(body.largest_velocity_change, body.velocity_coordinate));
  }
  return text;
}

AssemblyReport assemble(const Model& model, const State& approximate,
                        const AssemblyOptions& options) {
  const int n = model.coordinate_count();
  FSI_ASSERT(approximate.q.size() == n && approximate.v.size() == n,
             "the approximate state does not match the model");
  if (!(options.tolerance > 0.0) || options.max_iterations < 1) {
    throw Error("assembly tolerance " + significant(options.tolerance, 9) + " and " +
                    std::to_string(options.max_iterations) + " iterations",
                "initial assembly", "give a positive tolerance and at least one iteration");
  }
  if (!approximate.q.allFinite() || !approximate.v.allFinite()) {
    throw Error("the approximate configuration has non-finite coordinates or velocities",
                "initial assembly", "give finite initial positions and velocities");
  }
  const MinimumChange metric(model, free_coordinates(model, options.driving_coordinates));
  const std::vector<int> rows = position_rows(model);

  AssemblyReport report;
  report.state.time = approximate.time;
  report.state.q = approximate.q;
  report.state.v = approximate.v;
  report.state.lambda = Eigen::VectorXd::Zero(model.constraint_count());
  report.iterations = assemble_positions(model, metric, rows, options, report.state);
  assemble_velocities(model, metric, options, report.state);

  report.position_residual =
      largest(position_residual(model, rows, report.state.time, report.state.q, report.state.v));
  Eigen::VectorXd rate;
  model.constraint_rate(report.state.time, report.state.q, report.state.v, rate);
  report.velocity_residual = largest(rate);
  report.bodies = body_corrections(model, approximate, report.state);
  return report;
}

}  // namespace fsi::mbd
