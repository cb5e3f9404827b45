#pragma once
// What a contact law sees of one contact, computed once per pair (or particle–wall pair) by the
// loops, and the history a law may carry from step to step.
#include <cstdint>
#include <vector>

#include "demfit/dem_core/vec3.hpp"

namespace demfit::dem_core {

/// Geometry and kinematics of one contact between body i (a particle) and body j (a particle or
/// a wall). All vectors in the global frame.
struct ContactGeometry {
  Vec3 normal{};                     ///< unit normal pointing from i towards j
  double overlap = 0.0;              ///< delta = R_i + R_j - |x_j - x_i| (> 0 in contact) [m]
  Vec3 contact_velocity{};           ///< velocity of i relative to j at the contact point [m/s]
  Vec3 relative_angular_velocity{};  ///< omega_i - omega_j [rad/s] (wall: omega_i - omega_wall)
  double effective_mass = 0.0;       ///< m* = m_i m_j/(m_i+m_j); wall: m_i [kg]
  double effective_radius = 0.0;     ///< R* = R_i R_j/(R_i+R_j); wall: R_i [m]
  double normal_compliance = 0.0;    ///< sum of both bodies' normal compliances (see ParticleState)
  double shear_compliance = 0.0;     ///< Hertz–Mindlin: sum of (2-nu)/G; wall adds 0 (rigid)
  double inverse_inertia_sum = 0.0;  ///< 1/I_i + 1/I_j (wall: 1/I_i), for the rolling limiter
  double first_radius = 0.0;         ///< R_i [m] (the SJKR cohesion's intersection circle)
  double second_radius = 0.0;        ///< R_j [m]; 0 for a wall (a plane at the contact point)
};

/// Per-contact memory of the plain laws (LS-DYNA linear, Hertz–Mindlin), carried across steps
/// and across neighbour-list rebuilds; reset (set to default) when the contact ends. A law with
/// more memory declares its own history type that starts with this field (contact_laws.hpp);
/// this one stays 24 bytes per contact (memory per particle).
struct ContactHistory {
  Vec3 tangential_displacement{};  ///< incremental tangential spring elongation xi_t [m]
};
static_assert(sizeof(ContactHistory) == 24, "the plain laws' history is 24 bytes per contact");

/// A particle's own "half" of a contact's springs, from the physical inputs (each law's
/// `particle_compliance`); a contact sums both bodies' halves (springs in series).
struct ParticleCompliance {
  double normal = 0.0;  ///< linear law: 1/(NORMK K R) [m/N]; Hertz: (1-nu^2)/E [1/Pa]
  double shear = 0.0;   ///< Hertz: (2-nu)/G [1/Pa]; 0 for the linear law
};

/// Loads a law returns for body i (body j receives the opposite force; the loop turns the
/// tangential force into torques with the branch vectors of both bodies).
struct ContactForce {
  Vec3 force{};                 ///< total force on i [N] (normal + tangential)
  Vec3 tangential_force{};      ///< tangential part of `force`, acting at the contact point [N]
  Vec3 rolling_torque{};        ///< rolling-resistance torque on i [N·m] (j receives -rolling_torque)
  double elastic_energy = 0.0;  ///< energy stored in the normal and tangential springs [J]
};

/// What one touching pair exerts: the force on the first member [N] (the second receives
/// -force) and each member's torque about its own centre [N·m] (the loops' per-pair result).
struct PairLoads {
  Vec3 force{};
  Vec3 torque_first{};
  Vec3 torque_second{};
};

/// A touching pair whose members lie in different threads' chunks, computed before the chunks'
/// rows (PairLoadOrder::ascending_first_member, src/contact_loops_streamed.hpp).
struct CrossingPairLoads {
  std::uint32_t pair = 0;    ///< index in the half list
  std::uint32_t second = 0;  ///< second member (in a later chunk than the first)
  PairLoads loads{};
};

/// One block of rows' crossing pairs. Its own cache line: the threads fill neighbouring blocks at
/// the same time, and vectors side by side would pass their shared line back and forth on every
/// append.
struct alignas(64) CrossingBuffer {
  std::vector<CrossingPairLoads> pairs;
};

}  // namespace demfit::dem_core
