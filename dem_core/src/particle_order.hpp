#pragma once
// Spatial ordering of particles, so that particles close in space are close in memory (the pair
// loop and the per-particle gather then touch few cache lines even when the bed has mixed; issue
// 16: past the last-level cache the kernel was memory-bound) AND so that T threads' contiguous
// chunks of the order meet across planes: slabs one cell thick across the longest extent of the
// bed, Morton (Z) order of the cells within a slab. A chunk boundary then lies inside one slab,
// and the pairs crossing it are those of about one plane section of the bed; a 3-D Morton order
// cuts the bed along a staircase of octant faces. On the issue-16 drum 2.2 % of the list's pairs
// cross the middle in slab order against 2.4 % in Morton order (bench_dem --only drum prints it;
// bench/dem_core/measured/drum_2026-12-04_ab_slab_order.txt).
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "demfit/dem_core/vec3.hpp"

namespace demfit::dem_core {

/// Permutation order[new] = old that sorts the particles by (slab, 2-D Morton code of the cell
/// in the slab); cells have edge `cell` [m] > 0 on a grid anchored at the lowest corner, slabs
/// are one cell thick across the axis with the largest extent (ties: x, then y). Particles of one
/// cell keep ascending old index, so the result depends on the positions only (deterministic, any
/// thread count). Returns an empty vector when the current order already is that order. `threads`
/// share the work; the result does not depend on them.
std::vector<std::uint32_t> slab_order(std::span<const Vec3> positions, double cell, int threads = 1);

/// v[new] = old v[order[new]], applied to blocks of `block` consecutive elements
/// (per-(particle, wall) arrays have `walls` elements per particle). Empty vectors stay empty.
template <class T>
void apply_order(std::vector<T>& v, const std::vector<std::uint32_t>& order, std::size_t block = 1, int threads = 1) {
  if (v.empty() || block == 0) return;
  std::vector<T> moved(v.size());
  const auto count = static_cast<std::int64_t>(order.size());
#pragma omp parallel for schedule(static) num_threads(threads) if (threads > 1)
  for (std::int64_t k = 0; k < count; ++k) {
    const auto s = static_cast<std::size_t>(k);
    for (std::size_t b = 0; b < block; ++b) moved[s * block + b] = v[order[s] * block + b];
  }
  v.swap(moved);
}

}  // namespace demfit::dem_core
