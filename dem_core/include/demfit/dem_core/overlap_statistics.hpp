#pragma once
// How far the spheres interpenetrate. A soft normal spring (small NORMK) lets a bed reach a
// density by overlap instead of by arrangement, and an identification may exploit that (the
// Table 3 coarse bed, docs/measurements/2026-12-06-table3-soft-normk-and-transfer.md); these figures let a user judge an answer's
// physics (a common DEM guideline keeps overlaps near 1 % of the radius).
#include <cstddef>

namespace demfit::dem_core {

class Simulation;

struct OverlapStatistics {
  std::size_t contacts = 0;            ///< particle pairs touching now
  double mean_relative_overlap = 0.0;  ///< mean over those pairs of overlap / the smaller radius [-]
  double max_relative_overlap = 0.0;   ///< largest overlap / the smaller radius [-]
};

/// Particle–particle overlaps at the simulation's current positions (walls not counted).
[[nodiscard]] OverlapStatistics pair_overlap_statistics(const Simulation& simulation);

}  // namespace demfit::dem_core
