// Input validation at the API: every message is one line naming the field and the fix.
#include "demfit/dem_core/parameters.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "validation.hpp"

namespace demfit::dem_core {

void validate(const Material& m) {
  require_positive("material.bulk_modulus [Pa]", m.bulk_modulus);
  require_positive("material.density [kg/m^3]", m.density);
  require_finite("material.poisson_ratio", m.poisson_ratio);
  if (m.poisson_ratio <= -1.0 || m.poisson_ratio >= 0.5)
    fail("material.poisson_ratio", m.poisson_ratio, "must lie in (-1, 0.5)");
}

void validate(const ContactParameters& p) {
  require_positive("contact.normk (NORMK)", p.normk);
  require_non_negative("contact.sheark (SHEARK)", p.sheark);
  require_fraction("contact.ndamp (NDAMP)", p.ndamp);
  require_fraction("contact.tdamp (TDAMP)", p.tdamp);
  require_non_negative("contact.frics (FRICS)", p.frics);
  require_finite("contact.fricd (FRICD)", p.fricd);  // negative = "same as FRICS"
  require_non_negative("contact.dc (DC) [s/m]", p.dc);
  require_non_negative("contact.fricr (FRICR)", p.fricr);
  require_positive("contact.restitution", p.restitution);
  if (p.restitution > 1.0) fail("contact.restitution", p.restitution, "must lie in (0, 1]");
  require_finite("contact.unloading_stiffness_ratio", p.unloading_stiffness_ratio);
  if (p.unloading_stiffness_ratio < 1.0)
    fail("contact.unloading_stiffness_ratio", p.unloading_stiffness_ratio, "must be >= 1 (1 = elastic, no plasticity)");
  require_non_negative("contact.surface_energy [J/m^2]", p.surface_energy);
  require_finite("contact.stiffness_exponent", p.stiffness_exponent);
  if (p.stiffness_exponent < 1.0 || p.stiffness_exponent > 2.0)
    fail("contact.stiffness_exponent", p.stiffness_exponent, "must lie in [1, 2] (1 = linear, 1.5 = Hertzian shape)");
  require_non_negative("contact.cohesion_energy_density [J/m^3]", p.cohesion_energy_density);
}

void validate(const WallContactParameters& p) {
  require_non_negative("wall.frics (wall FRICS)", p.frics);
  require_non_negative("wall.fricd (wall FRICD, rolling)", p.fricd);
  require_fraction("wall.damp (wall DAMP)", p.damp);
  require_positive("wall.sfp (SFP)", p.sfp);
  require_non_negative("wall.youngs_modulus [Pa] (0 = rigid)", p.youngs_modulus);
  require_finite("wall.poisson_ratio", p.poisson_ratio);
  if (p.poisson_ratio <= -1.0 || p.poisson_ratio >= 0.5)
    fail("wall.poisson_ratio", p.poisson_ratio, "must lie in (-1, 0.5)");
}

}  // namespace demfit::dem_core
