#pragma once
// demfit vs LIGGGHTS on the Hertz benchmark drum from the same settled, flowing bed: particle-steps/s of
// each code on 1 core (1 thread vs 1 rank) and 2 cores (2 threads vs the best 2-rank split),
// median of `repeats` interleaved repeats, each printed with the load average.
#include <filesystem>
#include <string>

#include "liggghts_drum.hpp"

namespace demfit::bench {

struct DrumComparisonOptions {
  long steps = 10000;  ///< timed steps per run
  int repeats = 3;
  double settle_time = 0.3;      ///< [s] drum at rest
  double spin_up_time = 1.0;     ///< [s] turning before the timed runs (steady flow)
  std::filesystem::path dir;     ///< where the LIGGGHTS files go
  DrumMeshShape mesh{};          ///< LIGGGHTS' drum mesh
  bool liggghts = true;          ///< false: time demfit only (e.g. comparing OpenMP waiting policies)
  bool demfit_mesh = false;      ///< demfit on the same STL drum as LIGGGHTS (one rotating mesh wall)
  std::string memory_retention;  ///< how freed memory is handled (printed)
};

void compare_drum_with_liggghts(const DrumComparisonOptions& options);

}  // namespace demfit::bench
