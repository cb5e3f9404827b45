#pragma once
// Capacity for per-pair arrays rebuilt with the neighbour list (its partners, the carried contact
// histories). Internal to dem_core.
#include <cstddef>

namespace demfit::dem_core {

/// Capacity for `pairs` entries with room for a list that grows a little at the next rebuild
/// (a reallocation would hold the old and the new array at once: the peak memory of a rebuild).
inline std::size_t with_slack(std::size_t pairs) { return pairs + pairs / 16 + 64; }

}  // namespace demfit::dem_core
