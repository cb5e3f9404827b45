#pragma once
// The run budget: before a simulation starts, its step count and an estimated wall time from
// the particle count, and a refusal of runs that would take longer than a day (docs/cases.md
// "Run budget"). A typo in a duration, a time step of 1e-12 s or an absurd modulus would
// otherwise run silently for days.
#include <string>

#include "demfit/cases/case_runner.hpp"
#include "demfit/cases/case_spec.hpp"

namespace demfit::cases::detail {

// Throughput the estimate assumes: particle-steps per second on one core, below what the kernel
// reaches on a drum (bench/dem_core prints the measured figure), so the estimate errs long.
inline constexpr double kAssumedParticleStepsPerSecond = 3.0e6;
// Largest estimated wall time run without asking [s]: one day.
inline constexpr double kMaxEstimatedWallSeconds = 86400.0;
// Environment variable that lifts the limit (any non-empty value other than "0").
inline constexpr const char* kAllowLongRunsVariable = "DEMFIT_ALLOW_LONG_RUNS";

// Throws, naming the estimate and the way to allow it, when `particles` particles over
// `simulated_seconds` [s] at `time_step` [s] are estimated above kMaxEstimatedWallSeconds;
// prints the step count and the estimate to stderr when `options.progress` is set.
void check_run_budget(const std::string& stage, double particles, double simulated_seconds, double time_step,
                      const CaseRunOptions& options);

// Throws when a wall moving at `wall_speed` [m/s] travels more than half the smallest
// particle radius `radius` [m] in one `time_step` [s] (the soft springs of the Table 3 studies
// move the drum shell by a fifth of a radius per step; rpm 1e6 by revolutions): contacts would
// be skipped, and torque and angle would be plausible-looking noise. `field` names the input
// that sets the speed.
void check_wall_travel_per_step(const std::string& field, double wall_speed, double radius, double time_step);

}  // namespace demfit::cases::detail
