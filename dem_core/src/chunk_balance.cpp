// The time-balanced split of the pair rows between threads; see chunk_balance.hpp.
#include "demfit/dem_core/chunk_balance.hpp"

#include <algorithm>

namespace demfit::dem_core {

std::vector<std::size_t> ChunkBalance::chunks(std::span<const std::uint32_t> rows, std::size_t threads) const {
  const std::size_t n = rows.size() - 1;
  const double pairs = static_cast<double>(rows[n]);
  std::vector<std::size_t> chunk(threads + 1, n);
  chunk[0] = 0;
  const bool measured = fraction_.size() == threads + 1;
  for (std::size_t c = 1; c < threads; ++c) {
    const double fraction = measured ? fraction_[c] : static_cast<double>(c) / static_cast<double>(threads);
    const auto target = static_cast<std::uint32_t>(fraction * pairs);
    const auto at = static_cast<std::size_t>(std::lower_bound(rows.begin(), rows.end(), target) - rows.begin());
    chunk[c] = std::clamp(at, chunk[c - 1], n);
  }
  return chunk;
}

void ChunkBalance::observe(std::span<const std::uint32_t> rows, std::span<const std::size_t> chunk,
                           std::span<const double> seconds) {
  const std::size_t threads = seconds.size(), n = rows.size() - 1;
  const double pairs = static_cast<double>(rows[n]);
  double total = 0.0;
  for (const double t : seconds) total += t;
  if (threads < 2 || chunk.size() != threads + 1 || !(pairs > 0.0) || !(total > 0.0)) return;
  if (fraction_.size() != threads + 1) {
    fraction_.resize(threads + 1);
    for (std::size_t c = 0; c <= threads; ++c) fraction_[c] = static_cast<double>(c) / static_cast<double>(threads);
  }
  // Cost model: chunk c's time spread evenly over its pairs [rows[chunk[c]], rows[chunk[c+1]]).
  // Boundary c goes to where the accumulated cost reaches c/T of the total.
  std::size_t segment = 0;
  double cost_before = 0.0;  // time of the segments before `segment`
  for (std::size_t c = 1; c < threads; ++c) {
    const double wanted = total * static_cast<double>(c) / static_cast<double>(threads);
    while (segment + 1 < threads && cost_before + seconds[segment] < wanted) cost_before += seconds[segment++];
    const double first = rows[chunk[segment]], last = rows[chunk[segment + 1]];
    const double share = seconds[segment] > 0.0 ? std::clamp((wanted - cost_before) / seconds[segment], 0.0, 1.0) : 0.0;
    const double target = (first + share * (last - first)) / pairs;
    const double move = std::clamp(kGain * (target - fraction_[c]), -kLargestMove, kLargestMove);
    fraction_[c] = std::clamp(fraction_[c] + move, fraction_[c - 1], 1.0);
  }
}

}  // namespace demfit::dem_core
