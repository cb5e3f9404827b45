// Time step of the Hertz–Mindlin law: the Rayleigh-wave time of the smallest particle,
// T_R = pi R sqrt(rho/G)/(0.1631 nu + 0.8766), the usual bound for Hertzian DEM (a Rayleigh wave
// crossing the sphere); automatic step = 0.2 T_R (common LIGGGHTS practice), stability limit T_R.
// With SJKR cohesion the step also needs the cohesion below hertz_cohesion_limit
// (hertz_cohesion.hpp): checked here for every pair of the particles' materials (equal spheres)
// and for each material on the softest wall.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "demfit/dem_core/contact_law_hertz.hpp"

namespace demfit::dem_core {
namespace {

// (1 - nu^2)/E of a material [1/Pa] (the Hertz particle compliance).
double normal_compliance(const Material& m) { return (1.0 - m.poisson_ratio * m.poisson_ratio) / youngs_modulus(m); }

void require_stable_cohesion(const TimeStepInputs& inputs) {
  const ContactParameters& c = inputs.contact;
  if (c.cohesion_energy_density <= 0.0) return;
  std::vector<char> used(inputs.materials.size(), 0);
  for (const std::size_t m : inputs.particles.material) used[m] = 1;
  double limit = std::numeric_limits<double>::infinity();
  for (std::size_t a = 0; a < used.size(); ++a) {
    if (!used[a]) continue;
    const double own = normal_compliance(inputs.materials[a]);
    for (std::size_t b = a; b < used.size(); ++b)
      if (used[b])
        limit = std::min(
            limit, hertz_cohesion_limit(1.0 / (own + normal_compliance(inputs.materials[b])), c.cohesion_model, false));
    // Against the softest wall (a rigid one adds no compliance; no walls: the limit is looser
    // than the pairs' anyway).
    limit =
        std::min(limit, hertz_cohesion_limit(1.0 / (own + inputs.max_wall_hertz_compliance), c.cohesion_model, true));
  }
  if (c.cohesion_energy_density <= limit) return;
  char message[400];
  std::snprintf(message, sizeof message,
                "contact.cohesion_energy_density = %.4g J/m^3 exceeds the limit %.4g J/m^3 of these particles "
                "(%s: the cohesive force must not exceed the Hertz force at an overlap of %.0f %% of the radius, "
                "or overlaps outgrow the time step): lower it",
                c.cohesion_energy_density, limit, model_name(kCohesionModels, c.cohesion_model),
                100.0 * kCohesionPlannedOverlap);
  throw std::runtime_error(message);
}

}  // namespace

TimeStepEstimate hertz_time_step(const TimeStepInputs& inputs) {
  require_stable_cohesion(inputs);
  const ParticleState& p = inputs.particles;
  double rayleigh = std::numeric_limits<double>::max();
  for (std::size_t i = 0; i < p.size(); ++i) {
    const Material& m = inputs.materials[p.material[i]];
    const double nu = m.poisson_ratio;
    const double shear_modulus = youngs_modulus(m) / (2.0 * (1.0 + nu));
    const double t = std::numbers::pi * p.radius[i] * std::sqrt(m.density / shear_modulus) / (0.1631 * nu + 0.8766);
    rayleigh = std::min(rayleigh, t);
  }
  return {0.2 * rayleigh, rayleigh};
}

}  // namespace demfit::dem_core
