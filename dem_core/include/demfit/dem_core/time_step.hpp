#pragma once
// Time steps (docs/spec.md 1). Each contact law computes its own automatic step and stability limit
// (`Law::time_step`, derived where the law is: contact_law_linear.hpp, contact_law_hertz.hpp);
// estimate_time_step picks the simulation's law (contact_laws.hpp). Also closed-form contact
// times and restitution of the laws, used by the tests.
#include <vector>

#include "demfit/dem_core/parameters.hpp"
#include "demfit/dem_core/particle_state.hpp"

namespace demfit::dem_core {

struct TimeStepEstimate {
  double automatic = 0.0;     ///< [s]
  double stable_limit = 0.0;  ///< [s]
};

/// What a law's time step may depend on: the particles, their materials, the contact
/// parameters and the walls' stiffest and most damped contact.
struct TimeStepInputs {
  const ParticleState& particles;
  const std::vector<Material>& materials;
  const ContactParameters& contact;
  double max_wall_sfp = 0.0;   ///< largest SFP of the walls (0 if no walls) [-]
  double max_wall_damp = 0.0;  ///< largest wall DAMP [-]
  double factor = 0.15;        ///< SimulationSettings::time_step_factor [-]
  /// Largest normal compliance a wall adds to a Hertz contact (WallContactParameters::
  /// hertz_normal_compliance; 0 = rigid or no walls) [1/Pa]; the Hertz cohesion limit uses it.
  double max_wall_hertz_compliance = 0.0;
};

/// Steps of `law` for the given particles; `max_wall_sfp` = largest SFP of the walls (0 if no
/// walls), `max_wall_damp` = largest wall DAMP, `max_wall_hertz_compliance` = TimeStepInputs'.
/// Throws std::runtime_error if there are no particles (or the law refuses the parameters).
TimeStepEstimate estimate_time_step(ContactLawKind law, const ParticleState& particles,
                                    const std::vector<Material>& materials, const ContactParameters& contact,
                                    double max_wall_sfp, double max_wall_damp, double factor,
                                    double max_wall_hertz_compliance = 0.0);

/// Verlet stability bound of a mode with frequency omega [1/s] and damping ratio zeta (the
/// damping force uses the half-step velocity): dt < (2/omega)(sqrt(1+zeta^2) - zeta) [s].
double damped_limit(double omega, double zeta);
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
