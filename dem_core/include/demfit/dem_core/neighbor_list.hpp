#pragma once
// Verlet neighbour list with a skin, built with a cell grid in O(N), stored in CSR form as a
// half list (each pair once, first < second). Rebuild when any particle moved more than half the
// skin since the last build. A transposed index gives each particle the pairs in which it is the
// second member, so per-particle sums can run in a fixed order (bit-identical results for any
// thread count).
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "demfit/dem_core/vec3.hpp"

namespace demfit::dem_core {

class NeighborList {
 public:
  static constexpr std::size_t npos = static_cast<std::size_t>(-1);

  /// All pairs (i < j) with |x_i - x_j| < R_i + R_j + skin. positions [m], radii [m], skin [m] > 0.
  /// `transposed`: also build the transposed index (column_offsets/column_pairs, 4 bytes per pair
  /// and per particle), which only a gather of stored per-pair loads needs. `expected_pairs` (e.g.
  /// the previous list's count) sizes the build's buffers; the list does not depend on it.
  void build(std::span<const Vec3> positions, std::span<const double> radii, double skin, int threads,
             bool transposed = true, std::size_t expected_pairs = 0);
  /// True when some particle moved more than skin/2 since the last build (or never built, or the
  /// particle count changed).
  [[nodiscard]] bool needs_rebuild(std::span<const Vec3> positions, int threads) const;
  /// Largest particle displacement [m] since the last build (infinity if never built or the
  /// particle count changed).
  [[nodiscard]] double max_displacement(std::span<const Vec3> positions, int threads) const;

  [[nodiscard]] std::size_t pair_count() const { return second_.size(); }
  [[nodiscard]] std::size_t particle_count() const { return row_offsets_.empty() ? 0 : row_offsets_.size() - 1; }
  [[nodiscard]] double skin() const { return skin_; }
  /// CSR rows: pairs whose first member is i are [row_offsets()[i], row_offsets()[i+1]), ascending second.
  [[nodiscard]] std::span<const std::uint32_t> row_offsets() const { return row_offsets_; }
  [[nodiscard]] std::span<const std::uint32_t> second() const { return second_; }
  /// Transposed CSR: pair indices whose SECOND member is j, ascending by first member.
  [[nodiscard]] std::span<const std::uint32_t> column_offsets() const { return column_offsets_; }
  [[nodiscard]] std::span<const std::uint32_t> column_pairs() const { return column_pairs_; }
  /// Pair index of (i, j) with i < j, or npos (binary search in row i).
  [[nodiscard]] std::size_t find(std::size_t i, std::size_t j) const;
  [[nodiscard]] std::size_t build_count() const { return build_count_; }
  /// Frees the transposed index and the reference positions (what a list kept only for find()
  /// does not need: the carry of contact histories across a rebuild).
  void keep_rows_only();
  /// Positions at the last build (for callers that fuse the displacement check into their loops).
  [[nodiscard]] std::span<const Vec3> reference_positions() const { return reference_positions_; }

 private:
  std::vector<std::uint32_t> row_offsets_, second_, column_offsets_, column_pairs_;
  std::vector<Vec3> reference_positions_{};
  double skin_ = 0.0;
  std::size_t build_count_ = 0;
};

}  // namespace demfit::dem_core
