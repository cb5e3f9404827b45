#pragma once
// Effects library: the normal part of the LS-DYNA linear law with three optional
// physical effects the base model lacks. Each is off at its default (ContactParameters):
//
// 1. Plasticity, Walton & Braun (1986, J. Rheol. 30:949) hysteretic spring. Loading on the
//    virgin curve with k1 = k_n; unloading (and reloading below the largest overlap delta_max)
//    with k2 = ratio k1:  F = k2 (delta - delta0), delta0 = delta_max (1 - k1/k2), never
//    attractive (F = 0 for delta <= delta0). Reloading meets the loading line at delta_max.
//    The dissipated energy gives an undamped head-on restitution e = sqrt(k1/k2).
// 2. Cohesion: a constant JKR-like pull-off force F_c = 1.5 pi gamma R* (Johnson, Kendall &
//    Roberts 1971; R* = R_i R_j/(R_i + R_j), walls R* = R), attractive along the normal, acting
//    only while the bodies overlap (delta > 0). The contact therefore breaks at zero overlap:
//    pulling a resting pair apart needs F_c, and there is no neck of attraction beyond contact
//    (the pair loop only sees overlapping pairs; a range > 0 would need a larger search radius).
//    The Coulomb limit and the rolling torque use the REPULSIVE part (elastic + viscous) of the
//    normal force: cohesion presses the surfaces together, so it raises the friction a contact
//    can carry (as in LIGGGHTS' simplified JKR model), instead of cancelling it.
// 3. Nonlinear stiffness: F_el = k_n d_ref (delta/d_ref)^n, d_ref = 0.01 R*. At delta = d_ref
//    (1 % of the effective radius, a typical overlap of the LS-DYNA cases) the force and the
//    secant stiffness equal the linear law's, so the exponent changes the SHAPE of the
//    force-overlap curve (n = 1.5: Hertzian delta^(3/2)) while NORMK keeps setting its scale.
//    Elastic energy k_n d_ref^2/(n+1) (delta/d_ref)^(n+1) (exact integral of the force).
//
// Combination of 1 and 3: unloading follows the loading law's shape stiffened by `ratio`,
// F = F_L(delta_max) ((delta - delta0)/(delta_max - delta0))^n, delta_max - delta0 = delta_max/ratio.
// For n = 1 this is exactly the Walton–Braun line above; for any n the recovered energy is
// 1/ratio of the absorbed one, so e = 1/sqrt(ratio) still holds.
// Damping and the tangential spring keep using the reference k_n (NDAMP, TDAMP, SHEARK keep
// their LS-DYNA meaning: fractions of critical, ratio to k_n at the reference stiffness).
#include <algorithm>
#include <cmath>
#include <numbers>

#include "demfit/dem_core/contact_geometry.hpp"
#include "demfit/dem_core/parameters.hpp"

namespace demfit::dem_core {

/// Reference overlap of the nonlinear stiffness as a fraction of R*: d_ref = 0.01 R*.
inline constexpr double kStiffnessReferenceOverlap = 0.01;
/// Largest overlap the time step plans for, as a fraction of the smaller radius (5 %); for a
/// pair of equal spheres R* = R/2, so delta/d_ref = 0.05 R / (0.01 R/2) = 10 (walls: 5).
inline constexpr double kPlannedOverlapOverReference = 10.0;

/// JKR pull-off force per effective radius, 1.5 pi gamma [N/m].
inline double cohesion_force_per_radius(double surface_energy) { return 1.5 * std::numbers::pi * surface_energy; }

/// Factor by which the effects can raise the normal tangent stiffness above k_n, for the time
/// step: the loading tangent n (delta/d_ref)^(n-1) at the planned overlap (10 d_ref), times the
/// unloading ratio (the unloading tangent is `ratio` times the loading one). 1 when off.
inline double normal_stiffness_scale(const ContactParameters& p) {
  double scale = p.unloading_stiffness_ratio;
  if (p.stiffness_exponent != 1.0)
    scale *= p.stiffness_exponent * std::pow(kPlannedOverlapOverReference, p.stiffness_exponent - 1.0);
  return scale;
}

/// History of a contact under the effects law: the tangential spring and, for plasticity, the
/// largest overlap so far. Reset with the rest of the history when the contact ends, carried
/// with it across neighbour-list rebuilds (32 bytes per contact, only while an effect is on).
struct EffectsHistory {
  Vec3 tangential_displacement{};  ///< incremental tangential spring elongation xi_t [m]
  double max_overlap = 0.0;        ///< largest overlap delta_max [m]; 0 for a new contact
};

/// Normal part with the effects; same interface as LinearNormal (contact_law_linear.hpp).
struct EffectsNormal {
  using History = EffectsHistory;
  double damping_ratio = 0.0;        ///< NDAMP (pairs) or wall DAMP [-]
  double unloading_ratio = 1.0;      ///< k2/k1 >= 1
  double cohesion_per_radius = 0.0;  ///< 1.5 pi gamma [N/m]
  double exponent = 1.0;             ///< n in [1, 2]

  /// The effects of `p` with the given damping ratio (NDAMP for pairs, DAMP for walls).
  static EffectsNormal from(const ContactParameters& p, double damping) {
    EffectsNormal normal;
    normal.damping_ratio = damping;
    normal.unloading_ratio = p.unloading_stiffness_ratio;
    normal.cohesion_per_radius = cohesion_force_per_radius(p.surface_energy);
    normal.exponent = p.stiffness_exponent;
    return normal;
  }
  /// Stiffening of the normal mode for the time step (normal_stiffness_scale).
  static double stiffness_scale(const ContactParameters& p) { return normal_stiffness_scale(p); }
  /// The largest overlaps are remembered only while plasticity is on: switching it on (between
  /// two force evaluations) starts every contact's memory from zero.
  static bool restarts_history(const ContactParameters& before, const ContactParameters& after) {
    return before.unloading_stiffness_ratio == 1.0 && after.unloading_stiffness_ratio != 1.0;
  }

  struct Result {
    double force;           ///< net magnitude along -normal on i (repulsive > 0), cohesion included [N]
    double friction_load;   ///< repulsive part (elastic + viscous), for Coulomb and rolling [N]
    double stiffness;       ///< reference k_n [N/m] (tangential spring, damping)
    double energy;          ///< recoverable elastic energy of the normal spring [J]
    double critical_scale;  ///< sqrt(m* k_n) [kg/s]
  };

  /// Normal load of a contact whose history is `history` (its largest overlap is updated).
  Result evaluate(const ContactGeometry& g, History& history) const { return evaluate(g, &history.max_overlap); }

  /// `max_overlap` points to the contact's largest overlap so far [m] (0 for a new contact); it
  /// is read and updated only with plasticity on (unloading_ratio != 1); null = no memory (every
  /// step is virgin loading).
  Result evaluate(const ContactGeometry& g, double* max_overlap) const {
    const double k = 1.0 / g.normal_compliance;
    const double root = std::sqrt(g.effective_mass * k);
    const double delta = g.overlap;
    double elastic = 0.0, energy = 0.0;
    if (unloading_ratio == 1.0) {
      elastic = loading_force(k, delta, g.effective_radius);
      energy = elastic * delta / (exponent + 1.0);  // = k d^2/2 for n = 1
    } else {
      // Without a memory (null) every step is treated as virgin loading.
      const double delta_max = max_overlap != nullptr ? std::max(*max_overlap, delta) : delta;
      if (max_overlap != nullptr) *max_overlap = delta_max;
      const double span = delta_max / unloading_ratio;    // delta_max - delta0
      const double stretch = delta - (delta_max - span);  // delta - delta0
      if (stretch > 0.0) {
        // k2 (delta - delta0) for n = 1; the loading shape scaled to the unloading span otherwise.
        elastic = exponent == 1.0
                      ? unloading_ratio * k * stretch
                      : loading_force(k, delta_max, g.effective_radius) * std::pow(stretch / span, exponent);
        energy = elastic * stretch / (exponent + 1.0);
      }
    }
    const double viscous = 2.0 * damping_ratio * root * dot(g.contact_velocity, g.normal);
    const double repulsive = elastic + viscous;
    return {repulsive - cohesion_per_radius * g.effective_radius, repulsive, k, energy, root};
  }

 private:
  /// Loading (virgin) curve F_L(delta) = k d_ref (delta/d_ref)^n, = k delta for n = 1.
  double loading_force(double k, double delta, double effective_radius) const {
    if (exponent == 1.0) return k * delta;
    const double reference = kStiffnessReferenceOverlap * effective_radius;
    return k * reference * std::pow(delta / reference, exponent);
  }
};

}  // namespace demfit::dem_core
