#pragma once
// Hertz–Mindlin (no-slip) law with restitution-based damping (the form used by LIGGGHTS'
// hertz model; Tsuji et al. 1992 / Antypov & Elliott 2011):
//   a = sqrt(R* delta), S_n = 2 E* a, F_n = 4/3 E* a delta + c_n v_n,
//   S_t = 8 G* a,       F_t = -S_t xi - c_t v_t (Coulomb-limited),
//   c = -2 sqrt(5/6) beta sqrt(S m*), beta = ln e / sqrt(ln^2 e + pi^2).
// E* = 1/sum((1-nu^2)/E), G* = 1/sum((2-nu)/G) come in through ContactGeometry's compliances,
// summed from each particle's `particle_compliance` (E, nu of its material).
// Options (ContactParameters): SJKR cohesion F_coh = k_c A (hertz_cohesion.hpp; off at k_c = 0,
// then the force is bit-identical to the law without it) and the rolling resistance, a template
// argument because epsd2 keeps a torque per contact: cdt (ConstantTorqueRolling, the law's
// default) or epsd2 (ElasticPlasticRolling, contact_law_parts.hpp).
#include <cmath>
#include <numbers>
#include <type_traits>

#include "demfit/dem_core/contact_law_parts.hpp"
#include "demfit/dem_core/hertz_cohesion.hpp"
#include "demfit/dem_core/parameters.hpp"
#include "demfit/dem_core/time_step.hpp"

namespace demfit::dem_core {

/// beta(e) of the restitution-based damping; 0 for e = 1 (no damping).
inline double hertz_damping_beta(double restitution) {
  if (restitution >= 1.0) return 0.0;
  const double log_e = std::log(restitution);
  return log_e / std::sqrt(log_e * log_e + std::numbers::pi * std::numbers::pi);
}

struct HertzNormal {
  double beta = 0.0;  ///< from hertz_damping_beta(e), <= 0

  struct Result {
    double force;           ///< repulsive magnitude along -normal on i [N]
    double contact_radius;  ///< a = sqrt(R* delta) [m]
    double energy;          ///< 8/15 E* sqrt(R*) delta^{5/2} [J]
  };
  [[gnu::always_inline]] Result evaluate(const ContactGeometry& g) const {
    const double e_star = 1.0 / g.normal_compliance;
    const double a = std::sqrt(g.effective_radius * g.overlap);
    const double elastic = (4.0 / 3.0) * e_star * a * g.overlap;
    const double s_n = 2.0 * e_star * a;
    const double c_n = -2.0 * std::sqrt(5.0 / 6.0) * beta * std::sqrt(s_n * g.effective_mass);
    return {elastic + c_n * dot(g.contact_velocity, g.normal), a, 0.4 * elastic * g.overlap};
  }
};

/// Automatic step and stability limit of the Hertz law (src/contact_law_hertz.cpp); throws
/// std::runtime_error when the cohesion exceeds hertz_cohesion_limit for a pair of the particles'
/// materials or for one of them on the softest wall.
TimeStepEstimate hertz_time_step(const TimeStepInputs& inputs);

template <class Rolling>
struct HertzLaw {
  static constexpr bool kRollingSpring = std::is_same_v<Rolling, ElasticPlasticRolling>;
  /// cdt: no memory beyond the tangential spring; epsd2: the rolling torque too.
  using History = std::conditional_t<kRollingSpring, RollingSpringHistory, ContactHistory>;
  HertzNormal normal{};
  CoulombTangentialSpring tangential{};
  Rolling rolling{};
  SjkrCohesion cohesion{};
  /// Compliances of an elastic wall (WallContactParameters::hertz_*_compliance), added to the
  /// particle's; 0 for pairs (both particles are already in the geometry) and rigid walls, and
  /// adding 0 is exact, so those contacts compute bit-identically to before.
  double body_normal_compliance = 0.0;  ///< [1/Pa]
  double body_shear_compliance = 0.0;   ///< [1/Pa]

  static HertzLaw for_pairs(const ContactParameters& p) {
    HertzLaw law;
    law.normal.beta = hertz_damping_beta(p.restitution);
    law.tangential = {p.frics, p.dynamic_friction(), p.dc};
    law.rolling.coefficient = p.rotation_enabled() ? p.fricr : 0.0;
    law.cohesion = {p.cohesion_energy_density, p.cohesion_model};
    return law;
  }
  /// Wall: rigid body unless the wall has a Young's modulus (then its compliances are added, a
  /// second elastic body); same restitution and cohesion as the pairs, wall FRICS sliding, wall
  /// FRICD rolling. SFP scales the particle's normal compliance (in the loop) as it scales the
  /// linear wall spring.
  static HertzLaw for_wall(const ContactParameters& p, const WallContactParameters& w) {
    HertzLaw law;
    law.normal.beta = hertz_damping_beta(p.restitution);
    law.tangential = {w.frics, w.frics, 0.0};
    law.rolling.coefficient = p.rotation_enabled() ? w.fricd : 0.0;
    law.cohesion = {p.cohesion_energy_density, p.cohesion_model};
    law.body_normal_compliance = w.hertz_normal_compliance();
    law.body_shear_compliance = w.hertz_shear_compliance();
    return law;
  }
  /// The particle's halves of 1/E* and 1/G*: (1 - nu^2)/E and (2 - nu)/G, E = 3K(1 - 2 nu),
  /// G = E/(2(1 + nu)) [1/Pa] (the radius enters through a = sqrt(R* delta)).
  static ParticleCompliance particle_compliance(const Material& m, double /*radius*/, const ContactParameters& /*p*/) {
    const double e = youngs_modulus(m);
    const double nu = m.poisson_ratio;
    const double g = e / (2.0 * (1.0 + nu));
    return {(1.0 - nu * nu) / e, (2.0 - nu) / g};
  }
  /// Rayleigh time T_R = pi R sqrt(rho/G)/(0.1631 nu + 0.8766) of the smallest particle;
  /// automatic step = 0.2 T_R (common LIGGGHTS practice), stability limit = T_R
  /// (src/contact_law_hertz.cpp).
  static TimeStepEstimate time_step(const TimeStepInputs& inputs) { return hertz_time_step(inputs); }
  static bool restarts_history(const ContactParameters& /*before*/, const ContactParameters& /*after*/) {
    return false;
  }

  [[gnu::always_inline]] ContactForce force(const ContactGeometry& contact, History& history, double dt) const {
    ContactGeometry g = contact;
    g.normal_compliance += body_normal_compliance;
    g.shear_compliance += body_shear_compliance;
    const HertzNormal::Result n = normal.evaluate(g);
    ContactForce out;
    out.elastic_energy = n.energy;
    const double s_t = 8.0 * n.contact_radius / g.shear_compliance;
    const double c_t = -2.0 * std::sqrt(5.0 / 6.0) * normal.beta * std::sqrt(s_t * g.effective_mass);
    out.tangential_force =
        tangential.evaluate(g, s_t, c_t, n.force, history.tangential_displacement, dt, out.elastic_energy);
    // Net normal force: the repulsive Hertz part minus the cohesion (0 when off: n.force - 0 is
    // n.force exactly); friction and rolling see the repulsive part.
    out.force = out.tangential_force - (n.force - cohesion.force(g)) * g.normal;
    if constexpr (kRollingSpring) {
      out.rolling_torque = rolling.evaluate(g, s_t, n.force, history.rolling_torque, dt);
      out.elastic_energy += Rolling::energy(g, s_t, history.rolling_torque);
    } else {
      out.rolling_torque = rolling.evaluate(g, n.force, dt);
    }
    return out;
  }
  /// The springs' energy [J] as `force` left them (same terms, same order: bit-identical). The
  /// cohesion's work is not a spring energy and is not included.
  double elastic_energy(const ContactGeometry& contact, const History& history) const {
    ContactGeometry g = contact;
    g.normal_compliance += body_normal_compliance;
    g.shear_compliance += body_shear_compliance;
    const HertzNormal::Result n = normal.evaluate(g);
    const double s_t = 8.0 * n.contact_radius / g.shear_compliance;
    double energy = n.energy + 0.5 * s_t * norm2(history.tangential_displacement);
    if constexpr (kRollingSpring) energy += Rolling::energy(g, s_t, history.rolling_torque);
    return energy;
  }
};

/// The Hertz–Mindlin law with constant-torque rolling resistance (cdt) and with the epsd2
/// rolling spring.
using HertzMindlinLaw = HertzLaw<ConstantTorqueRolling>;
using HertzEpsd2Law = HertzLaw<ElasticPlasticRolling>;

}  // namespace demfit::dem_core
