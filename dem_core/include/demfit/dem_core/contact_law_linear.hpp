#pragma once
// LS-DYNA linear spring-dashpot law (*CONTROL_DISCRETE_ELEMENT, docs/spec.md 1), composed of a normal
// part, the Coulomb tangential spring and constant-torque rolling resistance. The law is a
// template on its normal part: LinearNormal (the plain LS-DYNA law) or EffectsNormal
// (plasticity, cohesion, nonlinear stiffness; contact_effects.hpp). The simulation picks the
// plain one whenever every effect is off (contact_laws.hpp), so the base law pays nothing for
// the effects. The law owns its physics: the particle springs from NORMK and the bulk modulus,
// its time step, and its per-contact history (the normal part's `History`).
#include <cmath>

#include "demfit/dem_core/contact_effects.hpp"
#include "demfit/dem_core/contact_law_parts.hpp"
#include "demfit/dem_core/parameters.hpp"
#include "demfit/dem_core/time_step.hpp"

namespace demfit::dem_core {

/// Normal spring-dashpot: k_n = 1/(sum of compliances) (springs in series, k_i = NORMK K_i R_i),
/// c_n = 2 NDAMP sqrt(m* k_n). The elastic part k_n delta is never attractive; the viscous part
/// is not clipped, so restitution is exactly e = exp(-pi zeta/sqrt(1-zeta^2)) (docs/spec.md 1).
struct LinearNormal {
  using History = ContactHistory;  ///< no memory beyond the tangential spring
  double damping_ratio = 0.0;      ///< NDAMP (pairs) or wall DAMP [-]

  static LinearNormal from(const ContactParameters& /*p*/, double damping) { return {damping}; }
  static double stiffness_scale(const ContactParameters& /*p*/) { return 1.0; }
  static bool restarts_history(const ContactParameters& /*before*/, const ContactParameters& /*after*/) {
    return false;
  }

  struct Result {
    double force;           ///< repulsive magnitude along -normal on i [N]
    double friction_load;   ///< load of the Coulomb limit and rolling torque (= force) [N]
    double stiffness;       ///< k_n [N/m]
    double energy;          ///< 1/2 k_n delta^2 [J]
    double critical_scale;  ///< sqrt(m* k_n) [kg/s], reused by the tangential part
  };
  Result evaluate(const ContactGeometry& g, const History& /*history*/) const {
    const double k = 1.0 / g.normal_compliance;
    const double root = std::sqrt(g.effective_mass * k);
    const double approach_speed = dot(g.contact_velocity, g.normal);
    const double force = k * g.overlap + 2.0 * damping_ratio * root * approach_speed;
    return {force, force, k, 0.5 * k * g.overlap * g.overlap, root};
  }
};

/// Automatic step and stability limit of the linear law; `stiffness_scale` >= 1 is the normal
/// part's stiffening (1 for the plain law). Derivation in src/contact_law_linear.cpp.
TimeStepEstimate linear_time_step(const TimeStepInputs& inputs, double stiffness_scale);

template <class Normal>
struct LinearLaw {
  using History = typename Normal::History;
  Normal normal{};
  double shear_ratio = 2.0 / 7.0;       ///< SHEARK: k_t = SHEARK k_n
  double tangential_damping_ratio = 0;  ///< TDAMP (pairs) or wall DAMP: c_t = 2 TDAMP sqrt(m* k_t)
  CoulombTangentialSpring tangential{};
  ConstantTorqueRolling rolling{};

  /// Particle–particle law from the global parameters.
  static LinearLaw for_pairs(const ContactParameters& p) {
    LinearLaw law;
    law.normal = Normal::from(p, p.ndamp);
    law.shear_ratio = p.sheark;
    law.tangential_damping_ratio = p.tdamp;
    law.tangential = {p.frics, p.dynamic_friction(), p.dc};
    law.rolling.coefficient = p.rotation_enabled() ? p.fricr : 0.0;
    return law;
  }
  /// Particle–wall law: wall FRICS is sliding friction, wall FRICD is ROLLING friction, DAMP
  /// damps the normal and the tangential spring; SHEARK (and the effects) come from the particle
  /// parameters (the effects act on walls with R* = R). SFP scales the spring in the loop.
  static LinearLaw for_wall(const ContactParameters& p, const WallContactParameters& w) {
    LinearLaw law;
    law.normal = Normal::from(p, w.damp);
    law.shear_ratio = p.sheark;
    law.tangential_damping_ratio = w.damp;
    law.tangential = {w.frics, w.frics, 0.0};
    law.rolling.coefficient = p.rotation_enabled() ? w.fricd : 0.0;
    return law;
  }
  /// k_i = NORMK K_i R_i (docs/spec.md 1); the particle's compliance is its inverse [m/N].
  static ParticleCompliance particle_compliance(const Material& m, double radius, const ContactParameters& p) {
    return {1.0 / (p.normk * m.bulk_modulus * radius), 0.0};
  }
  static TimeStepEstimate time_step(const TimeStepInputs& inputs) {
    return linear_time_step(inputs, Normal::stiffness_scale(inputs.contact));
  }
  static bool restarts_history(const ContactParameters& before, const ContactParameters& after) {
    return Normal::restarts_history(before, after);
  }

  ContactForce force(const ContactGeometry& g, History& history, double dt) const {
    const typename Normal::Result n = normal.evaluate(g, history);
    ContactForce out;
    out.elastic_energy = n.energy;
    const double k_t = shear_ratio * n.stiffness;
    // c_t = 2 TDAMP sqrt(m* k_t) = 2 TDAMP sqrt(SHEARK) sqrt(m* k_n)
    const double c_t = 2.0 * tangential_damping_ratio * std::sqrt(shear_ratio) * n.critical_scale;
    out.tangential_force =
        tangential.evaluate(g, k_t, c_t, n.friction_load, history.tangential_displacement, dt, out.elastic_energy);
    out.force = out.tangential_force - n.force * g.normal;
    out.rolling_torque = rolling.evaluate(g, n.friction_load, dt);
    return out;
  }
  /// The springs' energy [J] as `force` left them (same terms, same order: bit-identical).
  double elastic_energy(const ContactGeometry& g, const History& history) const {
    History copy = history;  // the effects' normal part updates its memory when evaluated
    const typename Normal::Result n = normal.evaluate(g, copy);
    return n.energy + 0.5 * (shear_ratio * n.stiffness) * norm2(history.tangential_displacement);
  }
};

/// The plain LS-DYNA law (docs/spec.md 1) and the same law with the effects library.
using LsDynaLinearLaw = LinearLaw<LinearNormal>;
using LsDynaEffectsLaw = LinearLaw<EffectsNormal>;

}  // namespace demfit::dem_core
