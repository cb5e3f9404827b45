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
  apply_order(p.position, order);
  apply_order(p.velocity, order);
  apply_order(p.angular_velocity, order);
  apply_order(p.force, order);
  apply_order(p.torque, order);
  apply_order(p.radius, order);
  apply_order(p.mass, order);
  apply_order(p.inverse_mass, order);
  apply_order(p.inverse_inertia, order);
  apply_order(p.material, order);
  apply_order(p.id, order);
  apply_order(p.normal_compliance, order);
  apply_order(p.shear_compliance, order);
  // Per-(particle, wall) state moves with its particle (candidates are recomputed by the caller).
  const std::size_t walls = walls_.size();
  apply_order(wall_history_, order, walls);
  apply_order(wall_force_on_particle_, order, walls);
  apply_order(wall_contact_point_, order, walls);
  apply_order(wall_rolling_torque_, order, walls);
  apply_order(wall_energy_, order, walls);
  apply_order(wall_touching_, order, walls);
  apply_order(wall_max_overlap_, order, walls);
  return order;
}

void Simulation::carry_pair_histories(const NeighborList& old, const std::vector<std::uint32_t>& order,
                                      std::vector<ContactHistory>& old_history, std::vector<std::uint8_t>& old_touching,
                                      std::vector<double>& old_max_overlap) {
  const std::size_t pairs = neighbors_.pair_count();
  pair_history_.assign(pairs, ContactHistory{});
  pair_force_.assign(pairs, Vec3{});
  pair_torque_first_.assign(pairs, Vec3{});
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
#pragma omp parallel for schedule(static) num_threads(settings_.threads) if(settings_.threads > 1)
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
