#pragma once
// Simulation: owns particles, walls, neighbour list and contact histories, and orchestrates one
// velocity-Verlet step: half kick -> drift -> walls move -> neighbours -> pair forces -> wall
// forces -> half kick. Units SI throughout; one global inertial frame.
//
// Determinism: every particle sums its loads in a fixed order that does not depend on the
// thread count (PairLoadOrder); wall loads are reduced serially in particle order. The result is
// therefore bit-identical for repeated runs AND for any thread count (measured in
// tests/dem_core/test_determinism.cpp and test_pair_load_order.cpp: 1, 2 and 3 threads agree bitwise).
//
// FRICS = 0 (ContactParameters::frics) disables rotation entirely, as in LS-DYNA: angular
// velocities stay zero, tangential forces (walls may still have friction) act on the centres only.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "demfit/dem_core/chunk_balance.hpp"
#include "demfit/dem_core/contact_geometry.hpp"
#include "demfit/dem_core/contact_laws.hpp"
#include "demfit/dem_core/neighbor_list.hpp"
#include "demfit/dem_core/parameters.hpp"
#include "demfit/dem_core/particle_state.hpp"
#include "demfit/dem_core/vec3.hpp"
#include "demfit/dem_core/wall.hpp"
#include "demfit/dem_core/wall_slots.hpp"

namespace demfit::dem_core {

/// The order in which each particle sums its pair loads. Both are deterministic and the same for
/// any thread count; they are two round-off realisations of the same physics.
enum class PairLoadOrder {
  /// Gravity, the pairs where the particle is first (ascending partner), then those where it is
  /// second, gathered from per-pair stored loads through a transposed index (53 bytes per pair
  /// more). Every shipped case result was made in this order.
  own_row_first,
  /// Gravity, then every pair in ascending first member, summed as the rows are computed
  /// (src/contact_loops_streamed.hpp): nothing stored per pair (the kernel's memory target, bench_dem --only scaling).
  ascending_first_member,
};

struct SimulationSettings {
  ContactLawKind law = ContactLawKind::lsdyna_linear;
  ContactParameters contact{};    ///< particle–particle parameters (docs/spec.md 1); its effects
                                  ///< (plasticity, cohesion, stiffness exponent) need the linear law
  Vec3 gravity{0.0, 0.0, -9.81};  ///< [m/s^2], global frame
  /// OpenMP threads used by this simulation (>= 1; 1 = no OpenMP region at all). How idle threads
  /// wait at the 3 barriers per step matters: unbounded spinning for a preempted partner made 2
  /// threads 5-10x SLOWER than 1 on a loaded machine, passive waiting costs ~10 % at every
  /// wake-up; programs call use_bounded_spin_waiting (openmp_waiting.hpp) first thing in main.
  int threads = 1;
  /// User time step [s]; 0 = automatic. A user step above stable_time_step() is refused.
  double time_step = 0.0;
  /// Automatic step = min(factor * 2 pi sqrt(m*/k_n) of the stiffest contact (LS-DYNA uses
  /// 0.15), damping-dependent stability bounds); the factor scales only the first term. See
  /// time_step.hpp (rotation, damping, Hertz variant).
  double time_step_factor = 0.15;
  /// Verlet skin [m]; <= 0 means 0.3 x the largest radius (set when the first step runs).
  double skin = 0.0;
  /// Sort the particles into slabs across the bed's longest extent, Morton order inside a slab
  /// (particle_order.hpp), at every neighbour-list rebuild, so
  /// that neighbours in space are neighbours in memory (large mixed beds are otherwise
  /// memory-bound). All per-particle arrays and contact histories follow the permutation; results
  /// stay deterministic and identical for any thread count, but particle INDICES then change at
  /// rebuilds: identify particles by ParticleState::id (outputs are written in id order). On by
  /// default: on the issue-16 drum x1.51 on 2 threads and nothing on 1 (bench/dem_core/measured/
  /// drum_2026-12-02_reorder_default.txt), 3.3x less cost growth from 1e4 to 1e6 particles;
  /// switch it off to follow a particle by its index.
  bool reorder_particles = true;
  /// dem_core's default is the leaner order; cases keep own_row_first unless they ask
  /// (cases' "numerics.pair_load_order"), so their results stay as published.
  PairLoadOrder pair_load_order = PairLoadOrder::ascending_first_member;
};

class Simulation;

/// Called by run_until every `every` steps with the simulation (which it may modify, e.g. change
/// a wall's motion); return false to stop the run.
using StepCallback = std::function<bool(Simulation&)>;

class Simulation {
 public:
  explicit Simulation(SimulationSettings settings = {});

  // ---- building -----------------------------------------------------------------------------
  /// Register a material; returns its index (first material is 0).
  std::size_t add_material(const Material& material);
  /// Add a solid sphere: centre [m], radius [m] > 0, material index, velocity [m/s], angular
  /// velocity [rad/s]. Returns the particle index. Throws std::runtime_error on bad input.
  std::size_t add_particle(const Vec3& position, double radius, std::size_t material = 0, const Vec3& velocity = {},
                           const Vec3& angular_velocity = {});
  /// Remove the particles whose flag is true (flags.size() == particle_count()); indices of the
  /// remaining particles are compacted in order (their ids are kept); contact histories are dropped.
  void remove_particles(const std::vector<bool>& flags);
  /// Returns the wall index. Restarts the particle–wall contact histories (pair histories stay).
  std::size_t add_wall(const WallSpec& spec);

  // ---- settings changeable between steps ----------------------------------------------------
  void set_gravity(const Vec3& gravity);
  void set_contact_parameters(const ContactParameters& parameters);
  void set_wall_contact_parameters(std::size_t wall, const WallContactParameters& parameters);
  void set_time_step(double time_step);  ///< [s]; 0 = automatic
  void set_threads(int threads);
  /// Switch SimulationSettings::reorder_particles; switching it on reorders at the next step.
  void set_reorder_particles(bool reorder);
  /// Switch SimulationSettings::pair_load_order (the neighbour list is rebuilt at the next step).
  void set_pair_load_order(PairLoadOrder order);
  void set_wall_motion(std::size_t wall, const WallMotion& motion);
  /// Velocity of a translating wall [m/s] (makes the wall translating if it was fixed).
  void set_wall_velocity(std::size_t wall, const Vec3& velocity);
  /// Angular velocity of a rotating wall [rad/s]; throws unless the wall rotates.
  void set_wall_angular_velocity(std::size_t wall, double angular_velocity);
  void set_particle_velocity(std::size_t particle, const Vec3& velocity, const Vec3& angular_velocity = {});
  void zero_velocities();  ///< all particle velocities and angular velocities to zero

  // ---- running -------------------------------------------------------------------------------
  void step();
  void run_steps(std::uint64_t steps);
  /// Step until time() >= t_end [s] (or the callback returns false); callback every `every` steps.
  void run_until(double t_end, const StepCallback& callback = {}, std::uint64_t every = 1);
  /// True when run_until(t_end) would take no step: the time is within a hundredth of a step of
  /// t_end or past it (the one stop rule of every loop that steps to a time).
  [[nodiscard]] bool reached(double t_end) const;

  // ---- state ---------------------------------------------------------------------------------
  [[nodiscard]] double time() const { return time_; }
  [[nodiscard]] std::uint64_t step_count() const { return step_count_; }
  /// Step in use [s]: the user step, or the automatic one (resolved from the current particles).
  [[nodiscard]] double time_step() const;
  /// Stability limit [s] of the current particles/walls/parameters (see time_step.hpp).
  [[nodiscard]] double stable_time_step() const;
  [[nodiscard]] std::size_t particle_count() const { return particles_.size(); }
  [[nodiscard]] std::size_t wall_count() const { return walls_.size(); }
  [[nodiscard]] std::span<const Vec3> positions() const { return particles_.position; }
  [[nodiscard]] std::span<const Vec3> velocities() const { return particles_.velocity; }
  [[nodiscard]] std::span<const Vec3> angular_velocities() const { return particles_.angular_velocity; }
  [[nodiscard]] std::span<const double> radii() const { return particles_.radius; }
  [[nodiscard]] std::span<const double> masses() const { return particles_.mass; }
  [[nodiscard]] const ParticleState& particles() const { return particles_; }
  [[nodiscard]] const Wall& wall(std::size_t index) const;
  /// Force [N] exerted by the particles on wall i during the last force evaluation.
  [[nodiscard]] Vec3 wall_force(std::size_t index) const { return wall(index).force; }
  /// Torque [N·m] of the particles on wall i about its torque axis (right-handed).
  [[nodiscard]] double wall_torque(std::size_t index) const { return wall(index).torque; }
  [[nodiscard]] const SimulationSettings& settings() const { return settings_; }
  [[nodiscard]] const std::vector<Material>& materials() const { return materials_; }

  // ---- diagnostics ---------------------------------------------------------------------------
  [[nodiscard]] double kinetic_energy() const;                  ///< translational + rotational [J]
  [[nodiscard]] double elastic_energy() const;                  ///< springs, last force evaluation [J]
  [[nodiscard]] double gravitational_potential_energy() const;  ///< -sum m g·x [J] (zero at the origin)
  [[nodiscard]] std::size_t contact_count() const;              ///< particle pairs touching
  [[nodiscard]] std::size_t wall_contact_count() const;         ///< particle–wall contacts
  [[nodiscard]] const NeighborList& neighbor_list() const { return neighbors_; }
  [[nodiscard]] double skin() const;  ///< Verlet skin in use [m]

 private:
  void invalidate_forces() { forces_valid_ = false; }
  /// Particles' compliances from the active law (contact_laws.hpp), from particle `first` on.
  void update_compliances(std::size_t first = 0);
  /// Drops the wall slots and their contact histories (walls added, particles removed).
  void drop_wall_slots();
  /// Rebuild the particle–wall slots, carrying contact state over from the old slots (particle
  /// new index s was old index order[s] when `order` is not empty).
  void find_wall_candidates(const std::vector<std::uint32_t>& order);
  /// Loads at the current state; `closing_kick` [s] > 0 applies the second Verlet half kick in the
  /// same pass; `moved` = largest displacement since the list build if known (< 0: compute it).
  void compute_forces(double dt, double closing_kick, double moved);
  /// compute_forces with the law type `Law` (chosen by with_contact_law).
  template <class Law>
  void evaluate_loads(double dt, double closing_kick);
  /// The state of law `Law`, converted from the current law's if the law changed (the
  /// tangential springs are kept) and restarted if the law asks (Law::restarts_history).
  template <class Law>
  ContactLawState<Law>& law_state();
  void ensure_neighbors(double moved);
  /// With settings_.reorder_particles: permute every per-particle array into slab order and
  /// return order[new] = old (empty when nothing moved). Pair arrays are rebuilt by the caller.
  std::vector<std::uint32_t> apply_spatial_order();
  /// New pair arrays after a rebuild, histories carried over from `old` (mapped through `order`;
  /// `old` is freed before the histories move).
  void rebuild_pair_arrays(NeighborList&& old, const std::vector<std::uint32_t>& order);
  double kick_and_drift(double dt);
  void reduce_diagnostics() const;       // wall loads, lazily, when one is asked for
  void reduce_pair_diagnostics() const;  // pair energy and contact count, lazily
  [[nodiscard]] double resolved_step() const;
  /// The law's automatic step and stability limit for the current particles, walls, parameters.
  [[nodiscard]] TimeStepEstimate step_estimate() const;

  SimulationSettings settings_;
  std::vector<Material> materials_{};
  ParticleState particles_;
  // mutable: the loads on the walls are reduced lazily from the per-contact arrays when asked for.
  mutable std::vector<Wall> walls_{};
  std::vector<Vec3> wall_displacement_at_build_{};   // wall translation when the list was built
  std::vector<double> wall_angle_at_build_{};        // wall rotation angle when the wall slots were built
  double slot_build_motion_ = 0.0;  // particle motion + wall translation since the list build, at the slots' build
  std::vector<std::uint8_t> wall_always_checked_{};  // per wall: moves in a way that changes distances
  NeighborList neighbors_;
  // Pair arrays aligned with neighbors_ pair indices (their histories: contact_state_).
  // own_row_first only: the second member's share, gathered after the rows.
  std::vector<Vec3> pair_force_, pair_torque_second_;
  std::vector<std::uint8_t> pair_touching_{};
  // ascending_first_member with threads > 1: per block of rows, the touching pairs crossing
  // into a later thread's chunk; and where the chunks split (learnt from their times).
  std::vector<CrossingBuffer> crossing_pair_loads_{};
  ChunkBalance chunk_balance_{};
  WallSlots wall_slots_{};  // particle–wall candidates and their last loads
  // The active law's contact histories (pairs and wall slots, of its history type) and wall laws.
  ContactLawStates contact_state_{};
  double time_ = 0.0;
  std::uint64_t step_count_ = 0;
  std::uint32_t next_id_ = 0;                 // id of the next particle added
  mutable double wall_elastic_energy_ = 0.0;  // wall slots' springs, summed with the wall loads
  mutable double elastic_energy_ = 0.0;       // walls' and pairs' springs
  mutable std::size_t contact_count_ = 0;
  mutable bool diagnostics_valid_ = false;       // wall loads
  mutable bool pair_diagnostics_valid_ = false;  // pair energy and contact count
  bool rebuild_requested_ = false;               // walls added or their motion changed
  bool forces_valid_ = false;
  mutable double cached_step_ = 0.0;
  mutable bool step_cache_valid_ = false;
  // The particle–wall laws in contact_state_ are rebuilt only when contact parameters or walls
  // change (not every step).
  bool wall_laws_valid_ = false;
};

}  // namespace demfit::dem_core
