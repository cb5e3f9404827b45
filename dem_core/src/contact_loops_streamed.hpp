#pragma once
// Pair loads in PairLoadOrder::ascending_first_member (issue 16): every particle sums gravity,
// then its pair loads in ascending first member, then its walls, and nothing is stored per pair
// (own_row_first keeps each pair's force and second torque, 48 bytes, plus a transposed index for
// the gather). One thread computes the rows in ascending order and adds each touching pair's
// loads to both members at once, which is that order. T threads split the particles into T
// contiguous chunks; a pair whose second member lies in a later chunk ("crossing") is computed
// first, by its row's thread, into that thread's buffer; after one barrier each thread adds the
// crossing pairs aimed at its chunk (ascending first member: earlier chunks in order) and then
// computes its own rows exactly as one thread would. Every particle therefore receives the same
// values in the same order for any T: results are bit-identical between 1 and 2 threads, and the
// buffers hold only the crossing pairs (few when particles are in spatial order).
#include <omp.h>

#include <algorithm>
#include <cstdint>
#include <span>
#include <vector>

#include "contact_loops.hpp"

namespace demfit::dem_core {

/// The pair side without per-pair loads: the law, the half list, the histories, the contact flags.
template <class Law>
struct StreamedPairSide {
  const Law& law;
  const NeighborList& list;
  typename Law::History* history;
  std::uint8_t* touching;
};

/// The crossing pairs of rows [begin, end) (second member >= end), in pair order, into `out`.
/// Rows are sorted by second member, so a row's crossing pairs are its tail.
template <class Law>
void crossing_pairs(const StreamedPairSide<Law>& pairs, const ParticleState& p, const StepInputs& step,
                    std::size_t begin, std::size_t end, std::vector<CrossingPairLoads>& out) {
  const auto rows = pairs.list.row_offsets();
  const auto second = pairs.list.second();
  out.clear();
  for (std::size_t i = begin; i < end; ++i) {
    std::uint32_t k = rows[i + 1];
    while (k > rows[i] && second[k - 1] >= end) --k;
    for (; k < rows[i + 1]; ++k) {
      CrossingPairLoads c{k, second[k], {}};
      if (pair_loads(pairs.law, pairs.history, pairs.touching, p, k, i, second[k], step, c.loads)) out.push_back(c);
    }
  }
}

/// Loads of chunk `chunk` = particles [begin, end): gravity, the crossing pairs of earlier chunks
/// aimed at it, then its rows in ascending order (crossing pairs of its own rows from its buffer),
/// then walls and the closing half kick.
template <class Law>
void stream_chunk(const StreamedPairSide<Law>& pairs, const WallSide<Law>& walls, ParticleState& p,
                  const StepInputs& step, std::size_t begin, std::size_t end,
                  const std::vector<std::vector<CrossingPairLoads>>& crossing, std::size_t chunk) {
  for (std::size_t i = begin; i < end; ++i) {
    p.force[i] = p.mass[i] * step.gravity;
    p.torque[i] = {};
  }
  for (std::size_t earlier = 0; earlier < chunk; ++earlier)
    for (const CrossingPairLoads& c : crossing[earlier])
      if (c.second >= begin && c.second < end) {
        p.force[c.second] -= c.loads.force;
        p.torque[c.second] += c.loads.torque_second;
      }
  const auto rows = pairs.list.row_offsets();
  const auto second = pairs.list.second();
  const std::vector<CrossingPairLoads>& own = crossing[chunk];
  std::size_t next_crossing = 0;
  for (std::size_t i = begin; i < end; ++i) {
    Vec3 f = p.force[i], t = p.torque[i];
    for (std::uint32_t k = rows[i]; k < rows[i + 1]; ++k) {
      const std::uint32_t j = second[k];
      if (j >= end) {  // computed by crossing_pairs (only the touching ones are in the buffer)
        if (next_crossing < own.size() && own[next_crossing].pair == k) {
          f += own[next_crossing].loads.force;
          t += own[next_crossing].loads.torque_first;
          ++next_crossing;
        }
        continue;
      }
      PairLoads loads;
      if (!pair_loads(pairs.law, pairs.history, pairs.touching, p, k, i, j, step, loads)) continue;
      f += loads.force;
      t += loads.torque_first;
      p.force[j] -= loads.force;
      p.torque[j] += loads.torque_second;
    }
    p.force[i] = f;
    p.torque[i] = t;
  }
  for (std::size_t i = begin; i < end; ++i) finish_particle(i, walls, p, step);
}

/// The first particle of each chunk (chunks + 1 entries). Any split gives the same results; this
/// one balances the work. A chunk's thread computes its crossing pairs before the barrier while
/// the last chunk's thread has none, so with two chunks the first one gets fewer pairs: its rows'
/// pairs minus its crossing pairs (last step's count, `crossing`) match the second's rows. More
/// chunks split the pairs evenly.
inline std::vector<std::size_t> chunk_starts(std::span<const std::uint32_t> rows, std::size_t chunks,
                                             std::size_t crossing) {
  const std::size_t n = rows.size() - 1, pairs = rows[n];
  std::vector<std::size_t> start(chunks + 1, n);
  start[0] = 0;
  for (std::size_t c = 1; c < chunks; ++c) {
    std::size_t target = pairs * c / chunks;
    if (chunks == 2) target = (pairs + std::min(crossing, pairs)) / 2;
    start[c] = static_cast<std::size_t>(std::lower_bound(rows.begin(), rows.end(), target) - rows.begin());
    start[c] = std::clamp(start[c], start[c - 1], n);
  }
  return start;
}

/// All loads and the closing half kick in PairLoadOrder::ascending_first_member; `crossing`
/// keeps its capacity between steps (one buffer per thread).
template <class Law>
void all_forces_streamed(const StreamedPairSide<Law>& pairs, const WallSide<Law>& walls, ParticleState& p,
                         const StepInputs& step, std::vector<std::vector<CrossingPairLoads>>& crossing) {
  const std::size_t n = p.size();
  if (step.threads <= 1 || n < 2) {
    crossing.resize(1);
    crossing[0].clear();
    stream_chunk(pairs, walls, p, step, 0, n, crossing, 0);
    return;
  }
  std::size_t crossed_last_step = 0;
  for (const auto& buffer : crossing) crossed_last_step += buffer.size();
  crossing.resize(static_cast<std::size_t>(step.threads));
#pragma omp parallel num_threads(step.threads)
  {
    // The chunks follow the threads actually granted; the results do not depend on them.
    const auto chunks = static_cast<std::size_t>(omp_get_num_threads());
    const auto chunk = static_cast<std::size_t>(omp_get_thread_num());
    const std::vector<std::size_t> start = chunk_starts(pairs.list.row_offsets(), chunks, crossed_last_step);
    crossing_pairs(pairs, p, step, start[chunk], start[chunk + 1], crossing[chunk]);
#pragma omp barrier
    stream_chunk(pairs, walls, p, step, start[chunk], start[chunk + 1], crossing, chunk);
  }
}

}  // namespace demfit::dem_core
