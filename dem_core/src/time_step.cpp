// Time step of the simulation's law (each law derives its own rule: contact_law_linear.cpp,
// contact_law_hertz.cpp) and closed-form contact times.
#include "demfit/dem_core/time_step.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "demfit/dem_core/contact_laws.hpp"

namespace demfit::dem_core {

double damped_limit(double omega, double zeta) { return 2.0 / omega * (std::sqrt(1.0 + zeta * zeta) - zeta); }

TimeStepEstimate estimate_time_step(ContactLawKind law, const ParticleState& particles,
                                    const std::vector<Material>& materials, const ContactParameters& contact,
                                    double max_wall_sfp, double max_wall_damp, double factor,
                                    double max_wall_hertz_compliance) {
  if (particles.size() == 0) throw std::runtime_error("time step: no particles yet; add particles before stepping");
  const TimeStepInputs inputs{
      particles, materials, contact, max_wall_sfp, max_wall_damp, factor, max_wall_hertz_compliance};
  return with_contact_law(law, contact, [&]<class Law>(std::type_identity<Law>) { return Law::time_step(inputs); });
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
