// Force evaluation: neighbours -> pair loads (per pair, parallel) -> per-particle gather in fixed
// CSR order -> wall loads (per particle, parallel) -> serial wall reduction. The loops are written
// once and templated on the contact law (no virtual call per contact); the law is chosen by one
// switch per evaluation.
#include <algorithm>
#include <cmath>
#include <utility>

#include "demfit/dem_core/contact_law_hertz.hpp"
#include "demfit/dem_core/contact_law_linear.hpp"
#include "demfit/dem_core/simulation.hpp"

namespace demfit::dem_core {
namespace {

struct PairOutputs {
  Vec3* force;          // on the first particle (the second particle gathers -force)
  Vec3* torque_second;  // on the second particle (the first one sums its torque directly)
  double* energy;
  std::uint8_t* touching;
  double* max_overlap;  // per pair, with plasticity on, else null
};

/// Loads of one pair k = (i, j), i < j: stores what j gathers later and returns i's force and
/// torque contributions (zero for a pair out of contact, added like the stored zeros were).
template <class Law>
void pair_contact(const Law& law, const ParticleState& p, std::size_t k, std::size_t i, std::size_t j,
                  ContactHistory* history, const PairOutputs& out, double dt, bool rotation, Vec3& force_i,
                  Vec3& torque_i) {
  const Vec3 d = p.position[j] - p.position[i];
  const double r_sum = p.radius[i] + p.radius[j];
  const double dist2 = norm2(d);
  if (dist2 >= r_sum * r_sum) {
    force_i = {};
    torque_i = {};
    if (!out.touching[k]) return;  // already cleared
    history[k] = {};
    if constexpr (Law::tracks_max_overlap)
      if (out.max_overlap) out.max_overlap[k] = 0.0;
    out.force[k] = {};
    out.torque_second[k] = {};
    out.energy[k] = 0.0;
    out.touching[k] = 0;
    return;
  }
  const double dist = std::sqrt(dist2);
  ContactGeometry g;
  g.normal = (1.0 / dist) * d;
  g.overlap = r_sum - dist;
  const double branch_i = p.radius[i] - 0.5 * g.overlap;
  const double branch_j = p.radius[j] - 0.5 * g.overlap;
  g.contact_velocity = p.velocity[i] - p.velocity[j];
  if (rotation) {
    g.contact_velocity +=
        cross(p.angular_velocity[i], branch_i * g.normal) + cross(p.angular_velocity[j], branch_j * g.normal);
    g.relative_angular_velocity = p.angular_velocity[i] - p.angular_velocity[j];
  }
  g.effective_mass = 1.0 / (p.inverse_mass[i] + p.inverse_mass[j]);
  g.effective_radius = p.radius[i] * p.radius[j] / r_sum;
  g.normal_compliance = p.normal_compliance[i] + p.normal_compliance[j];
  g.shear_compliance = p.shear_compliance[i] + p.shear_compliance[j];
  g.inverse_inertia_sum = p.inverse_inertia[i] + p.inverse_inertia[j];
  ContactForce f;
  if constexpr (Law::tracks_max_overlap)
    f = law.force(g, history[k], dt, out.max_overlap ? out.max_overlap + k : nullptr);
  else
    f = law.force(g, history[k], dt);
  out.force[k] = f.force;
  force_i = f.force;
  torque_i = {};
  if (rotation) {
    torque_i = cross(branch_i * g.normal, f.tangential_force) + f.rolling_torque;
    out.torque_second[k] = cross(branch_j * g.normal, f.tangential_force) - f.rolling_torque;
  }
  out.energy[k] = f.elastic_energy;
  out.touching[k] = 1;
}

/// Pair loads row by row (rows of the half list are contiguous pair ranges): the first member's
/// force and torque are summed as the row is computed (gravity first, then ascending j: the fixed
/// order of the gather), so only the second member's share is stored per pair.
template <class Law>
void pair_rows(const Law& law, ParticleState& p, const NeighborList& list, ContactHistory* history,
               const PairOutputs& out, const Vec3& gravity, double dt, bool rotation, int threads) {
  const auto rows = list.row_offsets();
  const auto second = list.second();
  const auto n = static_cast<std::int64_t>(p.size());
#pragma omp parallel for schedule(static) num_threads(threads) if (threads > 1)
  for (std::int64_t ii = 0; ii < n; ++ii) {
    const auto i = static_cast<std::size_t>(ii);
    Vec3 f = p.mass[i] * gravity;
    Vec3 t{};
    for (std::uint32_t k = rows[i]; k < rows[i + 1]; ++k) {
      Vec3 force_i, torque_i;
      pair_contact(law, p, k, i, second[k], history, out, dt, rotation, force_i, torque_i);
      f += force_i;
      t += torque_i;
    }
    p.force[i] = f;
    p.torque[i] = t;
  }
}

struct WallOutputs {
  const std::uint32_t* rows;  // slots of particle i: [rows[i], rows[i+1])
  const std::uint32_t* wall;  // wall of each slot
  Vec3* force;                // on the particle, per slot
  Vec3* contact_point;
  Vec3* rolling_torque;  // on the particle
  double* energy;
  std::uint8_t* touching;
  double* max_overlap;  // per slot, with plasticity on, else null
};

/// Loads of the candidate walls on particle i (the others cannot touch it before the next
/// rebuild), accumulated into the particle's force/torque in wall order.
template <class Law>
void wall_contacts_of(std::size_t i, const std::vector<Law>& laws, const std::vector<Wall>& walls, ParticleState& p,
                      ContactHistory* history, const WallOutputs& out, double dt, bool rotation) {
  for (std::uint32_t slot = out.rows[i]; slot < out.rows[i + 1]; ++slot) {
    const std::size_t w = out.wall[slot];
    const WallProximity prox = wall_proximity(walls[w].geometry, p.position[i], p.radius[i]);
    if (!prox.touching) {
      history[slot] = {};
      if constexpr (Law::tracks_max_overlap)
        if (out.max_overlap) out.max_overlap[slot] = 0.0;
      out.touching[slot] = 0;
      continue;
    }
    ContactGeometry g;
    g.normal = prox.normal;
    g.overlap = prox.overlap;
    const double branch = p.radius[i] - prox.overlap;  // contact point on the wall surface
    const Vec3 contact_point = p.position[i] + branch * prox.normal;
    g.contact_velocity = p.velocity[i] - wall_velocity_at(walls[w], contact_point);
    if (rotation) {
      g.contact_velocity += cross(p.angular_velocity[i], branch * prox.normal);
      g.relative_angular_velocity = p.angular_velocity[i] - wall_angular_velocity(walls[w]);
    }
    g.effective_mass = p.mass[i];
    g.effective_radius = p.radius[i];
    g.normal_compliance = p.normal_compliance[i] / walls[w].contact.sfp;  // k_n,w = SFP k_i
    g.shear_compliance = p.shear_compliance[i];
    g.inverse_inertia_sum = p.inverse_inertia[i];
    ContactForce f;
    if constexpr (Law::tracks_max_overlap)
      f = laws[w].force(g, history[slot], dt, out.max_overlap ? out.max_overlap + slot : nullptr);
    else
      f = laws[w].force(g, history[slot], dt);
    p.force[i] += f.force;
    if (rotation) p.torque[i] += cross(branch * prox.normal, f.tangential_force) + f.rolling_torque;
    out.force[slot] = f.force;
    out.contact_point[slot] = contact_point;
    out.rolling_torque[slot] = rotation ? f.rolling_torque : Vec3{};
    out.energy[slot] = f.elastic_energy;
    out.touching[slot] = 1;
  }
}

template <class Law, class WallLaw>
void all_forces(const Law& pair_law, const std::vector<WallLaw>& wall_laws, const std::vector<Wall>& walls,
                ParticleState& p, const NeighborList& list, ContactHistory* pair_history, const PairOutputs& pair_out,
                ContactHistory* wall_history, const WallOutputs& wall_out, const Vec3& gravity, double dt,
                double closing_kick, bool rotation, int threads) {
  pair_rows(pair_law, p, list, pair_history, pair_out, gravity, dt, rotation, threads);
  const auto columns = list.column_offsets();
  const auto column_pairs = list.column_pairs();
  const auto n = static_cast<std::int64_t>(p.size());
#pragma omp parallel for schedule(static) num_threads(threads) if (threads > 1)
  for (std::int64_t ii = 0; ii < n; ++ii) {
    const auto i = static_cast<std::size_t>(ii);
    // Fixed order: gravity and pairs where i is first (ascending j, summed by pair_rows), pairs
    // where i is second (ascending first member), then walls in index order.
    Vec3 f = p.force[i];
    Vec3 t = p.torque[i];
    for (std::uint32_t c = columns[i]; c < columns[i + 1]; ++c) {
      const std::uint32_t k = column_pairs[c];
      f -= pair_out.force[k];
      t += pair_out.torque_second[k];
    }
    p.force[i] = f;
    p.torque[i] = t;
    wall_contacts_of(i, wall_laws, walls, p, wall_history, wall_out, dt, rotation);
    // Second velocity-Verlet half kick with the complete new loads (fused: one pass).
    p.velocity[i] += (closing_kick * p.inverse_mass[i]) * p.force[i];
    if (rotation) p.angular_velocity[i] += (closing_kick * p.inverse_inertia[i]) * p.torque[i];
  }
}

}  // namespace

void Simulation::ensure_neighbors(double moved) {
  const double skin_now = skin();
  const std::size_t walls = walls_.size();
  wall_always_checked_.resize(walls);
  double wall_shift = 0.0;
  const bool wall_layout_ok = wall_displacement_at_build_.size() == walls;
  for (std::size_t w = 0; w < walls; ++w) {
    wall_always_checked_[w] = wall_distances_rigid(walls_[w]) ? 0 : 1;
    if (wall_layout_ok)
      wall_shift = std::max(wall_shift, norm(walls_[w].displacement - wall_displacement_at_build_[w]));
  }
  const bool stale = rebuild_requested_ || !wall_layout_ok || neighbors_.skin() != skin_now ||
                     neighbors_.particle_count() != particles_.size() || !wall_slots_.built_for(particles_.size());
  // Particle pairs and particle-wall candidates stay valid while the relative motion of any two
  // bodies is below half the skin.
  if (!stale && moved < 0.0) moved = neighbors_.max_displacement(particles_.position, settings_.threads);
  if (!stale && moved + wall_shift <= 0.5 * skin_now) return;
  rebuild_requested_ = false;
  wall_displacement_at_build_.resize(walls);
  for (std::size_t w = 0; w < walls; ++w) wall_displacement_at_build_[w] = walls_[w].displacement;
  const std::vector<std::uint32_t> order =
      settings_.reorder_particles ? apply_spatial_order() : std::vector<std::uint32_t>{};
  find_wall_candidates(order);
  // Moved, not copied (peak memory at rebuilds); the counters stay with neighbors_.
  const NeighborList old = std::move(neighbors_);
  std::vector<ContactHistory> old_history;
  old_history.swap(pair_history_);
  std::vector<std::uint8_t> old_touching;
  old_touching.swap(pair_touching_);
  std::vector<double> old_max_overlap;  // plasticity only; empty otherwise
  old_max_overlap.swap(pair_max_overlap_);
  neighbors_.build(particles_.position, particles_.radius, skin_now, settings_.threads);
  carry_pair_histories(old, order, old_history, old_touching, old_max_overlap);
}

void Simulation::compute_forces(double dt, double closing_kick, double moved) {
  ParticleState& p = particles_;
  ensure_neighbors(moved);  // (re)builds the wall slots too
  WallSlots& slots = wall_slots_;
  const ContactParameters& c = settings_.contact;
  // One switch per evaluation picks the law type; the effects law only when an effect is on.
  const bool linear = settings_.law == ContactLawKind::lsdyna_linear;  // fixed for a simulation
  const bool effects = linear && c.effects_enabled();
  // Largest-overlap memory only for plasticity (the other effects do not read it): allocated
  // (zero = new contacts) on first use, null pointers otherwise.
  const bool plastic = effects && c.unloading_stiffness_ratio != 1.0;
  if (plastic) {
    if (pair_max_overlap_.size() != neighbors_.pair_count()) pair_max_overlap_.assign(neighbors_.pair_count(), 0.0);
    if (slots.max_overlap.size() != slots.size()) slots.max_overlap.assign(slots.size(), 0.0);
  } else if (!pair_max_overlap_.empty() || !slots.max_overlap.empty()) {  // plasticity switched off
    pair_max_overlap_.clear();
    slots.max_overlap.clear();
  }
  const PairOutputs pair_out{pair_force_.data(), pair_torque_second_.data(), pair_energy_.data(), pair_touching_.data(),
                             plastic ? pair_max_overlap_.data() : nullptr};
  const WallOutputs wall_out{slots.rows.data(),
                             slots.wall.data(),
                             slots.force_on_particle.data(),
                             slots.contact_point.data(),
                             slots.rolling_torque.data(),
                             slots.energy.data(),
                             slots.touching.data(),
                             plastic ? slots.max_overlap.data() : nullptr};
  const bool rotation = settings_.contact.rotation_enabled();
  if (!wall_laws_valid_) {
    linear_wall_laws_.clear();
    effects_wall_laws_.clear();
    hertz_wall_laws_.clear();
    for (const Wall& w : walls_) {
      if (effects)
        effects_wall_laws_.push_back(make_effects_wall_law(c, w.contact));
      else if (linear)
        linear_wall_laws_.push_back(make_linear_wall_law(c, w.contact));
      else
        hertz_wall_laws_.push_back(make_hertz_wall_law(c, w.contact));
    }
    wall_laws_valid_ = true;
  }
  if (effects) {
    all_forces(make_effects_pair_law(c), effects_wall_laws_, walls_, p, neighbors_, pair_history_.data(), pair_out,
               slots.history.data(), wall_out, settings_.gravity, dt, closing_kick, rotation, settings_.threads);
  } else if (linear) {
    all_forces(make_linear_pair_law(c), linear_wall_laws_, walls_, p, neighbors_, pair_history_.data(), pair_out,
               slots.history.data(), wall_out, settings_.gravity, dt, closing_kick, rotation, settings_.threads);
  } else {
    all_forces(make_hertz_pair_law(c), hertz_wall_laws_, walls_, p, neighbors_, pair_history_.data(), pair_out,
               slots.history.data(), wall_out, settings_.gravity, dt, closing_kick, rotation, settings_.threads);
  }
  diagnostics_valid_ = false;
  forces_valid_ = true;
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
  elastic_energy_ = 0.0;
  contact_count_ = 0;
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
  std::size_t touching = 0;
  for (std::size_t k = 0; k < pair_energy_.size(); ++k) {
    energy += pair_energy_[k];
    touching += pair_touching_[k];
  }
  elastic_energy_ = energy;
  contact_count_ = touching;
}

}  // namespace demfit::dem_core
