#pragma once
// Where T threads split the particles for the pair loads in PairLoadOrder::ascending_first_member
// (src/contact_loops_streamed.hpp). The results do not depend on the split, only the waiting
// does: each thread's measured time for its chunk moves the boundaries toward equal times. A
// fixed cost model (pairs per chunk) left one thread waiting on the issue-16 drum, because the
// per-particle work (walls, the closing kick) and the crossing pairs are not spread like the
// pairs.
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace demfit::dem_core {

class ChunkBalance {
 public:
  /// Chunk c owns the rows [chunk[c], chunk[c + 1]) of `rows` (CSR row offsets of the half list,
  /// size n + 1); size threads + 1, ascending, chunk[0] = 0 and chunk[threads] = n.
  [[nodiscard]] std::vector<std::size_t> chunks(std::span<const std::uint32_t> rows, std::size_t threads) const;
  /// One step's measurement: chunk c (as returned by chunks()) took seconds[c]. Each boundary
  /// moves part of the way to where a cost spread evenly over each chunk's pairs would give equal
  /// times; the move per step is bounded, so one preempted thread cannot throw the split far.
  void observe(std::span<const std::uint32_t> rows, std::span<const std::size_t> chunk,
               std::span<const double> seconds);
  /// Boundaries as fractions of the pair list (threads + 1 values), empty before the first step.
  [[nodiscard]] std::span<const double> pair_fractions() const { return fraction_; }

  static constexpr double kGain = 0.3;          ///< part of the way moved per step
  static constexpr double kLargestMove = 0.02;  ///< largest move per step, fraction of the pairs

 private:
  std::vector<double> fraction_{};
};

}  // namespace demfit::dem_core
