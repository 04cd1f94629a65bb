#pragma once
// The settling drag of the equilibration (docs/theory.md, "Settling the fluid"): a velocity drag
// -lambda m v on every particle while the structure is held, removed before script 2. Pure
// arithmetic, no LIGGGHTS: the client resolves the scene's choice with it.

#include <cstdint>

namespace fsi::client {

// The drag takes at most this fraction of a particle's velocity per step (lambda dt <= 0.1): well
// inside the explicit limit lambda dt < 1 of a monotone decay, so that the drag never reverses a
// velocity and stays accurate to about 5 %.
inline constexpr double kDragPerStepLimit = 0.1;

struct SettlingDrag {
  double column_frequency = 0.0;  // omega = pi sqrt(|g| / H) [1/s]; 0 without gravity or height
  double critical_rate = 0.0;     // 2 omega: critical damping of that mode [1/s]
  double stability_limit = 0.0;   // kDragPerStepLimit / dt [1/s]
  double rate = 0.0;              // the drag applied: min(critical_rate, stability_limit) [1/s]
  bool limited_by_time_step = false;
};

// The automatic drag of a column of height H [m] under gravity |g| [m/s^2], stepped by dt [s]:
// critical damping of the column's slowest gravity mode, omega = pi sqrt(|g| / H), bounded by the
// time step. No drag (rate 0) without gravity or without height.
SettlingDrag automatic_settling_drag(double column_height, double gravity, double time_step);

// The equilibration runs in chunks of this many steps (the last one shorter), so that rank 0 can
// report its progress between them: at least 1 000 steps (LIGGGHTS' per-run overhead stays
// small), at most about 100 chunks. The same on every rank (each rank issues the same runs); a
// chunk after the first continues without set-up, as one long run would.
std::uint64_t equilibration_chunk(std::uint64_t total_steps);

}  // namespace fsi::client
