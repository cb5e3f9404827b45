// Cell-grid construction of the Verlet half list (O(N)): particles are counting-sorted into cells
// of edge >= 2 R_max + skin, so all partners of a particle lie in its 27 surrounding cells.
#include "demfit/dem_core/neighbor_list.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <omp.h>

#include "bounding_box.hpp"
#include "list_slack.hpp"

namespace demfit::dem_core {
namespace {

struct CellGrid {
  Vec3 origin;
  double inverse_edge = 0.0;
  std::int64_t nx = 1, ny = 1, nz = 1;
  std::vector<std::uint32_t> cell_start;      // size cells + 1
  std::vector<std::uint32_t> cell_particles;  // particle indices, ascending inside each cell

  [[nodiscard]] std::int64_t coordinate(double value, double origin_value, std::int64_t n) const {
    const auto c = static_cast<std::int64_t>((value - origin_value) * inverse_edge);
    return std::clamp<std::int64_t>(c, 0, n - 1);
  }
  [[nodiscard]] std::int64_t cell_of(const Vec3& p) const {
    return (coordinate(p.z, origin.z, nz) * ny + coordinate(p.y, origin.y, ny)) * nx + coordinate(p.x, origin.x, nx);
  }
};

CellGrid make_grid(std::span<const Vec3> positions, double edge, int threads) {
  const Bounds box = bounding_box(positions, threads);
  const Vec3 lo = box.low, hi = box.high;
  // Cap the cell count (escaped particles would otherwise blow up the grid): at most ~4N cells.
  const double limit = 4.0 * static_cast<double>(positions.size()) + 64.0;
  auto count = [&](double e) {
    return (std::floor((hi.x - lo.x) / e) + 1) * (std::floor((hi.y - lo.y) / e) + 1) *
           (std::floor((hi.z - lo.z) / e) + 1);
  };
  while (count(edge) > limit) edge *= 1.26;
  CellGrid grid;
  grid.origin = lo;
  grid.inverse_edge = 1.0 / edge;
  grid.nx = static_cast<std::int64_t>(std::floor((hi.x - lo.x) / edge)) + 1;
  grid.ny = static_cast<std::int64_t>(std::floor((hi.y - lo.y) / edge)) + 1;
  grid.nz = static_cast<std::int64_t>(std::floor((hi.z - lo.z) / edge)) + 1;
  const std::size_t cells = static_cast<std::size_t>(grid.nx * grid.ny * grid.nz);
  std::vector<std::uint32_t> cell_of(positions.size());
  grid.cell_start.assign(cells + 1, 0);
  for (std::size_t i = 0; i < positions.size(); ++i) {
    cell_of[i] = static_cast<std::uint32_t>(grid.cell_of(positions[i]));
    ++grid.cell_start[cell_of[i] + 1];
  }
  for (std::size_t c = 0; c < cells; ++c) grid.cell_start[c + 1] += grid.cell_start[c];
  grid.cell_particles.resize(positions.size());
  std::vector<std::uint32_t> fill(grid.cell_start.begin(), grid.cell_start.end() - 1);
  for (std::size_t i = 0; i < positions.size(); ++i)
    grid.cell_particles[fill[cell_of[i]]++] = static_cast<std::uint32_t>(i);
  return grid;
}

/// Visit every j > i within the cutoff of i; `emit(j)` is called in a deterministic order.
template <class Emit>
void for_each_partner(const CellGrid& g, std::span<const Vec3> x, std::span<const double> r, double skin, std::size_t i,
                      Emit&& emit) {
  const Vec3& p = x[i];
  const std::int64_t cx = g.coordinate(p.x, g.origin.x, g.nx);
  const std::int64_t cy = g.coordinate(p.y, g.origin.y, g.ny);
  const std::int64_t cz = g.coordinate(p.z, g.origin.z, g.nz);
  for (std::int64_t z = std::max<std::int64_t>(cz - 1, 0); z <= std::min(cz + 1, g.nz - 1); ++z)
    for (std::int64_t y = std::max<std::int64_t>(cy - 1, 0); y <= std::min(cy + 1, g.ny - 1); ++y)
      for (std::int64_t xx = std::max<std::int64_t>(cx - 1, 0); xx <= std::min(cx + 1, g.nx - 1); ++xx) {
        const std::size_t c = static_cast<std::size_t>((z * g.ny + y) * g.nx + xx);
        const std::uint32_t end = g.cell_start[c + 1];
        // A cell lists its particles in ascending index: one look at its last decides whether any
        // is a partner (j > i), and the first j > i is found without testing the smaller ones
        // one by one (in spatial order about half the cells around i hold only smaller indices).
        if (end == g.cell_start[c] || g.cell_particles[end - 1] <= i) continue;
        const auto first = std::upper_bound(g.cell_particles.begin() + g.cell_start[c], g.cell_particles.begin() + end,
                                            static_cast<std::uint32_t>(i));
        for (auto k = static_cast<std::uint32_t>(first - g.cell_particles.begin()); k < end; ++k) {
          const std::uint32_t j = g.cell_particles[k];
          const double cutoff = r[i] + r[j] + skin;
          if (norm2(x[j] - p) < cutoff * cutoff) emit(j);
        }
      }
}

constexpr std::size_t kBuildBlockRows = 256;
constexpr std::size_t kBuildWaves = 8;             // of blocks; the buffers hold one wave's pairs
constexpr std::size_t kBlocksPerWaveAtLeast = 16;  // up to kBuildWaves waves of at least this many blocks

/// Where each block of a wave begins in the buffer of the thread that took it.
struct BlockPlace {
  std::uint32_t thread = 0;
  std::size_t start = 0;
};

// One walk over the candidates of blocks [first_block, last_block): the threads take blocks as they
// come and append their sorted rows to their own buffer; then the wave's row counts are summed and
// each block is copied after the list so far.
void collect_wave(const CellGrid& grid, std::span<const Vec3> positions, std::span<const double> radii, double skin,
                  std::size_t first_block, std::size_t last_block, std::vector<std::vector<std::uint32_t>>& partners,
                  std::vector<BlockPlace>& place, std::vector<std::uint32_t>& row_offsets,
                  std::vector<std::uint32_t>& second) {
  const std::size_t n = positions.size();
  const auto threads = static_cast<int>(partners.size());
  const auto first = static_cast<std::int64_t>(first_block), last = static_cast<std::int64_t>(last_block);
#pragma omp parallel num_threads(threads) if (threads > 1)
  {
    const auto thread = static_cast<std::uint32_t>(omp_get_thread_num());
    // Appended to as a local: the threads' vectors side by side in `partners` share a cache line,
    // and every append would take it from the other thread.
    std::vector<std::uint32_t> mine;
    mine.swap(partners[thread]);
    mine.clear();
#pragma omp for schedule(dynamic, 1) nowait
    for (std::int64_t b = first; b < last; ++b) {
      const auto block = static_cast<std::size_t>(b);
      place[block - first_block] = {thread, mine.size()};
      for (std::size_t i = block * kBuildBlockRows; i < std::min(n, (block + 1) * kBuildBlockRows); ++i) {
        const std::size_t row_start = mine.size();
        for_each_partner(grid, positions, radii, skin, i, [&](std::uint32_t j) { mine.push_back(j); });
        std::sort(mine.begin() + static_cast<std::ptrdiff_t>(row_start), mine.end());
        row_offsets[i + 1] = static_cast<std::uint32_t>(mine.size() - row_start);
      }
    }
    partners[thread].swap(mine);
  }
  const std::size_t row_end = std::min(n, last_block * kBuildBlockRows);
  for (std::size_t i = first_block * kBuildBlockRows; i < row_end; ++i) row_offsets[i + 1] += row_offsets[i];
  second.resize(row_offsets[row_end]);
#pragma omp parallel for schedule(static) num_threads(threads) if (threads > 1)
  for (std::int64_t b = first; b < last; ++b) {
    const auto block = static_cast<std::size_t>(b);
    const std::uint32_t begin = row_offsets[block * kBuildBlockRows];
    const std::uint32_t end = row_offsets[std::min(n, (block + 1) * kBuildBlockRows)];
    const BlockPlace& at = place[block - first_block];
    const auto from = partners[at.thread].begin() + static_cast<std::ptrdiff_t>(at.start);
    std::copy(from, from + (end - begin), second.begin() + begin);
  }
}

// The half list in one walk over the candidates, in waves of blocks of rows (collect_wave).
// Counting first and walking again to fill checked every candidate's distance twice; the buffers
// of one wave cost 4 bytes per pair of that wave (1/8 of the list from 32,768 particles on, 1/2 at
// 8,192). `second`
// is reserved from `expected_pairs` (the previous list's count) or, when that is 0, from the first
// wave, so that it rarely grows. A row's partners are a set and each row is sorted, so the list is
// the same for any thread count, any assignment of blocks to threads and any `expected_pairs`.
void collect_partners(const CellGrid& grid, std::span<const Vec3> positions, std::span<const double> radii, double skin,
                      int threads, std::size_t expected_pairs, std::vector<std::uint32_t>& row_offsets,
                      std::vector<std::uint32_t>& second) {
  const std::size_t blocks = (positions.size() + kBuildBlockRows - 1) / kBuildBlockRows;
  const std::size_t waves = std::clamp<std::size_t>(blocks / kBlocksPerWaveAtLeast, 1, kBuildWaves);
  const std::size_t per_wave = (blocks + waves - 1) / waves;
  if (expected_pairs > 0) second.reserve(with_slack(expected_pairs));
  std::vector<std::vector<std::uint32_t>> partners(static_cast<std::size_t>(threads));
  std::vector<BlockPlace> place(per_wave);
  for (std::size_t first = 0; first < blocks; first += per_wave) {
    const std::size_t last = std::min(blocks, first + per_wave);
    collect_wave(grid, positions, radii, skin, first, last, partners, place, row_offsets, second);
    if (first == 0 && expected_pairs == 0 && waves > 1) {
      const std::size_t estimate = second.size() * blocks / last;
      second.reserve(estimate + estimate / 8 + 64);
    }
  }
}

}  // namespace

void NeighborList::build(std::span<const Vec3> positions, std::span<const double> radii, double skin, int threads,
                         bool transposed, std::size_t expected_pairs) {
  if (!(skin > 0.0)) throw std::runtime_error("neighbour list skin must be > 0");
  const std::size_t n = positions.size();
  skin_ = skin;
  ++build_count_;
  reference_positions_.assign(positions.begin(), positions.end());
  row_offsets_.assign(n + 1, 0);
  second_.clear();
  column_offsets_ = decltype(column_offsets_)();  // frees the storage (`= {}` would keep it)
  column_pairs_ = decltype(column_pairs_)();
  if (transposed) column_offsets_.assign(n + 1, 0);
  if (n == 0) return;
  const double r_max = *std::max_element(radii.begin(), radii.end());
  const CellGrid grid = make_grid(positions, 2.0 * r_max + skin, std::max(threads, 1));
  collect_partners(grid, positions, radii, skin, std::max(threads, 1), expected_pairs, row_offsets_, second_);
  const std::size_t pairs = second_.size();
  if (!transposed) return;
  // Transposed index; pairs are visited in ascending first member, so columns come out sorted.
  for (std::size_t p = 0; p < pairs; ++p) ++column_offsets_[second_[p] + 1];
  for (std::size_t j = 0; j < n; ++j) column_offsets_[j + 1] += column_offsets_[j];
  column_pairs_.resize(pairs);
  std::vector<std::uint32_t> fill(column_offsets_.begin(), column_offsets_.end() - 1);
  for (std::size_t p = 0; p < pairs; ++p) column_pairs_[fill[second_[p]]++] = static_cast<std::uint32_t>(p);
}

void NeighborList::keep_rows_only() {
  column_offsets_ = decltype(column_offsets_)();            // frees the storage (`= {}` would keep it)
  column_pairs_ = decltype(column_pairs_)();                // frees the storage (`= {}` would keep it)
  reference_positions_ = decltype(reference_positions_)();  // frees the storage (`= {}` would keep it)
}

bool NeighborList::needs_rebuild(std::span<const Vec3> positions, int threads) const {
  return max_displacement(positions, threads) > 0.5 * skin_;
}

double NeighborList::max_displacement(std::span<const Vec3> positions, int threads) const {
  if (build_count_ == 0 || positions.size() != reference_positions_.size())
    return std::numeric_limits<double>::infinity();
  const auto n = static_cast<std::int64_t>(positions.size());
  double worst = 0.0;  // max is order-independent, so the reduction is deterministic
#pragma omp parallel for reduction(max : worst) schedule(static) num_threads(threads) if (threads > 1)
  for (std::int64_t i = 0; i < n; ++i) {
    const double d2 = norm2(positions[static_cast<std::size_t>(i)] - reference_positions_[static_cast<std::size_t>(i)]);
    worst = std::max(worst, d2);
  }
  return std::sqrt(worst);
}

std::size_t NeighborList::find(std::size_t i, std::size_t j) const {
  if (i + 1 >= row_offsets_.size()) return npos;
  const auto begin = second_.begin() + row_offsets_[i];
  const auto end = second_.begin() + row_offsets_[i + 1];
  const auto it = std::lower_bound(begin, end, static_cast<std::uint32_t>(j));
  if (it == end || *it != j) return npos;
  return static_cast<std::size_t>(it - second_.begin());
}

}  // namespace demfit::dem_core
