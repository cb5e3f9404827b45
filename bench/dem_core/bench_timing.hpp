#pragma once
// Small timing helpers shared by the bench_dem sections.
#include <cstdint>
#include <string>
#include <vector>

#include "demfit/dem_core/simulation.hpp"

namespace demfit::bench {

/// Median of the values (the mean of the middle two for an even count); 0 for none.
double median(std::vector<double> values);
/// "load 1.23 1.10 0.98" (1, 5, 15 min averages from getloadavg).
std::string load_average();
/// Minor page faults of this process so far (getrusage): fresh pages the kernel handed over.
std::uint64_t minor_page_faults();
/// Microseconds per fresh page on this host: 280 KiB mapped, touched and unmapped 500 times (the
/// size of a list's partner array on the Hertz benchmark drum).
double fresh_page_microseconds();
/// Wall-clock seconds of sim.run_steps(steps).
double wall_seconds_for_steps(dem_core::Simulation& sim, std::uint64_t steps);

}  // namespace demfit::bench
