#pragma once
// Pair contact histories across a neighbour-list rebuild, carried in place (a rebuild
// used to hold the old and the new history arrays at once, 24 bytes per pair twice, the peak of a
// dense bed's memory). First each new pair finds its old pair (`pair_sources`, parallel, while the
// old list still exists); the old list is then freed and the history array is permuted in place
// (`apply_pair_sources`, in parallel: pair_history_permutation.hpp): 4 bytes per pair for the
// sources and one byte of flags instead of a second array. The values are the same as a copy into
// a new array would give, bit for bit. Internal to Simulation.
#include <cstdint>
#include <stdexcept>
#include <vector>

#include "demfit/dem_core/neighbor_list.hpp"
#include "demfit/dem_core/pair_history_permutation.hpp"
#include "list_slack.hpp"

namespace demfit::dem_core {

/// A neighbour-list rebuild: the old and the new list, order[new] = old particle index (empty
/// when the particles were not reordered), the old pairs' touching flags and the new ones (all 0).
struct PairRebuild {
  const NeighborList& old;
  const NeighborList& list;
  const std::vector<std::uint32_t>& order;
  const std::vector<std::uint8_t>& old_touching;
  std::vector<std::uint8_t>& touching;
  int threads;
};

/// Each new pair's source in the old list (empty when nothing can be carried: first build or
/// another particle count); the touching flags are carried at once.
inline std::vector<std::uint32_t> pair_sources(const PairRebuild& r) {
  if (r.old.pair_count() == 0 || r.old.particle_count() != r.list.particle_count()) return {};
  if (r.old.pair_count() >= kSwappedPair) throw std::runtime_error("neighbour list: more than 2^31 pairs");
  std::vector<std::uint32_t> source(r.list.pair_count(), kNewPair);
  const auto rows = r.list.row_offsets();
  const auto second = r.list.second();
  const bool reordered = !r.order.empty();
  const auto count = static_cast<std::int64_t>(r.list.particle_count());
#pragma omp parallel for schedule(static) num_threads(r.threads) if (r.threads > 1)
  for (std::int64_t ii = 0; ii < count; ++ii) {
    const auto i = static_cast<std::size_t>(ii);
    for (std::uint32_t k = rows[i]; k < rows[i + 1]; ++k) {
      std::size_t a = i, b = second[k];
      if (reordered) {
        a = r.order[a];
        b = r.order[b];
      }
      // The tangential elongation is that of the first particle relative to the second: a pair
      // whose members swapped roles carries it negated (exact), as is an epsd2 rolling torque
      // (as_carried); the rest of the history is scalar.
      const bool swapped = a > b;
      const std::size_t old_k = swapped ? r.old.find(b, a) : r.old.find(a, b);
      if (old_k == NeighborList::npos) continue;
      source[k] = static_cast<std::uint32_t>(old_k) | (swapped ? kSwappedPair : 0u);
      r.touching[k] = r.old_touching[old_k];  // so the pair loop clears it if it has ended
    }
  }
  return source;
}

/// history (aligned with the old list) becomes aligned with the new one: new pair k takes the
/// old history of source[k], a new pair (or an empty `source`) starts afresh. In place when the
/// capacity allows (pair_history_permutation.hpp), by `threads`; the result does not depend on them.
template <class History>
void apply_pair_sources(const std::vector<std::uint32_t>& source, std::size_t pairs, std::vector<History>& history,
                        int threads) {
  if (source.empty() || history.empty()) {
    history = std::vector<History>();
    history.reserve(with_slack(pairs));
    history.assign(pairs, History{});
    return;
  }
  if (pairs > history.capacity()) {  // no room to grow in place: copy (the old peak, rare)
    std::vector<History> next;
    next.reserve(with_slack(pairs));
    next.assign(pairs, History{});
    for (std::size_t k = 0; k < pairs; ++k)
      if (source[k] != kNewPair) next[k] = as_carried(history[source[k] & ~kSwappedPair], source[k]);
    history.swap(next);
    return;
  }
  apply_pair_sources_in_place(source, pairs, history, threads);
}

}  // namespace demfit::dem_core
