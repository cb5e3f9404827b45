// Time-step estimates (see time_step.hpp for the derivation of each rule).
#include "demfit/dem_core/time_step.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

#include "demfit/dem_core/contact_effects.hpp"

namespace demfit::dem_core {
namespace {

/// Verlet stability bound of a mode with frequency omega and damping ratio zeta (the damping
/// force uses the half-step velocity): dt < (2/omega)(sqrt(1+zeta^2) - zeta).
double damped_limit(double omega, double zeta) { return 2.0 / omega * (std::sqrt(1.0 + zeta * zeta) - zeta); }

TimeStepEstimate linear_estimate(const ParticleState& p, const ContactParameters& c, double max_wall_sfp,
                                 double max_wall_damp, double factor) {
  // a_i = m_i / k_i; the stiffest pair has m*/k_n >= min a_i, a wall contact a_i / SFP.
  double a_min = std::numeric_limits<double>::max();
  for (std::size_t i = 0; i < p.size(); ++i) a_min = std::min(a_min, p.mass[i] * p.normal_compliance[i]);
  if (max_wall_sfp > 1.0) a_min /= max_wall_sfp;
  const double omega = 1.0 / std::sqrt(a_min);  // two-body frequency sqrt(k_n/m*) of the tangential spring
  // Normal mode: the effects (plasticity, stiffness exponent) raise the tangent stiffness up to
  // normal_stiffness_scale() k_n (contact_effects.hpp); the damping ratio is kept (conservative:
  // c_n stays 2 NDAMP sqrt(m* k_n), a smaller fraction of the stiffer mode's critical damping).
  const double stiffness_scale = normal_stiffness_scale(c);
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
  e.automatic = std::min(factor * 2.0 * std::numbers::pi / std::max(omega_n, rotation ? omega_t : 0.0), 0.9 * bound);
  return e;
}

TimeStepEstimate hertz_estimate(const ParticleState& p, const std::vector<Material>& materials) {
  double rayleigh = std::numeric_limits<double>::max();
  for (std::size_t i = 0; i < p.size(); ++i) {
    const Material& m = materials[p.material[i]];
    const double nu = m.poisson_ratio;
    const double shear_modulus = youngs_modulus(m) / (2.0 * (1.0 + nu));
    const double t = std::numbers::pi * p.radius[i] * std::sqrt(m.density / shear_modulus) / (0.1631 * nu + 0.8766);
    rayleigh = std::min(rayleigh, t);
  }
  return {0.2 * rayleigh, rayleigh};
}

}  // namespace

TimeStepEstimate estimate_time_step(ContactLawKind law, const ParticleState& particles,
                                    const std::vector<Material>& materials, const ContactParameters& contact,
                                    double max_wall_sfp, double max_wall_damp, double factor) {
  if (particles.size() == 0) throw std::runtime_error("time step: no particles yet; add particles before stepping");
  if (law == ContactLawKind::hertz_mindlin) return hertz_estimate(particles, materials);
  return linear_estimate(particles, contact, max_wall_sfp, max_wall_damp, factor);
}

double linear_contact_duration(double effective_mass, double normal_stiffness, double damping_ratio) {
  const double omega = std::sqrt(normal_stiffness / effective_mass);
  return std::numbers::pi / (omega * std::sqrt(1.0 - damping_ratio * damping_ratio));
}

double linear_restitution(double damping_ratio) {
  return std::exp(-std::numbers::pi * damping_ratio / std::sqrt(1.0 - damping_ratio * damping_ratio));
}

double hertz_contact_duration(double effective_mass, double effective_radius, double effective_youngs_modulus,
                              double approach_speed) {
  const double base = effective_mass * effective_mass /
                      (effective_radius * effective_youngs_modulus * effective_youngs_modulus * approach_speed);
  return 2.87 * std::pow(base, 0.2);
}

double youngs_modulus(const Material& material) {
  return 3.0 * material.bulk_modulus * (1.0 - 2.0 * material.poisson_ratio);
}

}  // namespace demfit::dem_core
