#pragma once
// The force loops, written once and templated on the contact law (no virtual call per contact):
// pair loads row by row over the half list (parallel), the per-particle gather in the fixed CSR
// order, the particle's candidate walls and the closing half kick. Internal to Simulation
// (simulation_forces.cpp instantiates them once per law of contact_laws.hpp).
#include <cmath>
#include <cstdint>
#include <vector>

#include "demfit/dem_core/contact_geometry.hpp"
#include "demfit/dem_core/neighbor_list.hpp"
#include "demfit/dem_core/particle_state.hpp"
#include "demfit/dem_core/wall.hpp"

namespace demfit::dem_core {

/// The pair side: the law, the half list, the pairs' histories and what the loop stores per pair.
template <class Law>
struct PairSide {
  const Law& law;
  const NeighborList& list;
  typename Law::History* history;
  Vec3* force;          // on the first particle (the second particle gathers -force)
  Vec3* torque_second;  // on the second particle (the first one sums its torque directly)
  std::uint8_t* touching;
};

/// The wall side: a law per wall, the walls, the candidate slots, their histories and loads.
template <class Law>
struct WallSide {
  const std::vector<Law>& laws;
  const std::vector<Wall>& walls;
  const std::uint32_t* rows;  // slots of particle i: [rows[i], rows[i+1])
  const std::uint32_t* wall;  // wall of each slot
  typename Law::History* history;
  Vec3* force;  // on the particle, per slot
  Vec3* contact_point;
  Vec3* rolling_torque;  // on the particle
  double* energy;
  std::uint8_t* touching;
  const std::uint32_t* triangle_rows;  // mesh walls: candidate triangles of each slot (WallSlots)
  const std::uint32_t* triangles;
};

/// The step: gravity [m/s^2], dt [s] (0 = no history increment), closing half kick [s] (0 =
/// none), whether particles rotate, OpenMP threads.
struct StepInputs {
  Vec3 gravity;
  double dt;
  double closing_kick;
  bool rotation;
  int threads;
};

/// Geometry and kinematics of the pair (i, j), i < j, when the spheres overlap (false: apart).
/// branch_i/j [m]: centre-to-contact-point distances (the contact point halves the overlap).
/// Always inlined: called once per neighbour pair per step, and GCC 12 stopped inlining it on its
/// own when ContactGeometry grew (the drum benchmark lost ~30 % of its pair throughput).
[[gnu::always_inline]] inline bool pair_geometry(const ParticleState& p, std::size_t i, std::size_t j, bool rotation,
                                                 ContactGeometry& g, double& branch_i, double& branch_j) {
  const Vec3 d = p.position[j] - p.position[i];
  const double r_sum = p.radius[i] + p.radius[j];
  const double dist2 = norm2(d);
  if (dist2 >= r_sum * r_sum) return false;
  const double dist = std::sqrt(dist2);
  g.normal = (1.0 / dist) * d;
  g.overlap = r_sum - dist;
  branch_i = p.radius[i] - 0.5 * g.overlap;
  branch_j = p.radius[j] - 0.5 * g.overlap;
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
  g.first_radius = p.radius[i];
  g.second_radius = p.radius[j];
  return true;
}

/// Contact of pair k = (i, j), i < j: false (history cleared) when the spheres are apart, else
/// the law's loads with its history advanced by dt. The one place a pair's loads are computed,
/// for both PairLoadOrder variants.
template <class Law>
[[gnu::always_inline]] inline bool pair_loads(const Law& law, typename Law::History* history, std::uint8_t* touching,
                                              const ParticleState& p, std::size_t k, std::size_t i, std::size_t j,
                                              const StepInputs& step, PairLoads& out) {
  ContactGeometry g;
  double branch_i = 0.0, branch_j = 0.0;
  if (!pair_geometry(p, i, j, step.rotation, g, branch_i, branch_j)) {
    if (touching[k]) {
      history[k] = {};
      touching[k] = 0;
    }
    return false;
  }
  const ContactForce f = law.force(g, history[k], step.dt);
  out.force = f.force;
  out.torque_first = {};
  out.torque_second = {};
  if (step.rotation) {
    out.torque_first = cross(branch_i * g.normal, f.tangential_force) + f.rolling_torque;
    out.torque_second = cross(branch_j * g.normal, f.tangential_force) - f.rolling_torque;
  }
  touching[k] = 1;
  return true;
}

/// Loads of one pair k = (i, j), i < j, in PairLoadOrder::own_row_first: stores what j gathers
/// later and returns i's force and torque contributions (zero for a pair out of contact, added
/// like the stored zeros were).
template <class Law>
void pair_contact(const PairSide<Law>& pairs, const ParticleState& p, std::size_t k, std::size_t i, std::size_t j,
                  const StepInputs& step, Vec3& force_i, Vec3& torque_i) {
  const bool was_touching = pairs.touching[k] != 0;
  PairLoads loads;
  if (!pair_loads(pairs.law, pairs.history, pairs.touching, p, k, i, j, step, loads)) {
    force_i = {};
    torque_i = {};
    if (!was_touching) return;  // already cleared
    pairs.force[k] = {};
    pairs.torque_second[k] = {};
    return;
  }
  pairs.force[k] = loads.force;
  force_i = loads.force;
  torque_i = loads.torque_first;
  if (step.rotation) pairs.torque_second[k] = loads.torque_second;
}

/// Elastic energy [J] of the pairs in contact, in pair order, computed only when asked for (a
/// stored per-pair energy would cost 8 bytes per pair on every step): the law's spring energy at
/// the current positions with the stored histories, the same value the last evaluation computed
/// when the particles have not moved since. Each pair is added to `energy` (the walls' sum) in
/// pair order, as the stored energies were: a separate pair subtotal would round differently.
template <class Law>
double pair_elastic_energy(const Law& law, const NeighborList& list, const typename Law::History* history,
                           const std::uint8_t* touching, const ParticleState& p, bool rotation, double energy) {
  const auto rows = list.row_offsets();
  const auto second = list.second();
  for (std::size_t i = 0; i + 1 < rows.size(); ++i)
    for (std::uint32_t k = rows[i]; k < rows[i + 1]; ++k) {
      ContactGeometry g;
      double branch_i = 0.0, branch_j = 0.0;
      if (!touching[k] || !pair_geometry(p, i, second[k], rotation, g, branch_i, branch_j)) continue;
      energy += law.elastic_energy(g, history[k]);
    }
  return energy;
}

/// Pair loads row by row (rows of the half list are contiguous pair ranges): the first member's
/// force and torque are summed as the row is computed (gravity first, then ascending j: the fixed
/// order of the gather), so only the second member's share is stored per pair.
template <class Law>
void pair_rows(const PairSide<Law>& pairs, ParticleState& p, const StepInputs& step) {
  const auto rows = pairs.list.row_offsets();
  const auto second = pairs.list.second();
  const auto n = static_cast<std::int64_t>(p.size());
#pragma omp parallel for schedule(static) num_threads(step.threads) if (step.threads > 1)
  for (std::int64_t ii = 0; ii < n; ++ii) {
    const auto i = static_cast<std::size_t>(ii);
    Vec3 f = p.mass[i] * step.gravity;
    Vec3 t{};
    for (std::uint32_t k = rows[i]; k < rows[i + 1]; ++k) {
      Vec3 force_i, torque_i;
      pair_contact(pairs, p, k, i, second[k], step, force_i, torque_i);
      f += force_i;
      t += torque_i;
    }
    p.force[i] = f;
    p.torque[i] = t;
  }
}

/// Loads of one wall contact (`prox`, or none) in slot `slot` of particle i, added to the
/// particle's force/torque; a slot out of contact has its history cleared.
template <class Law>
void wall_slot_contact(std::size_t i, std::uint32_t slot, const Wall& wall, const WallProximity& prox,
                       const WallSide<Law>& walls, ParticleState& p, const StepInputs& step) {
  if (!prox.touching) {
    walls.history[slot] = {};
    walls.touching[slot] = 0;
    return;
  }
  ContactGeometry g;
  g.normal = prox.normal;
  g.overlap = prox.overlap;
  const double branch = p.radius[i] - prox.overlap;  // contact point on the wall surface
  const Vec3 contact_point = p.position[i] + branch * prox.normal;
  g.contact_velocity = p.velocity[i] - wall_velocity_at(wall, contact_point);
  if (step.rotation) {
    g.contact_velocity += cross(p.angular_velocity[i], branch * prox.normal);
    g.relative_angular_velocity = p.angular_velocity[i] - wall_angular_velocity(wall);
  }
  g.effective_mass = p.mass[i];
  g.effective_radius = p.radius[i];
  g.normal_compliance = p.normal_compliance[i] / wall.contact.sfp;  // k_n,w = SFP k_i
  g.shear_compliance = p.shear_compliance[i];
  g.inverse_inertia_sum = p.inverse_inertia[i];
  g.first_radius = p.radius[i];  // second_radius 0: the wall is a plane at the contact
  const ContactForce f = walls.laws[walls.wall[slot]].force(g, walls.history[slot], step.dt);
  p.force[i] += f.force;
  if (step.rotation) p.torque[i] += cross(branch * prox.normal, f.tangential_force) + f.rolling_torque;
  walls.force[slot] = f.force;
  walls.contact_point[slot] = contact_point;
  walls.rolling_torque[slot] = step.rotation ? f.rolling_torque : Vec3{};
  walls.energy[slot] = f.elastic_energy;
  walls.touching[slot] = 1;
}

/// A mesh wall's slots [first, end) of particle i: its contacts (deepest first) are matched to
/// the slots that were touching with the closest previous normal (direction to the previous
/// contact point, within 60 degrees), so a contact keeps its tangential history while its normal
/// turns continuously, whichever triangle carries it; new contacts take free slots, in slot
/// order; contacts beyond the slots are dropped (the shallowest). Returns `end`.
template <class Law>
std::uint32_t mesh_slot_contacts(std::size_t i, std::uint32_t first, std::uint32_t end, const Wall& wall,
                                 const MeshGeometry& mesh, const WallSide<Law>& walls, ParticleState& p,
                                 const StepInputs& step) {
  WallProximity found[8];
  const int slots = static_cast<int>(end - first);
  const std::span<const std::uint32_t> candidates(walls.triangles + walls.triangle_rows[first],
                                                  walls.triangles + walls.triangle_rows[first + 1]);
  const int n = mesh_wall_contacts(mesh, p.position[i], p.radius[i], candidates, found, slots);
  int contact_of[8] = {-1, -1, -1, -1, -1, -1, -1, -1};  // per slot
  for (int k = 0; k < n; ++k) {
    int best = -1;
    double best_cos = 0.5;
    for (int s = 0; s < slots; ++s) {
      const std::uint32_t slot = first + static_cast<std::uint32_t>(s);
      if (contact_of[s] >= 0 || !walls.touching[slot]) continue;
      const double c = dot(normalized(walls.contact_point[slot] - p.position[i]), found[k].normal);
      if (c > best_cos) best = s, best_cos = c;
    }
    for (int s = 0; s < slots && best < 0; ++s)
      if (contact_of[s] < 0 && !walls.touching[first + static_cast<std::uint32_t>(s)]) best = s;
    for (int s = 0; s < slots && best < 0; ++s)  // a touching slot whose contact has ended
      if (contact_of[s] < 0) best = s;
    if (best >= 0) contact_of[best] = k;
  }
  for (int s = 0; s < slots; ++s)
    wall_slot_contact(i, first + static_cast<std::uint32_t>(s), wall,
                      contact_of[s] >= 0 ? found[contact_of[s]] : WallProximity{}, walls, p, step);
  return end;
}

/// Loads of the candidate walls on particle i (the others cannot touch it before the next
/// rebuild), accumulated into the particle's force/torque in wall order (a mesh wall's slots are
/// consecutive). The geometry is dispatched on the variant index, no virtual call.
template <class Law>
void wall_contacts_of(std::size_t i, const WallSide<Law>& walls, ParticleState& p, const StepInputs& step) {
  const std::uint32_t row_end = walls.rows[i + 1];
  for (std::uint32_t slot = walls.rows[i]; slot < row_end;) {
    const std::uint32_t w = walls.wall[slot];
    const Wall& wall = walls.walls[w];
    if (const auto* mesh = std::get_if<MeshGeometry>(&wall.geometry)) {
      std::uint32_t end = slot + 1;
      while (end < row_end && walls.wall[end] == w) ++end;
      slot = mesh_slot_contacts(i, slot, end, wall, *mesh, walls, p, step);
      continue;
    }
    wall_slot_contact(i, slot, wall, wall_proximity(wall.geometry, p.position[i], p.radius[i]), walls, p, step);
    ++slot;
  }
}

/// The walls' loads on particle i (after all its pair loads) and the second velocity-Verlet half
/// kick with the complete new loads (fused: one pass).
template <class Law>
void finish_particle(std::size_t i, const WallSide<Law>& walls, ParticleState& p, const StepInputs& step) {
  wall_contacts_of(i, walls, p, step);
  p.velocity[i] += (step.closing_kick * p.inverse_mass[i]) * p.force[i];
  if (step.rotation) p.angular_velocity[i] += (step.closing_kick * p.inverse_inertia[i]) * p.torque[i];
}

/// All loads and the closing half kick in PairLoadOrder::own_row_first. Fixed order per particle: gravity and pairs
/// where i is first (ascending j, summed by pair_rows), pairs where i is second (ascending first member), then walls in
/// index order.
template <class Law>
void all_forces(const PairSide<Law>& pairs, const WallSide<Law>& walls, ParticleState& p, const StepInputs& step) {
  pair_rows(pairs, p, step);
  const auto columns = pairs.list.column_offsets();
  const auto column_pairs = pairs.list.column_pairs();
  const auto n = static_cast<std::int64_t>(p.size());
#pragma omp parallel for schedule(static) num_threads(step.threads) if (step.threads > 1)
  for (std::int64_t ii = 0; ii < n; ++ii) {
    const auto i = static_cast<std::size_t>(ii);
    Vec3 f = p.force[i];
    Vec3 t = p.torque[i];
    for (std::uint32_t c = columns[i]; c < columns[i + 1]; ++c) {
      const std::uint32_t k = column_pairs[c];
      f -= pairs.force[k];
      t += pairs.torque_second[k];
    }
    p.force[i] = f;
    p.torque[i] = t;
    finish_particle(i, walls, p, step);
  }
}

}  // namespace demfit::dem_core
