// Time step of the LS-DYNA linear law (docs/spec.md 1), plain or with the effects library.
//
// For a pair, m*/k_n = (m_j a_i + m_i a_j)/(m_i + m_j) with a_i = m_i/k_i, a weighted mean of the
// per-particle a_i, so the stiffest pair is bounded by min_i a_i (exact for a pair of equal
// particles); a wall contact has m/k_n,w = a_i/SFP. omega = sqrt(k_n/m*).
// With rotation, the tangential spring acting on translation + rotation of two spheres has an
// effective mass 2m*/7: omega_t = sqrt(3.5 SHEARK) omega, and c_t = 2 TDAMP sqrt(m* k_t) is a
// damping ratio sqrt(3.5) TDAMP of that mode (same for walls with DAMP).
// Velocity Verlet with the damping force on the half-step velocity is stable for
//   dt < L(omega, zeta) = (2/omega)(sqrt(1+zeta^2) - zeta)   (damped_limit, time_step.hpp).
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
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "demfit/dem_core/contact_law_linear.hpp"

namespace demfit::dem_core {

TimeStepEstimate linear_time_step(const TimeStepInputs& inputs, double stiffness_scale) {
  const ParticleState& p = inputs.particles;
  const ContactParameters& c = inputs.contact;
  const double max_wall_damp = inputs.max_wall_damp;
  // a_i = m_i / k_i; the stiffest pair has m*/k_n >= min a_i, a wall contact a_i / SFP.
  double a_min = std::numeric_limits<double>::max();
  for (std::size_t i = 0; i < p.size(); ++i) a_min = std::min(a_min, p.mass[i] * p.normal_compliance[i]);
  if (inputs.max_wall_sfp > 1.0) a_min /= inputs.max_wall_sfp;
  const double omega = 1.0 / std::sqrt(a_min);  // two-body frequency sqrt(k_n/m*) of the tangential spring
  // Normal mode: the effects (plasticity, stiffness exponent) raise the tangent stiffness up to
  // stiffness_scale k_n (contact_effects.hpp); the damping ratio is kept (conservative: c_n
  // stays 2 NDAMP sqrt(m* k_n), a smaller fraction of the stiffer mode's critical damping).
  const double omega_n = stiffness_scale == 1.0 ? omega : omega * std::sqrt(stiffness_scale);
  const bool rotation = c.rotation_enabled();
  // Tangential mode of two spheres with rotation: effective mass 2m*/7, so omega_t =
  // sqrt(3.5 SHEARK) omega and the damping ratio of c_t = 2 TDAMP sqrt(m* k_t) is sqrt(3.5) TDAMP.
  const double omega_t = omega * std::sqrt(3.5 * c.sheark);
  const double zeta_n = std::max(c.ndamp, max_wall_damp);
  const double zeta_t = std::sqrt(3.5) * std::max(c.tdamp, max_wall_damp);
  TimeStepEstimate e;
  e.stable_limit = damped_limit(omega_n, zeta_n);
  if (rotation && omega_t > 0.0) e.stable_limit = std::min(e.stable_limit, damped_limit(omega_t, zeta_t));
  // Automatic: LS-DYNA's factor * 2 pi sqrt(m*/k_n), but also 0.9 x the bound of a particle
  // loaded from both sides (chains, packings, wall + neighbour): frequency and, with damping
  // proportional to stiffness, damping ratio both sqrt(2) times the two-body values.
  const double root2 = std::sqrt(2.0);
  double bound = damped_limit(root2 * omega_n, root2 * zeta_n);
  if (rotation && omega_t > 0.0) {
    bound = std::min(bound, damped_limit(root2 * omega_t, root2 * zeta_t));
    // Rotational "gear" mode of a packing: a sphere with z sticking contacts whose neighbours
    // counter-rotate: omega_g^2 = 2.5 z SHEARK omega^2, damping ratio sqrt(2.5 z) TDAMP.
    constexpr double coordination = 6.0;
    const double omega_g = omega * std::sqrt(2.5 * coordination * c.sheark);
    const double zeta_g = std::sqrt(2.5 * coordination) * std::max(c.tdamp, max_wall_damp);
    bound = std::min(bound, damped_limit(omega_g, zeta_g));
  }
  e.automatic =
      std::min(inputs.factor * 2.0 * std::numbers::pi / std::max(omega_n, rotation ? omega_t : 0.0), 0.9 * bound);
  return e;
}

}  // namespace demfit::dem_core
