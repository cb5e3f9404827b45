// The run budget (see run_budget.hpp).
#include "run_budget.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <string>

namespace demfit::cases::detail {
namespace {

std::string duration_text(double seconds) {
  char text[64];
  if (seconds < 120.0)
    std::snprintf(text, sizeof text, "%.0f s", seconds);
  else if (seconds < 7200.0)
    std::snprintf(text, sizeof text, "%.0f min", seconds / 60.0);
  else if (seconds < 2.0 * 86400.0)
    std::snprintf(text, sizeof text, "%.1f h", seconds / 3600.0);
  else
    std::snprintf(text, sizeof text, "%.3g days", seconds / 86400.0);
  return text;
}

bool long_runs_allowed() {
  const char* value = std::getenv(kAllowLongRunsVariable);
  return value && *value && std::string(value) != "0";
}

}  // namespace

void check_run_budget(const std::string& stage, double particles, double simulated_seconds, double time_step,
                      const CaseRunOptions& options) {
  const double steps = std::ceil(simulated_seconds / time_step);
  const double estimate = particles * steps / kAssumedParticleStepsPerSecond;
  char text[400];
  if (!std::isfinite(estimate) || estimate > kMaxEstimatedWallSeconds) {
    if (long_runs_allowed() && std::isfinite(estimate)) {
      if (options.progress)
        std::fprintf(stderr, "%s: %.3g steps of %.3g s for %.0f particles, estimated %s (allowed by %s)\n",
                     stage.c_str(), steps, time_step, particles, duration_text(estimate).c_str(),
                     kAllowLongRunsVariable);
      return;
    }
    std::snprintf(text, sizeof text,
                  "%s: %.3g s simulated at a time step of %.3g s is %.3g steps for %.0f particles, estimated %s on "
                  "one core (limit %s): shorten the run, check the time step, Young's modulus and density, or set "
                  "%s=1 to run it anyway",
                  stage.c_str(), simulated_seconds, time_step, steps, particles, duration_text(estimate).c_str(),
                  duration_text(kMaxEstimatedWallSeconds).c_str(), kAllowLongRunsVariable);
    throw std::runtime_error(text);
  }
  if (options.progress && estimate > 10.0)
    std::fprintf(stderr, "%s: %.3g steps of %.3g s for %.0f particles, estimated at most %s on one core\n",
                 stage.c_str(), steps, time_step, particles, duration_text(estimate).c_str());
}

void check_wall_travel_per_step(const std::string& field, double wall_speed, double radius, double time_step) {
  const double travel = std::abs(wall_speed) * time_step;
  if (!(travel <= 0.5 * radius)) {
    char text[320];
    std::snprintf(text, sizeof text,
                  "'%s': the wall moves %.3g m per time step (%.3g m/s x %.3g s), more than half the smallest "
                  "particle radius (%.3g m): contacts would be skipped; lower the speed or the time step",
                  field.c_str(), travel, wall_speed, time_step, radius);
    throw std::runtime_error(text);
  }
}

}  // namespace demfit::cases::detail
