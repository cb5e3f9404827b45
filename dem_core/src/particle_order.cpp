// Morton order: interleave the bits of the three cell coordinates (21 bits each).
#include "particle_order.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace demfit::dem_core {
namespace {

/// Spread the low 21 bits of x so that bit b lands at bit 3b.
std::uint64_t spread_bits(std::uint64_t x) {
  x &= 0x1fffffULL;
  x = (x | x << 32) & 0x1f00000000ffffULL;
  x = (x | x << 16) & 0x1f0000ff0000ffULL;
  x = (x | x << 8) & 0x100f00f00f00f00fULL;
  x = (x | x << 4) & 0x10c30c30c30c30c3ULL;
  x = (x | x << 2) & 0x1249249249249249ULL;
  return x;
}

std::uint64_t cell_coordinate(double value, double origin, double inverse_cell) {
  const double c = std::floor((value - origin) * inverse_cell);
  return static_cast<std::uint64_t>(std::clamp(c, 0.0, static_cast<double>(0x1fffff)));
}

/// Sorts (code, old index) pairs: all keys differ, so every sort gives one result and the
/// threads' pieces (sorted at once, then merged) give exactly what one std::sort would.
void sort_unique_keys(std::vector<std::pair<std::uint64_t, std::uint32_t>>& keys, int threads) {
  const std::size_t n = keys.size();
  if (threads < 2 || n < 4096) {
    std::sort(keys.begin(), keys.end());
    return;
  }
  const auto middle = keys.begin() + static_cast<std::ptrdiff_t>(n / 2);
#pragma omp parallel for schedule(static, 1) num_threads(2)
  for (int half = 0; half < 2; ++half) half == 0 ? std::sort(keys.begin(), middle) : std::sort(middle, keys.end());
  std::inplace_merge(keys.begin(), middle, keys.end());
}

}  // namespace

std::vector<std::uint32_t> morton_order(std::span<const Vec3> positions, double cell, int threads) {
  const std::size_t n = positions.size();
  if (n < 2 || !(cell > 0.0)) return {};
  const auto count = static_cast<std::int64_t>(n);
  // min is order-independent: the same corner for any thread count.
  double lo_x = std::numeric_limits<double>::max(), lo_y = lo_x, lo_z = lo_x;
#pragma omp parallel for schedule(static) reduction(min : lo_x, lo_y, lo_z) num_threads(threads) if (threads > 1)
  for (std::int64_t k = 0; k < count; ++k) {
    const Vec3& p = positions[static_cast<std::size_t>(k)];
    lo_x = std::min(lo_x, p.x);
    lo_y = std::min(lo_y, p.y);
    lo_z = std::min(lo_z, p.z);
  }
  const double inverse = 1.0 / cell;
  std::vector<std::pair<std::uint64_t, std::uint32_t>> keys(n);
#pragma omp parallel for schedule(static) num_threads(threads) if (threads > 1)
  for (std::int64_t k = 0; k < count; ++k) {
    const auto i = static_cast<std::size_t>(k);
    const Vec3& p = positions[i];
    keys[i] = {spread_bits(cell_coordinate(p.x, lo_x, inverse)) |
                   spread_bits(cell_coordinate(p.y, lo_y, inverse)) << 1 |
                   spread_bits(cell_coordinate(p.z, lo_z, inverse)) << 2,
               static_cast<std::uint32_t>(i)};
  }
  if (std::is_sorted(keys.begin(), keys.end())) return {};
  sort_unique_keys(keys, threads);
  std::vector<std::uint32_t> order(n);
#pragma omp parallel for schedule(static) num_threads(threads) if (threads > 1)
  for (std::int64_t k = 0; k < count; ++k)
    order[static_cast<std::size_t>(k)] = keys[static_cast<std::size_t>(k)].second;
  return order;
}

}  // namespace demfit::dem_core
