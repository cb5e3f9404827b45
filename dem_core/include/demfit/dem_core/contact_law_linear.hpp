#pragma once
// LS-DYNA linear spring-dashpot law (*CONTROL_DISCRETE_ELEMENT, SPEC 1), composed of a normal
// part, the Coulomb tangential spring and constant-torque rolling resistance. The law is a
// template on its normal part: LinearNormal (the plain LS-DYNA law) or EffectsNormal
// (plasticity, cohesion, nonlinear stiffness; contact_effects.hpp). The simulation picks the
// plain one whenever every effect is off, so the base law pays nothing for the effects.
#include <cmath>

#include "demfit/dem_core/contact_effects.hpp"
#include "demfit/dem_core/contact_law_parts.hpp"
#include "demfit/dem_core/parameters.hpp"

namespace demfit::dem_core {

/// Normal spring-dashpot: k_n = 1/(sum of compliances) (springs in series, k_i = NORMK K_i R_i),
/// c_n = 2 NDAMP sqrt(m* k_n). The elastic part k_n delta is never attractive; the viscous part
/// is not clipped, so restitution is exactly e = exp(-pi zeta/sqrt(1-zeta^2)) (SPEC 1).
struct LinearNormal {
  static constexpr bool tracks_max_overlap = false;
  double damping_ratio = 0.0;  ///< NDAMP (pairs) or wall DAMP [-]

  struct Result {
    double force;           ///< repulsive magnitude along -normal on i [N]
    double friction_load;   ///< load of the Coulomb limit and rolling torque (= force) [N]
    double stiffness;       ///< k_n [N/m]
    double energy;          ///< 1/2 k_n delta^2 [J]
    double critical_scale;  ///< sqrt(m* k_n) [kg/s], reused by the tangential part
  };
  /// `max_overlap` is unused (same interface as EffectsNormal).
  Result evaluate(const ContactGeometry& g, double* /*max_overlap*/) const {
    const double k = 1.0 / g.normal_compliance;
    const double root = std::sqrt(g.effective_mass * k);
    const double approach_speed = dot(g.contact_velocity, g.normal);
    const double force = k * g.overlap + 2.0 * damping_ratio * root * approach_speed;
    return {force, force, k, 0.5 * k * g.overlap * g.overlap, root};
  }
};

template <class Normal>
struct LinearLaw {
  Normal normal{};
  double shear_ratio = 2.0 / 7.0;       ///< SHEARK: k_t = SHEARK k_n
  double tangential_damping_ratio = 0;  ///< TDAMP (pairs) or wall DAMP: c_t = 2 TDAMP sqrt(m* k_t)
  CoulombTangentialSpring tangential{};
  ConstantTorqueRolling rolling{};

  /// True when the loops must keep the contact's largest overlap and pass it as `max_overlap`.
  static constexpr bool tracks_max_overlap = Normal::tracks_max_overlap;

  ContactForce force(const ContactGeometry& g, ContactHistory& history, double dt,
                     double* max_overlap = nullptr) const {
    const typename Normal::Result n = normal.evaluate(g, max_overlap);
    ContactForce out;
    out.elastic_energy = n.energy;
    const double k_t = shear_ratio * n.stiffness;
    // c_t = 2 TDAMP sqrt(m* k_t) = 2 TDAMP sqrt(SHEARK) sqrt(m* k_n)
    const double c_t = 2.0 * tangential_damping_ratio * std::sqrt(shear_ratio) * n.critical_scale;
    out.tangential_force = tangential.evaluate(g, k_t, c_t, n.friction_load, history, dt, out.elastic_energy);
    out.force = out.tangential_force - n.force * g.normal;
    out.rolling_torque = rolling.evaluate(g, n.friction_load, dt);
    return out;
  }
};

/// The plain LS-DYNA law (SPEC 1) and the same law with the effects library.
using LsDynaLinearLaw = LinearLaw<LinearNormal>;
using LsDynaEffectsLaw = LinearLaw<EffectsNormal>;

/// Particle–particle law from the global parameters.
inline LsDynaLinearLaw make_linear_pair_law(const ContactParameters& p) {
  LsDynaLinearLaw law;
  law.normal.damping_ratio = p.ndamp;
  law.shear_ratio = p.sheark;
  law.tangential_damping_ratio = p.tdamp;
  law.tangential = {p.frics, p.dynamic_friction(), p.dc};
  law.rolling.coefficient = p.rotation_enabled() ? p.fricr : 0.0;
  return law;
}

/// Particle–wall law: wall FRICS is sliding friction, wall FRICD is ROLLING friction, DAMP damps
/// the normal and the tangential spring; SHEARK comes from the particle parameters.
inline LsDynaLinearLaw make_linear_wall_law(const ContactParameters& p, const WallContactParameters& w) {
  LsDynaLinearLaw law;
  law.normal.damping_ratio = w.damp;
  law.shear_ratio = p.sheark;
  law.tangential_damping_ratio = w.damp;
  law.tangential = {w.frics, w.frics, 0.0};
  law.rolling.coefficient = p.rotation_enabled() ? w.fricd : 0.0;
  return law;
}

/// Copies the damping, tangential and rolling parts of a plain law and adds the effects of `p`.
inline LsDynaEffectsLaw with_effects(const LsDynaLinearLaw& plain, const ContactParameters& p) {
  LsDynaEffectsLaw law;
  law.normal.damping_ratio = plain.normal.damping_ratio;
  law.normal.unloading_ratio = p.unloading_stiffness_ratio;
  law.normal.cohesion_per_radius = cohesion_force_per_radius(p.surface_energy);
  law.normal.exponent = p.stiffness_exponent;
  law.shear_ratio = plain.shear_ratio;
  law.tangential_damping_ratio = plain.tangential_damping_ratio;
  law.tangential = plain.tangential;
  law.rolling = plain.rolling;
  return law;
}

/// Pair and wall laws with the effects (the same effects act on walls, with R* = R).
inline LsDynaEffectsLaw make_effects_pair_law(const ContactParameters& p) {
  return with_effects(make_linear_pair_law(p), p);
}
inline LsDynaEffectsLaw make_effects_wall_law(const ContactParameters& p, const WallContactParameters& w) {
  return with_effects(make_linear_wall_law(p, w), p);
}

}  // namespace demfit::dem_core
