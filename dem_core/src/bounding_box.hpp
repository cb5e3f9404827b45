#pragma once
// The particles' axis-aligned bounding box, shared by the cell grid of the neighbour list and the
// slab order (both anchor their cells at its lowest corner). Internal to dem_core.
#include <algorithm>
#include <cstdint>
#include <limits>
#include <span>

#include "demfit/dem_core/vec3.hpp"

namespace demfit::dem_core {

struct Bounds {
  Vec3 low, high;
};

/// min and max are order-independent, so the box is the same for any thread count.
inline Bounds bounding_box(std::span<const Vec3> positions, int threads) {
  const auto count = static_cast<std::int64_t>(positions.size());
  double lo_x = std::numeric_limits<double>::max(), lo_y = lo_x, lo_z = lo_x;
  double hi_x = std::numeric_limits<double>::lowest(), hi_y = hi_x, hi_z = hi_x;
#pragma omp parallel for schedule(static) reduction(min                                               \
                                                    : lo_x, lo_y, lo_z) reduction(max                 \
                                                                                  : hi_x, hi_y, hi_z) \
    num_threads(threads) if (threads > 1)
  for (std::int64_t k = 0; k < count; ++k) {
    const Vec3& p = positions[static_cast<std::size_t>(k)];
    lo_x = std::min(lo_x, p.x);
    lo_y = std::min(lo_y, p.y);
    lo_z = std::min(lo_z, p.z);
    hi_x = std::max(hi_x, p.x);
    hi_y = std::max(hi_y, p.y);
    hi_z = std::max(hi_z, p.z);
  }
  return {{lo_x, lo_y, lo_z}, {hi_x, hi_y, hi_z}};
}

}  // namespace demfit::dem_core
