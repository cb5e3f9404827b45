// Force evaluation: neighbours -> pair loads (per pair, parallel) -> per-particle gather in fixed
// CSR order -> wall loads (per particle, parallel) -> serial wall reduction. The loops are written
// once and templated on the contact law (no virtual call per contact); the law is chosen by one
// switch per evaluation.
#include <algorithm>
#include <cmath>

#include "demfit/dem_core/contact_law_hertz.hpp"
#include "demfit/dem_core/contact_law_linear.hpp"
#include "demfit/dem_core/simulation.hpp"

namespace demfit::dem_core {
namespace {

struct PairOutputs {
  Vec3* force;            // on the first particle
  Vec3* torque_first;
  Vec3* torque_second;
  double* energy;
  std::uint8_t* touching;
  double* max_overlap;    // per pair, with plasticity on, else null
};

template <class Law>
void pair_loop(const Law& law, const ParticleState& p, const NeighborList& list, ContactHistory* history,
               const PairOutputs& out, double dt, bool rotation, int threads) {
  const auto first = list.first();
  const auto second = list.second();
  const auto pairs = static_cast<std::int64_t>(list.pair_count());
#pragma omp parallel for schedule(static) num_threads(threads) if(threads > 1)
  for (std::int64_t kk = 0; kk < pairs; ++kk) {
    const auto k = static_cast<std::size_t>(kk);
    const std::size_t i = first[k], j = second[k];
    const Vec3 d = p.position[j] - p.position[i];
    const double r_sum = p.radius[i] + p.radius[j];
    const double dist2 = norm2(d);
    if (dist2 >= r_sum * r_sum) {
      if (!out.touching[k]) continue;  // already cleared
      history[k] = {};
      if constexpr (Law::tracks_max_overlap) if (out.max_overlap) out.max_overlap[k] = 0.0;
      out.force[k] = {}; out.torque_first[k] = {}; out.torque_second[k] = {};
      out.energy[k] = 0.0; out.touching[k] = 0;
      continue;
    }
    const double dist = std::sqrt(dist2);
    ContactGeometry g;
    g.normal = (1.0 / dist) * d;
    g.overlap = r_sum - dist;
    const double branch_i = p.radius[i] - 0.5 * g.overlap;
    const double branch_j = p.radius[j] - 0.5 * g.overlap;
    g.contact_velocity = p.velocity[i] - p.velocity[j];
    if (rotation) {
      g.contact_velocity += cross(p.angular_velocity[i], branch_i * g.normal) +
                            cross(p.angular_velocity[j], branch_j * g.normal);
      g.relative_angular_velocity = p.angular_velocity[i] - p.angular_velocity[j];
    }
    g.effective_mass = 1.0 / (p.inverse_mass[i] + p.inverse_mass[j]);
    g.effective_radius = p.radius[i] * p.radius[j] / r_sum;
    g.normal_compliance = p.normal_compliance[i] + p.normal_compliance[j];
    g.shear_compliance = p.shear_compliance[i] + p.shear_compliance[j];
    g.inverse_inertia_sum = p.inverse_inertia[i] + p.inverse_inertia[j];
    ContactForce f;
    if constexpr (Law::tracks_max_overlap) f = law.force(g, history[k], dt, out.max_overlap ? out.max_overlap + k : nullptr);
    else f = law.force(g, history[k], dt);
    out.force[k] = f.force;
    if (rotation) {
      out.torque_first[k] = cross(branch_i * g.normal, f.tangential_force) + f.rolling_torque;
      out.torque_second[k] = cross(branch_j * g.normal, f.tangential_force) - f.rolling_torque;
    }
    out.energy[k] = f.elastic_energy;
    out.touching[k] = 1;
  }
}

struct WallOutputs {
  Vec3* force;           // on the particle, index i * walls + w
  Vec3* contact_point;
  Vec3* rolling_torque;  // on the particle
  double* energy;
  std::uint8_t* touching;
  double* max_overlap;   // index i * walls + w, with plasticity on, else null
};

/// Loads of all walls on particle i, accumulated into the particle's force/torque in wall order.
template <class Law>
void wall_contacts_of(std::size_t i, const std::vector<Law>& laws, const std::vector<Wall>& walls,
                      const std::uint8_t* candidate, const std::uint8_t* always_checked, ParticleState& p,
                      ContactHistory* history, const WallOutputs& out, double dt, bool rotation) {
  const std::size_t count = walls.size();
  for (std::size_t w = 0; w < count; ++w) {
    const std::size_t slot = i * count + w;
    if (!candidate[slot] && !always_checked[w]) continue;  // cannot touch before the next rebuild
    const WallProximity prox = wall_proximity(walls[w].geometry, p.position[i], p.radius[i]);
    if (!prox.touching) {
      history[slot] = {};
      if constexpr (Law::tracks_max_overlap) if (out.max_overlap) out.max_overlap[slot] = 0.0;
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
    if constexpr (Law::tracks_max_overlap) f = laws[w].force(g, history[slot], dt, out.max_overlap ? out.max_overlap + slot : nullptr);
    else f = laws[w].force(g, history[slot], dt);
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
                const std::uint8_t* candidate, const std::uint8_t* always_checked, ParticleState& p, const NeighborList& list, ContactHistory* pair_history,
                const PairOutputs& pair_out, ContactHistory* wall_history, const WallOutputs& wall_out,
                const Vec3& gravity, double dt, double closing_kick, bool rotation, int threads) {
  pair_loop(pair_law, p, list, pair_history, pair_out, dt, rotation, threads);
  const auto rows = list.row_offsets();
  const auto columns = list.column_offsets();
  const auto column_pairs = list.column_pairs();
  const auto n = static_cast<std::int64_t>(p.size());
#pragma omp parallel for schedule(static) num_threads(threads) if(threads > 1)
  for (std::int64_t ii = 0; ii < n; ++ii) {
    const auto i = static_cast<std::size_t>(ii);
    // Fixed order: gravity, pairs where i is first (ascending j), pairs where i is second
    // (ascending first member), then walls in index order.
    Vec3 f = p.mass[i] * gravity;
    Vec3 t{};
    for (std::uint32_t k = rows[i]; k < rows[i + 1]; ++k) {
      f += pair_out.force[k];
      t += pair_out.torque_first[k];
    }
    for (std::uint32_t c = columns[i]; c < columns[i + 1]; ++c) {
      const std::uint32_t k = column_pairs[c];
      f -= pair_out.force[k];
      t += pair_out.torque_second[k];
    }
    p.force[i] = f;
    p.torque[i] = t;
    wall_contacts_of(i, wall_laws, walls, candidate, always_checked, p, wall_history, wall_out, dt, rotation);
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
    if (wall_layout_ok) wall_shift = std::max(wall_shift, norm(walls_[w].displacement - wall_displacement_at_build_[w]));
  }
  const bool stale = rebuild_requested_ || !wall_layout_ok || neighbors_.skin() != skin_now ||
                     neighbors_.particle_count() != particles_.size();
  // Particle pairs and particle-wall candidates stay valid while the relative motion of any two
  // bodies is below half the skin.
  if (!stale && moved < 0.0) moved = neighbors_.max_displacement(particles_.position, settings_.threads);
  if (!stale && moved + wall_shift <= 0.5 * skin_now) return;
  rebuild_requested_ = false;
  wall_displacement_at_build_.resize(walls);
  for (std::size_t w = 0; w < walls; ++w) wall_displacement_at_build_[w] = walls_[w].displacement;
  const std::vector<std::uint32_t> order = settings_.reorder_particles ? apply_spatial_order() : std::vector<std::uint32_t>{};
  find_wall_candidates();
  const NeighborList old = neighbors_;
  std::vector<ContactHistory> old_history;
  old_history.swap(pair_history_);
  std::vector<std::uint8_t> old_touching;
  old_touching.swap(pair_touching_);
  std::vector<double> old_max_overlap;  // plasticity only; empty otherwise
  old_max_overlap.swap(pair_max_overlap_);
  neighbors_.build(particles_.position, particles_.radius, skin_now, settings_.threads);
  carry_pair_histories(old, order, old_history, old_touching, old_max_overlap);
}

void Simulation::find_wall_candidates() {
  const std::size_t walls = walls_.size();
  const double margin = skin();
  wall_candidate_.resize(particles_.size() * walls);
  const auto n = static_cast<std::int64_t>(particles_.size());
#pragma omp parallel for schedule(static) num_threads(settings_.threads) if(settings_.threads > 1)
  for (std::int64_t ii = 0; ii < n; ++ii) {
    const auto i = static_cast<std::size_t>(ii);
    for (std::size_t w = 0; w < walls; ++w) {
      const std::size_t slot = i * walls + w;
      wall_candidate_[slot] = wall_may_touch(walls_[w].geometry, particles_.position[i], particles_.radius[i], margin) ? 1 : 0;
      if (!wall_candidate_[slot] && slot < wall_touching_.size()) {
        wall_touching_[slot] = 0;
        wall_history_[slot] = {};
        if (slot < wall_max_overlap_.size()) wall_max_overlap_[slot] = 0.0;
      }
    }
  }
}

void Simulation::compute_forces(double dt, double closing_kick, double moved) {
  ParticleState& p = particles_;
  const std::size_t walls = walls_.size();
  if (wall_history_.size() != p.size() * walls) wall_history_.assign(p.size() * walls, ContactHistory{});
  if (wall_touching_.size() != p.size() * walls) {  // layout (particles x walls) changed
    wall_force_on_particle_.assign(p.size() * walls, Vec3{});
    wall_contact_point_.assign(p.size() * walls, Vec3{});
    wall_rolling_torque_.assign(p.size() * walls, Vec3{});
    wall_energy_.assign(p.size() * walls, 0.0);
    wall_touching_.assign(p.size() * walls, 0);
  }
  ensure_neighbors(moved);
  const ContactParameters& c = settings_.contact;
  // One switch per evaluation picks the law type; the effects law only when an effect is on.
  const bool linear = settings_.law == ContactLawKind::lsdyna_linear;  // fixed for a simulation
  const bool effects = linear && c.effects_enabled();
  // Largest-overlap memory only for plasticity (the other effects do not read it): allocated
  // (zero = new contacts) on first use, null pointers otherwise.
  const bool plastic = effects && c.unloading_stiffness_ratio != 1.0;
  if (plastic) {
    if (pair_max_overlap_.size() != neighbors_.pair_count()) pair_max_overlap_.assign(neighbors_.pair_count(), 0.0);
    if (wall_max_overlap_.size() != p.size() * walls) wall_max_overlap_.assign(p.size() * walls, 0.0);
  } else if (!pair_max_overlap_.empty() || !wall_max_overlap_.empty()) {  // plasticity switched off
    pair_max_overlap_.clear();
    wall_max_overlap_.clear();
  }
  const PairOutputs pair_out{pair_force_.data(), pair_torque_first_.data(), pair_torque_second_.data(),
                             pair_energy_.data(), pair_touching_.data(), plastic ? pair_max_overlap_.data() : nullptr};
  const WallOutputs wall_out{wall_force_on_particle_.data(), wall_contact_point_.data(),
                             wall_rolling_torque_.data(), wall_energy_.data(), wall_touching_.data(),
                             plastic ? wall_max_overlap_.data() : nullptr};
  const bool rotation = settings_.contact.rotation_enabled();
  if (!wall_laws_valid_) {
    linear_wall_laws_.clear();
    effects_wall_laws_.clear();
    hertz_wall_laws_.clear();
    for (const Wall& w : walls_) {
      if (effects) effects_wall_laws_.push_back(make_effects_wall_law(c, w.contact));
      else if (linear) linear_wall_laws_.push_back(make_linear_wall_law(c, w.contact));
      else hertz_wall_laws_.push_back(make_hertz_wall_law(c, w.contact));
    }
    wall_laws_valid_ = true;
  }
  if (effects) {
    all_forces(make_effects_pair_law(c), effects_wall_laws_, walls_, wall_candidate_.data(), wall_always_checked_.data(), p, neighbors_, pair_history_.data(), pair_out,
               wall_history_.data(), wall_out, settings_.gravity, dt, closing_kick, rotation, settings_.threads);
  } else if (linear) {
    all_forces(make_linear_pair_law(c), linear_wall_laws_, walls_, wall_candidate_.data(), wall_always_checked_.data(), p, neighbors_, pair_history_.data(), pair_out,
               wall_history_.data(), wall_out, settings_.gravity, dt, closing_kick, rotation, settings_.threads);
  } else {
    all_forces(make_hertz_pair_law(c), hertz_wall_laws_, walls_, wall_candidate_.data(), wall_always_checked_.data(), p, neighbors_, pair_history_.data(), pair_out,
               wall_history_.data(), wall_out, settings_.gravity, dt, closing_kick, rotation, settings_.threads);
  }
  diagnostics_valid_ = false;
  forces_valid_ = true;
}

void Simulation::reduce_diagnostics() const {
  if (diagnostics_valid_) return;
  // Serial, fixed-order sums: wall loads and energies are identical for any thread count.
  const std::size_t walls = walls_.size();
  for (Wall& w : walls_) { w.force = {}; w.moment = {}; w.torque = 0.0; w.contact_count = 0; }
  elastic_energy_ = 0.0;
  contact_count_ = 0;
  if (!forces_valid_ || wall_touching_.size() != particles_.size() * walls) return;  // nothing evaluated yet
  diagnostics_valid_ = true;
  double energy = 0.0;
  for (std::size_t i = 0; i < particles_.size(); ++i) {
    for (std::size_t w = 0; w < walls; ++w) {
      const std::size_t slot = i * walls + w;
      if (!wall_touching_[slot]) continue;
      Wall& wall = walls_[w];
      // The wall receives -F at the contact point and the couple -M_r.
      const Vec3 f = -wall_force_on_particle_[slot];
      wall.force += f;
      wall.moment += cross(wall_contact_point_[slot] - wall.torque_axis.point, f) - wall_rolling_torque_[slot];
      ++wall.contact_count;
      energy += wall_energy_[slot];
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
