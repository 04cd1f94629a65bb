// Step-doubling error control around the fixed-step Radau IIA driver (adaptive_radau.hpp).

#include "fsi/mbd/adaptive_radau.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <utility>

#include "fsi/common/error.hpp"

namespace fsi::mbd {
namespace {

void validate(const AdaptiveOptions& o) {
  std::string problems;
  if (!(o.relative_tolerance > 0.0 && o.relative_tolerance < 1.0)) {
    problems += " relative_tolerance must be in (0, 1);";
  }
  if (!(o.absolute_tolerance > 0.0 && std::isfinite(o.absolute_tolerance))) {
    problems += " absolute_tolerance must be positive;";
  }
  if (!(o.initial_step > 0.0 && std::isfinite(o.initial_step))) {
    problems += " initial_step must be positive;";
  }
  if (!(o.min_step > 0.0 && o.min_step <= o.initial_step)) {
    problems += " min_step must be in (0, initial_step];";
  }
  if (!(o.max_step >= 0.0 && std::isfinite(o.max_step))) problems += " max_step must be >= 0;";
  if (!(o.safety > 0.0 && o.safety <= 1.0)) problems += " safety must be in (0, 1];";
  if (!(o.max_growth > 1.0)) problems += " max_growth must be > 1;";
  if (!(o.min_shrink > 0.0 && o.min_shrink < 1.0)) problems += " min_shrink must be in (0, 1);";
  if (!problems.empty()) {
    problems.pop_back();
    throw Error("invalid adaptive step options:" + problems, "adaptive Radau IIA options",
                "use e.g. relative_tolerance = 1e-6, absolute_tolerance = 1e-8, "
                "initial_step = 1e-3");
  }
}

}  // namespace

struct AdaptiveRadau::Impl {
  AdaptiveOptions options;
  RadauIIA whole, halves;  // separate instances keep their factorisations for h and h/2
  double exponent;         // 1 / (s + 1)
  double h;
  AdaptiveStatistics stats;
  Eigen::VectorXd advance_integral, trial_integral;

  Impl(const RadauOptions& radau, const AdaptiveOptions& adaptive)
      : options(adaptive),
        whole(radau),
        halves(radau),
        exponent(1.0 / (radau.stages + 1)),
        h(adaptive.initial_step) {}

  void count(const StepStatistics& s) {
    ++stats.radau_steps;
    stats.newton_iterations += static_cast<std::uint64_t>(s.newton_iterations);
    stats.jacobian_evaluations += static_cast<std::uint64_t>(s.jacobian_evaluations);
    stats.factorisations += static_cast<std::uint64_t>(s.factorisations);
  }

  // Weighted RMS norm of the differences in q and v (adaptive_radau.hpp): weights
  // rtol |y_i| + atol, for v plus the index-3 round-off floor 100 eps max|q| / h.
  double error(const State& coarse, const State& fine, double step) const {
    const double rtol = options.relative_tolerance, atol = options.absolute_tolerance;
    const auto n = fine.q.size();
    if (n == 0) return 0.0;
    const double floor = 100.0 * std::numeric_limits<double>::epsilon() *
                         std::max(fine.q.lpNorm<Eigen::Infinity>(), 1e-300) / step;
    double sum = 0.0;
    for (Eigen::Index i = 0; i < n; ++i) {
      const double eq = (fine.q(i) - coarse.q(i)) /
                        (rtol * std::max(std::abs(fine.q(i)), std::abs(coarse.q(i))) + atol);
      const double ev =
          (fine.v(i) - coarse.v(i)) /
          (rtol * std::max(std::abs(fine.v(i)), std::abs(coarse.v(i))) + atol + floor);
      sum += eq * eq + ev * ev;
    }
    return std::sqrt(sum / static_cast<double>(2 * n));
  }
};

AdaptiveRadau::AdaptiveRadau(const RadauOptions& radau, const AdaptiveOptions& adaptive) {
  validate(adaptive);
  impl_ = std::make_unique<Impl>(radau, adaptive);
}

AdaptiveRadau::~AdaptiveRadau() = default;
AdaptiveRadau::AdaptiveRadau(AdaptiveRadau&&) noexcept = default;
AdaptiveRadau& AdaptiveRadau::operator=(AdaptiveRadau&&) noexcept = default;

void AdaptiveRadau::advance(const ConstrainedSystem& system, State& state, double end_time) {
  Impl& w = *impl_;
  const AdaptiveOptions& o = w.options;
  if (!(end_time > state.time) || !std::isfinite(end_time)) {
    char text[128];
    std::snprintf(text, sizeof text, "end time %.9g s is not after the state's time %.9g s",
                  end_time, state.time);
    throw Error(text, "adaptive Radau IIA", "advance to a later time");
  }
  // A step that would leave less than 1e-3 of itself before end_time is stretched to it.
  const double tiny = 1e-12 * std::max(1.0, std::abs(end_time));
  w.advance_integral.setZero(w.halves.last_step_integral().size());
  while (state.time < end_time - tiny) {
    if (o.max_step > 0.0) w.h = std::min(w.h, o.max_step);
    const double remaining = end_time - state.time;
    const bool last = w.h >= remaining * (1.0 - 1e-3);
    const double h = last ? remaining : w.h;
    State coarse = state, fine = state;
    double err = 0.0;
    bool converged = true;
    try {
      w.count(w.whole.step(system, coarse, h));
      w.count(w.halves.step(system, fine, 0.5 * h));
      w.trial_integral = w.halves.last_step_integral();
      w.count(w.halves.step(system, fine, 0.5 * h));
      w.trial_integral += w.halves.last_step_integral();
      err = w.error(coarse, fine, h);
    } catch (const Error&) {
      converged = false;
    }
    if (converged && std::isfinite(err) && err <= 1.0) {
      ++w.stats.accepted;
      state = fine;
      w.advance_integral += w.trial_integral;
      if (last) state.time = end_time;  // no round-off left over
      const double factor =
          err > 0.0 ? std::min(o.max_growth,
                               std::max(o.min_shrink, o.safety * std::pow(err, -w.exponent)))
                    : o.max_growth;
      // Keep h when it would grow only a little: the Radau instances then keep their
      // factorisations (Hairer & Wanner's Radau5 does the same).
      if (!(factor >= 1.0 && factor < 1.2))
        w.h = h * factor;
      else
        w.h = h;
    } else {
      ++w.stats.rejected;
      if (!converged) ++w.stats.newton_failures;
      const double factor = converged && std::isfinite(err)
                                ? std::max(o.min_shrink, o.safety * std::pow(err, -w.exponent))
                                : 0.25;
      w.h = h * std::min(factor, 0.9);
    }
    if (w.h < o.min_step) {
      char text[256];
      std::snprintf(text, sizeof text,
                    "the step size fell to %.3g s (min_step %.3g s) at t = %.9g s%s", w.h,
                    o.min_step, state.time,
                    converged ? " to meet the error tolerance" : ": Newton does not converge");
      throw Error(text, "adaptive Radau IIA",
                  "check the model for a singularity at that time, loosen the tolerances or "
                  "lower min_step");
    }
  }
}

void AdaptiveRadau::set_integrand(Integrand integrand) {
  impl_->halves.set_integrand(std::move(integrand));
  impl_->advance_integral.setZero(impl_->halves.last_step_integral().size());
}

const Eigen::VectorXd& AdaptiveRadau::last_advance_integral() const {
  return impl_->advance_integral;
}

double AdaptiveRadau::step_size() const {
  return impl_->h;
}

const AdaptiveStatistics& AdaptiveRadau::statistics() const {
  return impl_->stats;
}

}  // namespace fsi::mbd
