#pragma once
// Meshed against analytic drum: the Hertz drum of hertz_drum.hpp settled and spun up once with
// its analytic walls (cylinder shell and two disks), then continued from the same particle state
// twice: with the analytic walls and with one rotating mesh wall (drum_mesh.hpp's STL geometry,
// read back through dem_core::parse_stl). Prints mean drive torque, bed tilt and cost of both.
#include <cstdint>
#include <memory>

#include "demfit/dem_core/simulation.hpp"
#include "demfit/dem_core/triangle_mesh.hpp"
#include "hertz_drum.hpp"

namespace demfit::bench {

struct MeshDrumOptions {
  double settle_time = 0.15;   ///< [s] at rest, analytic walls
  double spin_up_time = 0.1;   ///< [s] turning, analytic walls (bench_dem --spin-up)
  std::uint64_t steps = 2000;  ///< measured steps of each run, after the same restart (bench_dem --steps)
  int segments = 360, shell_rings = 4, cap_rings = 20;  ///< bench_dem --mesh
  int threads = 1;
  int repeats = 3;  ///< analytic and meshed runs alternate; the median cost ratio is printed (--repeats)
};

void compare_meshed_drum(const MeshDrumOptions& options);

/// The spec's settings for a restarted drum (its law, step, skin, gravity along -y).
dem_core::SimulationSettings drum_restart_settings(const HertzDrumSpec& spec, int threads);

/// The same particles (positions, velocities, spins; contact histories start afresh, as
/// LIGGGHTS' read_data gives them) in a new drum turning at the spec's speed under `settings`,
/// with the analytic walls (cylinder shell, two disks) or, when `mesh` is set, one mesh wall.
dem_core::Simulation restart_drum(const dem_core::Simulation& from, const HertzDrumSpec& spec,
                                  const dem_core::SimulationSettings& settings,
                                  const std::shared_ptr<const dem_core::TriangleMesh>& mesh);

}  // namespace demfit::bench
