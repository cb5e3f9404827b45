// Neighbour-list rebuild helpers: the optional spatial reordering of the particles, the new pair
// arrays and wall slots, and the carry of their contact histories (contact_history.hpp).
#include <algorithm>
#include <variant>

#include "contact_history.hpp"
#include "pair_history_carry.hpp"
#include "demfit/dem_core/simulation.hpp"
#include "particle_order.hpp"

namespace demfit::dem_core {

std::vector<std::uint32_t> Simulation::apply_spatial_order() {
  ParticleState& p = particles_;
  if (p.size() < 2) return {};
  const double r_max = *std::max_element(p.radius.begin(), p.radius.end());
  const int threads = settings_.threads;
  std::vector<std::uint32_t> order = slab_order(p.position, 2.0 * r_max + skin(), threads);
  if (order.empty()) return order;
  p.for_each_array([&](auto& values) { apply_order(values, order, 1, threads); });
  return order;  // the wall slots are rebuilt next, through `order`
}

void Simulation::rebuild_pair_arrays(NeighborList&& old, const std::vector<std::uint32_t>& order) {
  const std::size_t pairs = neighbors_.pair_count();
  std::vector<std::uint8_t> old_touching;
  old_touching.swap(pair_touching_);
  pair_touching_.assign(pairs, 0);
  const bool histories_kept = std::visit([](const auto& state) { return !state.pair_history.empty(); }, contact_state_);
  const std::vector<std::uint32_t> source =
      histories_kept ? pair_sources({old, neighbors_, order, old_touching, pair_touching_, settings_.threads})
                     : std::vector<std::uint32_t>{};
  // Freed before the histories move (peak memory at rebuilds; `= {}` would keep the storage).
  old = NeighborList();
  old_touching = decltype(old_touching)();
  std::visit([&](auto& state) { apply_pair_sources(source, pairs, state.pair_history, settings_.threads); },
             contact_state_);
  // Allocated once the old histories are gone (ensure_neighbors freed the old loads before the
  // build): the peak of a rebuild stays below the steady per-pair storage.
  if (settings_.pair_load_order != PairLoadOrder::own_row_first) return;  // nothing stored per pair
  pair_force_.assign(pairs, Vec3{});
  pair_torque_second_.assign(pairs, Vec3{});
}

namespace {

/// Particle–wall candidate flags, and for mesh walls the triangles within R + margin of each
/// candidate particle: per contiguous particle range (one per thread, in particle order) one
/// list, particle by particle, walls ascending, so that their concatenation is in slot order.
struct WallCandidates {
  std::vector<std::uint8_t> flag;                     // per (particle, wall)
  std::vector<std::uint32_t> triangle_count;          // per (particle, wall); meshes only
  std::vector<std::vector<std::uint32_t>> triangles;  // per particle range
};

WallCandidates flag_wall_candidates(const ParticleState& p, const std::vector<Wall>& walls,
                                    const std::vector<std::uint8_t>& always_checked, double margin, int threads) {
  const std::size_t n = p.size(), w_count = walls.size();
  WallCandidates c;
  c.flag.assign(n * w_count, 0);
  c.triangle_count.assign(n * w_count, 0);
  const int ranges = std::max(1, threads);
  c.triangles.resize(static_cast<std::size_t>(ranges));
#pragma omp parallel for schedule(static, 1) num_threads(threads) if (threads > 1)
  for (int r = 0; r < ranges; ++r) {
    std::vector<std::uint32_t>& listed = c.triangles[static_cast<std::size_t>(r)];
    const std::size_t begin = n * static_cast<std::size_t>(r) / static_cast<std::size_t>(ranges);
    const std::size_t end = n * static_cast<std::size_t>(r + 1) / static_cast<std::size_t>(ranges);
    for (std::size_t i = begin; i < end; ++i)
      for (std::size_t w = 0; w < w_count; ++w) {
        const std::size_t k = i * w_count + w;
        if (const auto* mesh = std::get_if<MeshGeometry>(&walls[w].geometry)) {
          const std::size_t before = listed.size();
          mesh_wall_candidates(*mesh, p.position[i], p.radius[i] + margin, listed);
          c.triangle_count[k] = static_cast<std::uint32_t>(listed.size() - before);
          c.flag[k] = always_checked[w] || c.triangle_count[k] > 0;
        } else {
          c.flag[k] = always_checked[w] || wall_may_touch(walls[w].geometry, p.position[i], p.radius[i], margin);
        }
      }
  }
  return c;
}

/// The mesh walls' candidate triangles in CSR over the slots (all on a group's first slot).
void list_slot_triangles(const WallCandidates& c, const std::vector<std::uint32_t>& slots_of, WallSlots& s) {
  const std::size_t walls = slots_of.size(), n = s.rows.size() - 1;
  s.triangle_rows.assign(s.size() + 1, 0);
  for (std::size_t i = 0; i < n; ++i) {
    std::uint32_t slot = s.rows[i];
    for (std::size_t w = 0; w < walls; ++w) {
      if (!c.flag[i * walls + w]) continue;
      s.triangle_rows[slot + 1] = c.triangle_count[i * walls + w];
      slot += slots_of[w];
    }
  }
  for (std::size_t k = 0; k < s.size(); ++k) s.triangle_rows[k + 1] += s.triangle_rows[k];
  s.triangles.clear();
  s.triangles.reserve(s.triangle_rows.back());
  for (const std::vector<std::uint32_t>& listed : c.triangles) s.triangles.insert(s.triangles.end(), listed.begin(), listed.end());
}

}  // namespace

void Simulation::find_wall_candidates(const std::vector<std::uint32_t>& order) {
  const std::size_t n = particles_.size(), walls = walls_.size();
  // Candidate flags per (particle, wall), in parallel; then the CSR rows in a fixed order.
  const WallCandidates candidates = flag_wall_candidates(particles_, walls_, wall_always_checked_, skin(), settings_.threads);
  const std::vector<std::uint8_t>& flag = candidates.flag;
  std::vector<std::uint32_t> slots_of(walls);  // a mesh wall has several contact slots per particle
  bool any_mesh = false;
  for (std::size_t w = 0; w < walls; ++w) {
    slots_of[w] = static_cast<std::uint32_t>(wall_contact_slots(walls_[w].geometry));
    any_mesh = any_mesh || std::holds_alternative<MeshGeometry>(walls_[w].geometry);
  }
  const auto count = static_cast<std::int64_t>(n);
  WallSlots old;
  std::swap(old, wall_slots_);
  WallSlots& s = wall_slots_;
  s.rows.assign(n + 1, 0);
  for (std::size_t i = 0; i < n; ++i) {
    std::uint32_t c = 0;
    for (std::size_t w = 0; w < walls; ++w) c += flag[i * walls + w] ? slots_of[w] : 0;
    s.rows[i + 1] = s.rows[i] + c;
  }
  const std::size_t slots = s.rows[n];
  s.wall.resize(slots);
  s.force_on_particle.assign(slots, Vec3{});
  s.contact_point.assign(slots, Vec3{});
  s.rolling_torque.assign(slots, Vec3{});
  s.energy.assign(slots, 0.0);
  s.touching.assign(slots, 0);
#pragma omp parallel for schedule(static) num_threads(settings_.threads) if (settings_.threads > 1)
  for (std::int64_t ii = 0; ii < count; ++ii) {
    const auto i = static_cast<std::size_t>(ii);
    std::uint32_t slot = s.rows[i];
    for (std::size_t w = 0; w < walls; ++w)
      for (std::uint32_t k = 0; flag[i * walls + w] && k < slots_of[w]; ++k) s.wall[slot++] = static_cast<std::uint32_t>(w);
  }
  if (any_mesh) list_slot_triangles(candidates, slots_of, s);
  // Contact state of walls that stay candidates is carried over (contact_history.hpp).
  std::visit([&](auto& state) { carry_wall_histories(old, s, order, state.wall_history, settings_.threads); },
             contact_state_);
}

}  // namespace demfit::dem_core
