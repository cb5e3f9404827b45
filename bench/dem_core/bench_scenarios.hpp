#pragma once
// Benchmark scenarios built with the public dem_core API (docs/spec.md 2.1 pellet bed, docs/spec.md 2.2 drum).
#include <cstdint>

#include "demfit/dem_core/simulation.hpp"

namespace demfit::bench {

/// Rotary drum of docs/spec.md 2.2 at scale factor s (R = s mm, Table 3 initial parameters), filled with
/// phi = 0.64 x 30 % of the drum volume, settled for `settle_time` [s], then set rotating at 60 RPM.
dem_core::Simulation make_drum(double scale, double settle_time, int threads);
/// Pellet bed of docs/spec.md 2.1 (R = 1.86 mm, 36 mm cylinder, ~1450 pellets) densified (frictionless
/// settle, at most `settle_time` [s]);
/// wall 0 = bottom, 1 = shell, 2 = piston (a disk just above the bed, fixed).
dem_core::Simulation make_pellet_bed(double normk, double sheark, double settle_time, int threads);
/// Wall-clock seconds for `steps` steps; `cpu` receives the process CPU seconds (all threads),
/// which is the better measure of single-thread cost on a shared, loaded machine.
double time_steps(dem_core::Simulation& sim, std::uint64_t steps, double* cpu = nullptr);
/// Process CPU seconds so far (all threads).
double cpu_seconds();
/// Wall-clock seconds to push the piston down at `speed` [m/s] until the piston pressure reaches
/// `pressure` [Pa]; returns the seconds and reports the simulated time and final pressure.
double time_compression(dem_core::Simulation& sim, double speed, double pressure, double& simulated, double& reached,
                        double* cpu = nullptr);

}  // namespace demfit::bench
