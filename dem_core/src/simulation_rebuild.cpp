// Neighbour-list rebuild helpers: the optional spatial reordering of the particles and the carry
// of pair contact histories from the old list to the new one.
#include <algorithm>

#include "demfit/dem_core/simulation.hpp"
#include "particle_order.hpp"

namespace demfit::dem_core {

std::vector<std::uint32_t> Simulation::apply_spatial_order() {
  ParticleState& p = particles_;
  if (p.size() < 2) return {};
  const double r_max = *std::max_element(p.radius.begin(), p.radius.end());
  std::vector<std::uint32_t> order = morton_order(p.position, 2.0 * r_max + skin());
  if (order.empty()) return order;
  p.for_each_array([&](auto& values) { apply_order(values, order); });
  return order;  // the wall slots are rebuilt next, through `order`
}

void Simulation::carry_pair_histories(const NeighborList& old, const std::vector<std::uint32_t>& order,
                                      std::vector<ContactHistory>& old_history, std::vector<std::uint8_t>& old_touching,
                                      std::vector<double>& old_max_overlap) {
  const std::size_t pairs = neighbors_.pair_count();
  pair_history_.assign(pairs, ContactHistory{});
  pair_force_.assign(pairs, Vec3{});
  pair_torque_second_.assign(pairs, Vec3{});
  pair_energy_.assign(pairs, 0.0);
  pair_touching_.assign(pairs, 0);
  const bool plastic = !old_max_overlap.empty();
  if (plastic) pair_max_overlap_.assign(pairs, 0.0);
  if (old_history.empty() || old.particle_count() != particles_.size()) return;
  // Look each new pair up in the old list (by old indices when the particles were reordered).
  const auto first = neighbors_.first();
  const auto second = neighbors_.second();
  const bool reordered = !order.empty();
  const auto count = static_cast<std::int64_t>(pairs);
#pragma omp parallel for schedule(static) num_threads(settings_.threads) if (settings_.threads > 1)
  for (std::int64_t kk = 0; kk < count; ++kk) {
    const auto k = static_cast<std::size_t>(kk);
    std::size_t a = first[k], b = second[k];
    if (reordered) {
      a = order[a];
      b = order[b];
    }
    // The tangential elongation is that of the first particle relative to the second: a pair
    // whose members swapped roles carries it negated (exact).
    const bool swapped = a > b;
    const std::size_t old_k = swapped ? old.find(b, a) : old.find(a, b);
    if (old_k == NeighborList::npos) continue;
    pair_history_[k] = old_history[old_k];
    if (swapped) pair_history_[k].tangential_displacement = -pair_history_[k].tangential_displacement;
    pair_touching_[k] = old_touching[old_k];  // so the pair loop clears it if it has ended
    if (plastic) pair_max_overlap_[k] = old_max_overlap[old_k];
  }
}

}  // namespace demfit::dem_core

namespace demfit::dem_core {

void Simulation::find_wall_candidates(const std::vector<std::uint32_t>& order) {
  const std::size_t n = particles_.size(), walls = walls_.size();
  const double margin = skin();
  // Candidate flags per (particle, wall), in parallel; then the CSR rows in a fixed order.
  std::vector<std::uint8_t> flag(n * walls);
  const auto count = static_cast<std::int64_t>(n);
#pragma omp parallel for schedule(static) num_threads(settings_.threads) if (settings_.threads > 1)
  for (std::int64_t ii = 0; ii < count; ++ii) {
    const auto i = static_cast<std::size_t>(ii);
    for (std::size_t w = 0; w < walls; ++w)
      flag[i * walls + w] = wall_always_checked_[w] ||
                            wall_may_touch(walls_[w].geometry, particles_.position[i], particles_.radius[i], margin);
  }
  WallSlots old;
  std::swap(old, wall_slots_);
  WallSlots& s = wall_slots_;
  s.rows.assign(n + 1, 0);
  for (std::size_t i = 0; i < n; ++i) {
    std::uint32_t c = 0;
    for (std::size_t w = 0; w < walls; ++w) c += flag[i * walls + w];
    s.rows[i + 1] = s.rows[i] + c;
  }
  const std::size_t slots = s.rows[n];
  s.wall.resize(slots);
  s.history.assign(slots, ContactHistory{});
  s.force_on_particle.assign(slots, Vec3{});
  s.contact_point.assign(slots, Vec3{});
  s.rolling_torque.assign(slots, Vec3{});
  s.energy.assign(slots, 0.0);
  s.touching.assign(slots, 0);
  const bool plastic = !old.max_overlap.empty();
  if (plastic) s.max_overlap.assign(slots, 0.0);
  const std::size_t old_particles = old.rows.empty() ? 0 : old.rows.size() - 1;
#pragma omp parallel for schedule(static) num_threads(settings_.threads) if (settings_.threads > 1)
  for (std::int64_t ii = 0; ii < count; ++ii) {
    const auto i = static_cast<std::size_t>(ii);
    std::uint32_t slot = s.rows[i];
    for (std::size_t w = 0; w < walls; ++w)
      if (flag[i * walls + w]) s.wall[slot++] = static_cast<std::uint32_t>(w);
    // Contact state of walls that stay candidates is carried over (walls ascending in both).
    const std::size_t o = order.empty() ? i : order[i];
    if (o >= old_particles) continue;  // a new particle
    std::uint32_t k = old.rows[o];
    for (std::uint32_t j = s.rows[i]; j < s.rows[i + 1]; ++j) {
      while (k < old.rows[o + 1] && old.wall[k] < s.wall[j]) ++k;
      if (k == old.rows[o + 1] || old.wall[k] != s.wall[j]) continue;
      s.history[j] = old.history[k];
      s.touching[j] = old.touching[k];
      if (plastic) s.max_overlap[j] = old.max_overlap[k];
    }
  }
}

}  // namespace demfit::dem_core
