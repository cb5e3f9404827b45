#pragma once
// Pair loads in PairLoadOrder::ascending_first_member: every particle sums gravity,
// then its pair loads in ascending first member, then its walls, and nothing is stored per pair
// (own_row_first keeps each pair's force and second torque, 48 bytes, plus a transposed index for
// the gather). One thread computes the rows in ascending order and adds each touching pair's
// loads to both members at once, which is that order. T threads split the particles into T
// contiguous chunks (ChunkBalance places the boundaries from the chunks' measured times); a pair
// whose second member lies in a later chunk ("crossing") is computed first, the threads taking
// blocks of rows as they come, into one buffer per block; after the blocks are done each thread
// adds the crossing pairs aimed at its chunk (ascending first member: buffers in block order)
// and then computes its own rows exactly as one thread would. Every particle therefore receives
// the same values in the same order for any T and any split: results are bit-identical between
// 1 and 2 threads, and the buffers hold only the crossing pairs (few when particles are in
// spatial order).
#include <omp.h>

#include <algorithm>
#include <cstdint>
#include <span>
#include <vector>

#include "contact_loops.hpp"
#include "demfit/dem_core/chunk_balance.hpp"

namespace demfit::dem_core {

/// The pair side without per-pair loads: the law, the half list, the histories, the contact flags.
template <class Law>
struct StreamedPairSide {
  const Law& law;
  const NeighborList& list;
  typename Law::History* history;
  std::uint8_t* touching;
};

/// Rows [0, rows_with_crossing) in blocks of `kCrossingBlockRows`: block b is rows
/// [b kCrossingBlockRows, ...). The threads take blocks as they come (the crossing pairs gather
/// near the chunk boundaries, so a fixed share would leave one thread with most of them); block
/// b's touching crossing pairs go to buffer b, so the buffers in block order hold them in pair
/// order whichever thread computed which block.
inline constexpr std::size_t kCrossingBlockRows = 64;

inline std::size_t crossing_blocks(std::size_t rows_with_crossing) {
  return (rows_with_crossing + kCrossingBlockRows - 1) / kCrossingBlockRows;
}

/// The crossing pairs of rows [begin, end) (second member in a later chunk than the row), in pair
/// order, into `out`. Rows are sorted by second member, so a row's crossing pairs are its tail.
template <class Law>
void crossing_pairs(const StreamedPairSide<Law>& pairs, const ParticleState& p, const StepInputs& step,
                    const std::vector<std::size_t>& chunk, std::size_t begin, std::size_t end, CrossingBuffer& buffer) {
  std::vector<CrossingPairLoads>& out = buffer.pairs;
  const auto rows = pairs.list.row_offsets();
  const auto second = pairs.list.second();
  out.clear();
  auto c = static_cast<std::size_t>(std::upper_bound(chunk.begin(), chunk.end(), begin) - chunk.begin()) - 1;
  for (std::size_t i = begin; i < end; ++i) {
    while (chunk[c + 1] <= i) ++c;
    const std::size_t chunk_end = chunk[c + 1];
    std::uint32_t k = rows[i + 1];
    while (k > rows[i] && second[k - 1] >= chunk_end) --k;
    for (; k < rows[i + 1]; ++k) {
      CrossingPairLoads x{k, second[k], {}};
      if (pair_loads(pairs.law, pairs.history, pairs.touching, p, k, i, second[k], step, x.loads)) out.push_back(x);
    }
  }
}

/// Walks the crossing buffers in pair order from the first entry of pair `from` on.
class CrossingCursor {
 public:
  CrossingCursor(const std::vector<CrossingBuffer>& buffers, std::size_t count, std::uint32_t from)
      : buffers_(buffers), count_(count) {
    while (buffer_ < count_ && (buffers_[buffer_].pairs.empty() || buffers_[buffer_].pairs.back().pair < from))
      ++buffer_;
    if (buffer_ == count_) return;
    const auto& b = buffers_[buffer_].pairs;
    index_ = static_cast<std::size_t>(
        std::lower_bound(b.begin(), b.end(), from,
                         [](const CrossingPairLoads& x, std::uint32_t k) { return x.pair < k; }) -
        b.begin());
  }
  /// The entry of pair k if it is the next one (then the cursor moves on), else nullptr.
  const CrossingPairLoads* take(std::uint32_t k) {
    if (buffer_ == count_ || buffers_[buffer_].pairs[index_].pair != k) return nullptr;
    const CrossingPairLoads* entry = &buffers_[buffer_].pairs[index_];
    if (++index_ == buffers_[buffer_].pairs.size()) {
      index_ = 0;
      do ++buffer_;
      while (buffer_ < count_ && buffers_[buffer_].pairs.empty());
    }
    return entry;
  }

 private:
  const std::vector<CrossingBuffer>& buffers_;
  std::size_t count_, buffer_ = 0, index_ = 0;
};

/// Loads of chunk [begin, end): gravity, the crossing pairs of earlier rows aimed at it (in pair
/// order), then its rows in ascending order (their crossing pairs from the buffers), then walls
/// and the closing half kick.
template <class Law>
void stream_chunk(const StreamedPairSide<Law>& pairs, const WallSide<Law>& walls, ParticleState& p,
                  const StepInputs& step, std::size_t begin, std::size_t end,
                  const std::vector<CrossingBuffer>& crossing, std::size_t buffers) {
  for (std::size_t i = begin; i < end; ++i) {
    p.force[i] = p.mass[i] * step.gravity;
    p.torque[i] = {};
  }
  const auto rows = pairs.list.row_offsets();
  for (std::size_t w = 0; w < buffers; ++w)
    for (const CrossingPairLoads& c : crossing[w].pairs) {
      if (c.pair >= rows[begin]) break;  // from here on: this chunk's rows and later ones
      if (c.second >= begin && c.second < end) {
        p.force[c.second] -= c.loads.force;
        p.torque[c.second] += c.loads.torque_second;
      }
    }
  const auto second = pairs.list.second();
  CrossingCursor own(crossing, buffers, rows[begin]);
  for (std::size_t i = begin; i < end; ++i) {
    Vec3 f = p.force[i], t = p.torque[i];
    for (std::uint32_t k = rows[i]; k < rows[i + 1]; ++k) {
      const std::uint32_t j = second[k];
      if (j >= end) {  // computed before the barrier (only the touching ones are in the buffers)
        if (const CrossingPairLoads* c = own.take(k)) {
          f += c->loads.force;
          t += c->loads.torque_first;
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

/// All loads and the closing half kick in PairLoadOrder::ascending_first_member. `crossing`
/// keeps its buffers' capacity between steps; `balance` places the chunk boundaries and learns
/// from each step's chunk times (results do not depend on it).
template <class Law>
void all_forces_streamed(const StreamedPairSide<Law>& pairs, const WallSide<Law>& walls, ParticleState& p,
                         const StepInputs& step, std::vector<CrossingBuffer>& crossing, ChunkBalance& balance) {
  const std::size_t n = p.size();
  if (step.threads <= 1 || n < 2) {
    crossing.resize(1);
    crossing[0].pairs.clear();
    stream_chunk(pairs, walls, p, step, 0, n, crossing, 0);
    return;
  }
  const auto rows = pairs.list.row_offsets();
  const auto requested = static_cast<std::size_t>(step.threads);
  const std::vector<std::size_t> planned = balance.chunks(rows, requested);
  std::vector<double> seconds(requested, 0.0);
  crossing.resize(std::max(crossing.size(), crossing_blocks(n)));  // enough for any split
  bool as_planned = true;
#pragma omp parallel num_threads(step.threads)
  {
    // Fewer threads than requested only when OpenMP limits them: an even split then, unmeasured.
    const auto threads = static_cast<std::size_t>(omp_get_num_threads());
    const auto thread = static_cast<std::size_t>(omp_get_thread_num());
    std::vector<std::size_t> even;
    if (threads != requested) even = ChunkBalance{}.chunks(rows, threads);
    const std::vector<std::size_t>& chunk = threads == requested ? planned : even;
    const std::size_t blocks = crossing_blocks(chunk[threads - 1]);  // later rows have no crossing pairs
    if (thread == 0) as_planned = threads == requested;
#pragma omp for schedule(dynamic, 1)
    for (std::size_t b = 0; b < blocks; ++b)
      crossing_pairs(pairs, p, step, chunk, b * kCrossingBlockRows,
                     std::min((b + 1) * kCrossingBlockRows, chunk[threads - 1]), crossing[b]);
    // (the loop's implied barrier: every crossing pair is computed before any chunk sums)
    const double start = omp_get_wtime();
    stream_chunk(pairs, walls, p, step, chunk[thread], chunk[thread + 1], crossing, blocks);
    seconds[thread] = omp_get_wtime() - start;
  }
  if (as_planned) balance.observe(rows, planned, seconds);
}

}  // namespace demfit::dem_core
