#include <cmath>
#include <cstdio>
#include <string>

#include "fsi/scene/scene.hpp"

namespace fsi::scene {
namespace {

std::string tolerances(const SolverSettings& solver) {
  char text[96];
  std::snprintf(text, sizeof text, "rtol %g, atol %g", solver.relative_tolerance,
                solver.absolute_tolerance);
  return text;
}

}  // namespace

std::string SolverSettings::integrator_description(bool coupled) const {
  const std::string tableau =
      mbd::butcher_tableau(family, stages).name + ", " + std::to_string(stages) + " stages" +
      (constraint_form == mbd::ConstraintForm::Index2 ? ", index-2 constraints" : "");
  if (coupled) {
    return substeps > 1
               ? tableau + ", " + std::to_string(substeps) + " fluid steps per structure step"
               : tableau;
  }
  switch (method) {
    case IntegrationMethod::FixedStep:
      return tableau;
    case IntegrationMethod::AdaptiveRadau:
      return "adaptive " + tableau + " (step doubling, " + tolerances(*this) + ")";
    case IntegrationMethod::Ida:
      return "SUNDIALS IDA (BDF orders 1-5, " + tolerances(*this) + ")";
  }
  return tableau;
}

std::uint64_t SolverSettings::step_count() const {
  return static_cast<std::uint64_t>(std::llround(end_time / step_size));
}

}  // namespace fsi::scene
