// Slab order: the slab index (21 bits) above the interleaved bits of the two other cell
// coordinates (21 bits each).
#include "particle_order.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "bounding_box.hpp"

namespace demfit::dem_core {
namespace {

/// Spread the low 21 bits of x so that bit b lands at bit 2b.
std::uint64_t spread_bits(std::uint64_t x) {
  x &= 0x1fffffULL;
  x = (x | x << 16) & 0x0000ffff0000ffffULL;
  x = (x | x << 8) & 0x00ff00ff00ff00ffULL;
  x = (x | x << 4) & 0x0f0f0f0f0f0f0f0fULL;
  x = (x | x << 2) & 0x3333333333333333ULL;
  x = (x | x << 1) & 0x5555555555555555ULL;
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

/// Axis of the largest extent (0 x, 1 y, 2 z; ties to the lower axis).
int longest_axis(const Bounds& b) {
  const double ex = b.high.x - b.low.x, ey = b.high.y - b.low.y, ez = b.high.z - b.low.z;
  if (ex >= ey && ex >= ez) return 0;
  return ey >= ez ? 1 : 2;
}

double component(const Vec3& v, int axis) { return axis == 0 ? v.x : axis == 1 ? v.y : v.z; }

}  // namespace

std::vector<std::uint32_t> slab_order(std::span<const Vec3> positions, double cell, int threads) {
  const std::size_t n = positions.size();
  if (n < 2 || !(cell > 0.0)) return {};
  const auto count = static_cast<std::int64_t>(n);
  const Bounds box = bounding_box(positions, threads);
  const int across = longest_axis(box), first = across == 0 ? 1 : 0, second = across == 2 ? 1 : 2;
  const double inverse = 1.0 / cell;
  std::vector<std::pair<std::uint64_t, std::uint32_t>> keys(n);
#pragma omp parallel for schedule(static) num_threads(threads) if (threads > 1)
  for (std::int64_t k = 0; k < count; ++k) {
    const auto i = static_cast<std::size_t>(k);
    const Vec3& p = positions[i];
    const std::uint64_t slab = cell_coordinate(component(p, across), component(box.low, across), inverse);
    keys[i] = {slab << 42 | spread_bits(cell_coordinate(component(p, first), component(box.low, first), inverse)) |
                   spread_bits(cell_coordinate(component(p, second), component(box.low, second), inverse)) << 1,
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
