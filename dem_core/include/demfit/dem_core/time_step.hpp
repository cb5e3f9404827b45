#pragma once
// Time-step rules and closed-form contact times (SPEC 1).
//
// Linear law. For a pair, m*/k_n = (m_j a_i + m_i a_j)/(m_i + m_j) with a_i = m_i/k_i, a weighted
// mean of the per-particle a_i, so the stiffest pair is bounded by min_i a_i (exact for a pair of
// equal particles); a wall contact has m/k_n,w = a_i/SFP. omega = sqrt(k_n/m*).
// With rotation, the tangential spring acting on translation + rotation of two spheres has an
// effective mass 2m*/7: omega_t = sqrt(3.5 SHEARK) omega, and c_t = 2 TDAMP sqrt(m* k_t) is a
// damping ratio sqrt(3.5) TDAMP of that mode (same for walls with DAMP).
// Velocity Verlet with the damping force on the half-step velocity is stable for
//   dt < L(omega, zeta) = (2/omega)(sqrt(1+zeta^2) - zeta).
//   stability limit (user steps above it are refused) = two-body bound, min over the normal mode
//                   (omega, max(NDAMP, wall DAMP)) and, with rotation, the tangential mode.
//   automatic step  = min(factor * 2 pi / omega            (factor 0.15: LS-DYNA's choice),
//                         0.9 * the same bounds for a particle loaded from both sides (chains,
//                         packings, wall + neighbour): frequency and damping ratio sqrt(2) x).
//                         With rotation also the "gear" mode of a packing: a sphere with z = 6
//                         sticking contacts whose neighbours counter-rotate, omega_g^2 =
//                         2.5 z SHEARK omega^2, damping ratio sqrt(2.5 z) TDAMP.
// The extra bounds matter mainly with damping. Measured: a 5-sphere column with NDAMP = 0.5, a
// sphere on a wall with DAMP = 0.5 and rotation, and a settling bed with TDAMP = 0.5 and FRICS
// 0.3-0.8 (it kept creeping at KE ~ 1e-3 m g R per particle) are unstable at 0.15 * 2 pi / omega;
// with these bounds the bed comes to rest. Cost: with SHEARK = 2/7 and TDAMP = 0.5 the automatic
// step is ~0.22/omega instead of 0.94/omega.
// Effects library (contact_effects.hpp): plasticity and the stiffness exponent stiffen the normal
// spring; the normal-mode bounds use omega_n = omega sqrt(normal_stiffness_scale), the tangent
// stiffness at a planned largest overlap of 5 % of the smaller radius (n (delta/d_ref)^(n-1) with
// delta/d_ref = 10) times the unloading ratio. Beds loaded beyond 5 % overlap need a user step.
// Hertz–Mindlin. Rayleigh time T_R = pi R sqrt(rho/G)/(0.1631 nu + 0.8766) of the smallest
// particle; automatic step = 0.2 T_R (common LIGGGHTS practice), stability limit = T_R.
#include <vector>

#include "demfit/dem_core/parameters.hpp"
#include "demfit/dem_core/particle_state.hpp"

namespace demfit::dem_core {

struct TimeStepEstimate {
  double automatic = 0.0;     ///< [s]
  double stable_limit = 0.0;  ///< [s]
};

/// Steps for the given particles; `max_wall_sfp` = largest SFP of the walls (0 if no walls),
/// `max_wall_damp` = largest wall DAMP. Throws std::runtime_error if there are no particles.
TimeStepEstimate estimate_time_step(ContactLawKind law, const ParticleState& particles,
                                    const std::vector<Material>& materials, const ContactParameters& contact,
                                    double max_wall_sfp, double max_wall_damp, double factor);

/// Linear spring-dashpot: contact duration pi/omega_d, omega_d = sqrt(k/m*) sqrt(1 - zeta^2) [s].
double linear_contact_duration(double effective_mass, double normal_stiffness, double damping_ratio);
/// Linear spring-dashpot restitution e = exp(-pi zeta / sqrt(1 - zeta^2)).
double linear_restitution(double damping_ratio);
/// Hertz elastic impact duration 2.87 (m*^2/(R* E*^2 v))^(1/5) [s] at approach speed v [m/s].
double hertz_contact_duration(double effective_mass, double effective_radius, double effective_youngs_modulus,
                              double approach_speed);
/// Young's modulus from bulk modulus and Poisson ratio: E = 3K(1 - 2 nu) [Pa].
double youngs_modulus(const Material& material);

}  // namespace demfit::dem_core
