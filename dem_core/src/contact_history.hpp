#pragma once
// Contact histories across wall-slot rebuilds and across a change of law, written once for every
// law's history type (an aggregate whose first member is the tangential spring;
// contact_laws.hpp); pair histories across list rebuilds: pair_history_carry.hpp. Internal to
// Simulation.
#include <cstdint>
#include <vector>

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

/// Replaces `history` (aligned with the slots of `old`) by one aligned with `slots` (rows and
/// walls built, touching all 0): the contact state of the walls that stay candidates of a
/// particle is carried over (walls ascending in both, a mesh wall's slots in the same order;
/// particle i was order[i] in `old`).
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
      slots.contact_point[j] = old.contact_point[k];  // a mesh contact finds its slot by it
      ++k;  // a mesh wall has several consecutive slots: the next one carries the next
    }
  }
}

}  // namespace demfit::dem_core
