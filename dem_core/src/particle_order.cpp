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

}  // namespace

std::vector<std::uint32_t> morton_order(std::span<const Vec3> positions, double cell) {
  const std::size_t n = positions.size();
  if (n < 2 || !(cell > 0.0)) return {};
  Vec3 lo{std::numeric_limits<double>::max(), std::numeric_limits<double>::max(), std::numeric_limits<double>::max()};
  for (const Vec3& p : positions) lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
  const double inverse = 1.0 / cell;
  std::vector<std::pair<std::uint64_t, std::uint32_t>> keys(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3& p = positions[i];
    const std::uint64_t code = spread_bits(cell_coordinate(p.x, lo.x, inverse)) |
                               spread_bits(cell_coordinate(p.y, lo.y, inverse)) << 1 |
                               spread_bits(cell_coordinate(p.z, lo.z, inverse)) << 2;
    keys[i] = {code, static_cast<std::uint32_t>(i)};
  }
  if (std::is_sorted(keys.begin(), keys.end())) return {};
  std::sort(keys.begin(), keys.end());  // (code, old index): unique keys, one result
  std::vector<std::uint32_t> order(n);
  for (std::size_t s = 0; s < n; ++s) order[s] = keys[s].second;
  return order;
}

}  // namespace demfit::dem_core
