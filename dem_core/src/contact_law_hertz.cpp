// Time step of the Hertz–Mindlin law: the Rayleigh-wave time of the smallest particle,
// T_R = pi R sqrt(rho/G)/(0.1631 nu + 0.8766), the usual bound for Hertzian DEM (a Rayleigh wave
// crossing the sphere); automatic step = 0.2 T_R (common LIGGGHTS practice), stability limit T_R.
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "demfit/dem_core/contact_law_hertz.hpp"

namespace demfit::dem_core {

TimeStepEstimate HertzMindlinLaw::time_step(const TimeStepInputs& inputs) {
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
