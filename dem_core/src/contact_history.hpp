#pragma once
// Contact histories across neighbour-list and wall-slot rebuilds and across a change of law,
// written once for every law's history type (an aggregate whose first member is the tangential
// spring; contact_laws.hpp). Internal to Simulation.
#include <cstdint>
#include <vector>

#include "demfit/dem_core/neighbor_list.hpp"
#include "demfit/dem_core/wall_slots.hpp"

namespace demfit::dem_core {

/// `from` as histories of type To (another law's, or the same law's restarted): the tangential
/// spring is kept, everything else starts as for a new contact.
template <class To, class From>
std::vector<To> keep_tangential_springs(const std::vector<From>& from) {
  std::vector<To> to(from.size());
  for (std::size_t k = 0; k < from.size(); ++k) to[k].tangential_displacement = from[k].tangential_displacement;
  return to;
}

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

/// Replaces `history` (aligned with r.old) by one aligned with r.list: each new pair takes the
/// history and the touching flag of the same pair in the old list, new pairs start afresh.
template <class History>
void carry_pair_histories(const PairRebuild& r, std::vector<History>& history) {
  std::vector<History> old_history;
  old_history.swap(history);  // moved, not copied (peak memory at rebuilds)
  const std::size_t pairs = r.list.pair_count();
  history.assign(pairs, History{});
  if (old_history.empty() || r.old.particle_count() != r.list.particle_count()) return;
  // Look each new pair up in the old list (by old indices when the particles were reordered).
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
      // whose members swapped roles carries it negated (exact); the rest of the history is scalar.
      const bool swapped = a > b;
      const std::size_t old_k = swapped ? r.old.find(b, a) : r.old.find(a, b);
      if (old_k == NeighborList::npos) continue;
      history[k] = old_history[old_k];
      if (swapped) history[k].tangential_displacement = -history[k].tangential_displacement;
      r.touching[k] = r.old_touching[old_k];  // so the pair loop clears it if it has ended
    }
  }
}

/// Replaces `history` (aligned with the slots of `old`) by one aligned with `slots` (rows and
/// walls built, touching all 0): the contact state of the walls that stay candidates of a
/// particle is carried over (walls ascending in both; particle i was order[i] in `old`).
template <class History>
void carry_wall_histories(const WallSlots& old, WallSlots& slots, const std::vector<std::uint32_t>& order,
                          std::vector<History>& history, int threads) {
  std::vector<History> old_history;
  old_history.swap(history);
  history.assign(slots.size(), History{});
  const std::size_t old_particles = old.rows.empty() ? 0 : old.rows.size() - 1;
  if (old_history.size() != old.size()) return;  // the old slots' histories were dropped
  const auto count = static_cast<std::int64_t>(slots.rows.empty() ? 0 : slots.rows.size() - 1);
#pragma omp parallel for schedule(static) num_threads(threads) if (threads > 1)
  for (std::int64_t ii = 0; ii < count; ++ii) {
    const auto i = static_cast<std::size_t>(ii);
    const std::size_t o = order.empty() ? i : order[i];
    if (o >= old_particles) continue;  // a new particle
    std::uint32_t k = old.rows[o];
    for (std::uint32_t j = slots.rows[i]; j < slots.rows[i + 1]; ++j) {
      while (k < old.rows[o + 1] && old.wall[k] < slots.wall[j]) ++k;
      if (k == old.rows[o + 1] || old.wall[k] != slots.wall[j]) continue;
      history[j] = old_history[k];
      slots.touching[j] = old.touching[k];
    }
  }
}

}  // namespace demfit::dem_core
