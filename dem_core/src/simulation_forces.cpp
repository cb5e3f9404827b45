// Force evaluation: neighbours -> pair loads in one of the two fixed orders of PairLoadOrder
// (parallel) -> wall loads (per particle, parallel) -> serial wall reduction. The loops
// (contact_loops.hpp) are templated on the contact law; the law type is chosen by one switch per
// evaluation (with_contact_law, contact_laws.hpp).
#include <algorithm>
#include <cmath>
#include <utility>
#include <variant>

#include "contact_history.hpp"
#include "contact_loops.hpp"
#include "contact_loops_streamed.hpp"
#include "demfit/dem_core/simulation.hpp"

namespace demfit::dem_core {

void Simulation::ensure_neighbors(double moved) {
  const double skin_now = skin();
  const std::size_t walls = walls_.size();
  wall_always_checked_.resize(walls);
  double wall_shift = 0.0, mesh_sweep = 0.0;
  const bool wall_layout_ok = wall_displacement_at_build_.size() == walls && wall_angle_at_build_.size() == walls;
  for (std::size_t w = 0; w < walls; ++w) {
    // A rotating mesh moves its surface by at most |angle turned| x its reach from the axis, so
    // only particles near the mesh hold its slots; the sweep is measured since the slots' build.
    const double reach = wall_sweep_radius(walls_[w]);
    wall_always_checked_[w] = wall_distances_rigid(walls_[w]) || reach > 0.0 ? 0 : 1;
    if (!wall_layout_ok) continue;
    wall_shift = std::max(wall_shift, norm(walls_[w].displacement - wall_displacement_at_build_[w]));
    mesh_sweep = std::max(mesh_sweep, std::abs(walls_[w].rotation_angle - wall_angle_at_build_[w]) * reach);
  }
  const bool stale = rebuild_requested_ || !wall_layout_ok || neighbors_.skin() != skin_now ||
                     neighbors_.particle_count() != particles_.size() || !wall_slots_.built_for(particles_.size());
  // Particle pairs and particle-wall candidates stay valid while the relative motion of any two
  // bodies is below half the skin.
  if (!stale && moved < 0.0) moved = neighbors_.max_displacement(particles_.position, settings_.threads);
  if (!stale && moved + wall_shift <= 0.5 * skin_now) {
    // The pairs are valid. The wall slots (margin: the skin) stay valid while particle motion
    // since their build (at most moved + what had moved when they were rebuilt alone), wall
    // translation and mesh sweep stay below the skin; else they alone are rebuilt (no
    // reordering, no pair list: a turning mesh does not rebuild the whole list).
    if (moved + slot_build_motion_ + wall_shift + mesh_sweep <= skin_now) return;
    for (std::size_t w = 0; w < walls; ++w) wall_angle_at_build_[w] = walls_[w].rotation_angle;
    slot_build_motion_ = moved + wall_shift;
    find_wall_candidates({});
    return;
  }
  rebuild_requested_ = false;
  slot_build_motion_ = 0.0;
  wall_displacement_at_build_.resize(walls);
  wall_angle_at_build_.resize(walls);
  for (std::size_t w = 0; w < walls; ++w) {
    wall_displacement_at_build_[w] = walls_[w].displacement;
    wall_angle_at_build_[w] = walls_[w].rotation_angle;
  }
  const std::vector<std::uint32_t> order =
      settings_.reorder_particles ? apply_spatial_order() : std::vector<std::uint32_t>{};
  find_wall_candidates(order);
  // Moved, not copied (peak memory at rebuilds); the counters stay with neighbors_. Only the old
  // rows are needed to carry the histories; the per-pair loads are recomputed on the next step.
  NeighborList old = std::move(neighbors_);
  old.keep_rows_only();
  pair_force_ = decltype(pair_force_)();                  // frees the storage (`= {}` would keep it)
  pair_torque_second_ = decltype(pair_torque_second_)();  // frees the storage (`= {}` would keep it)
  neighbors_.build(particles_.position, particles_.radius, skin_now, settings_.threads,
                   settings_.pair_load_order == PairLoadOrder::own_row_first, old.pair_count());
  rebuild_pair_arrays(std::move(old), order);
}

void Simulation::compute_forces(double dt, double closing_kick, double moved) {
  ensure_neighbors(moved);  // (re)builds the wall slots too
  with_contact_law(settings_.law, settings_.contact,
                   [&]<class Law>(std::type_identity<Law>) { evaluate_loads<Law>(dt, closing_kick); });
  diagnostics_valid_ = false;
  pair_diagnostics_valid_ = false;
  forces_valid_ = true;
}

template <class Law>
ContactLawState<Law>& Simulation::law_state() {
  using History = typename Law::History;
  const ContactParameters& c = settings_.contact;
  if (!std::holds_alternative<ContactLawState<Law>>(contact_state_)) {
    // The law changed (an effect switched on or off): keep the tangential springs.
    ContactLawState<Law> next;
    std::visit(
        [&](const auto& state) {
          next.pair_history = keep_tangential_springs<History>(state.pair_history);
          next.wall_history = keep_tangential_springs<History>(state.wall_history);
        },
        contact_state_);
    contact_state_ = std::move(next);
    wall_laws_valid_ = false;
  }
  auto& state = std::get<ContactLawState<Law>>(contact_state_);
  if (Law::restarts_history(state.evaluated_with, c)) {
    state.pair_history = keep_tangential_springs<History>(state.pair_history);
    state.wall_history = keep_tangential_springs<History>(state.wall_history);
  }
  state.evaluated_with = c;
  return state;
}

template <class Law>
void Simulation::evaluate_loads(double dt, double closing_kick) {
  ContactLawState<Law>& state = law_state<Law>();
  const ContactParameters& c = settings_.contact;
  if (!wall_laws_valid_) {
    state.wall_laws.clear();
    for (const Wall& w : walls_) state.wall_laws.push_back(Law::for_wall(c, w.contact));
    wall_laws_valid_ = true;
  }
  const Law pair_law = Law::for_pairs(c);
  WallSlots& slots = wall_slots_;
  const WallSide<Law> walls{state.wall_laws,
                            walls_,
                            slots.rows.data(),
                            slots.wall.data(),
                            state.wall_history.data(),
                            slots.force_on_particle.data(),
                            slots.contact_point.data(),
                            slots.rolling_torque.data(),
                            slots.energy.data(),
                            slots.touching.data(),
                            slots.triangle_rows.data(),
                            slots.triangles.data()};
  const StepInputs step{settings_.gravity, dt, closing_kick, c.rotation_enabled(), settings_.threads};
  switch (settings_.pair_load_order) {
    case PairLoadOrder::own_row_first: {
      const PairSide<Law> pairs{pair_law,
                                neighbors_,
                                state.pair_history.data(),
                                pair_force_.data(),
                                pair_torque_second_.data(),
                                pair_touching_.data()};
      all_forces(pairs, walls, particles_, step);
      return;
    }
    case PairLoadOrder::ascending_first_member: {
      const StreamedPairSide<Law> pairs{pair_law, neighbors_, state.pair_history.data(), pair_touching_.data()};
      all_forces_streamed(pairs, walls, particles_, step, crossing_pair_loads_, chunk_balance_);
      return;
    }
  }
}

void Simulation::reduce_diagnostics() const {
  if (diagnostics_valid_) return;
  // Serial, fixed-order sums: wall loads and energies are identical for any thread count.
  for (Wall& w : walls_) {
    w.force = {};
    w.moment = {};
    w.torque = 0.0;
    w.contact_count = 0;
  }
  wall_elastic_energy_ = 0.0;
  const WallSlots& slots = wall_slots_;
  if (!forces_valid_ || !slots.built_for(particles_.size())) return;  // nothing evaluated yet
  diagnostics_valid_ = true;
  double energy = 0.0;
  for (std::size_t i = 0; i < particles_.size(); ++i) {
    for (std::uint32_t slot = slots.rows[i]; slot < slots.rows[i + 1]; ++slot) {  // walls ascending
      if (!slots.touching[slot]) continue;
      Wall& wall = walls_[slots.wall[slot]];
      // The wall receives -F at the contact point and the couple -M_r.
      const Vec3 f = -slots.force_on_particle[slot];
      wall.force += f;
      wall.moment += cross(slots.contact_point[slot] - wall.torque_axis.point, f) - slots.rolling_torque[slot];
      ++wall.contact_count;
      energy += slots.energy[slot];
    }
  }
  for (Wall& w : walls_) w.torque = dot(w.moment, w.torque_axis.direction);
  wall_elastic_energy_ = energy;
}

void Simulation::reduce_pair_diagnostics() const {
  // Kept apart from the wall loads: a drum asks for its wall torque every step, and summing every
  // pair's spring energy with it cost 12 % of an s = 1.5 GranuDrum run (perf, 2026-12-04).
  if (pair_diagnostics_valid_) return;
  reduce_diagnostics();
  elastic_energy_ = 0.0;
  contact_count_ = 0;
  if (!diagnostics_valid_) return;  // nothing evaluated yet
  pair_diagnostics_valid_ = true;
  double energy = wall_elastic_energy_;
  std::size_t touching = 0;
  for (const std::uint8_t t : pair_touching_) touching += t;
  if (neighbors_.particle_count() == particles_.size() && neighbors_.pair_count() == pair_touching_.size())
    std::visit(
        [&]<class Law>(const ContactLawState<Law>& state) {
          if (state.pair_history.size() != pair_touching_.size()) return;
          energy =
              pair_elastic_energy(Law::for_pairs(state.evaluated_with), neighbors_, state.pair_history.data(),
                                  pair_touching_.data(), particles_, state.evaluated_with.rotation_enabled(), energy);
        },
        contact_state_);
  elastic_energy_ = energy;
  contact_count_ = touching;
}

}  // namespace demfit::dem_core
