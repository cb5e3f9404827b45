#include "demfit/dem_core/overlap_statistics.hpp"

#include <algorithm>
#include <cstdint>

#include "demfit/dem_core/neighbor_list.hpp"
#include "demfit/dem_core/simulation.hpp"

namespace demfit::dem_core {

OverlapStatistics pair_overlap_statistics(const Simulation& simulation) {
  OverlapStatistics stats;
  const auto positions = simulation.positions();
  const auto radii = simulation.radii();
  if (positions.empty()) return stats;
  // A list of its own, built now: the simulation's list may predate the last drift.
  NeighborList list;
  const double skin = 1e-6 * *std::max_element(radii.begin(), radii.end());
  list.build(positions, radii, skin, 1, false);
  const auto rows = list.row_offsets();
  const auto second = list.second();
  double sum = 0.0;
  for (std::size_t i = 0; i + 1 < rows.size(); ++i) {
    for (std::uint32_t p = rows[i]; p < rows[i + 1]; ++p) {
      const std::size_t j = second[p];
      const double overlap = radii[i] + radii[j] - norm(positions[j] - positions[i]);
      if (overlap <= 0.0) continue;
      const double relative = overlap / std::min(radii[i], radii[j]);
      ++stats.contacts;
      sum += relative;
      stats.max_relative_overlap = std::max(stats.max_relative_overlap, relative);
    }
  }
  if (stats.contacts > 0) stats.mean_relative_overlap = sum / static_cast<double>(stats.contacts);
  return stats;
}

}  // namespace demfit::dem_core
