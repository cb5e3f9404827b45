// Table 2 coarse-graining rules (see coarse_graining.hpp for the formulas and the CVF radius note).
#include "demfit/cases/coarse_graining.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace demfit::cases {

CoarseGraining parse_coarse_graining(const std::string& name) {
  if (name == "scg") return CoarseGraining::scg;
  if (name == "cvf") return CoarseGraining::cvf;
  throw std::runtime_error("coarse-graining model '" + name + "' is unknown (use \"scg\" or \"cvf\")");
}

std::string to_string(CoarseGraining model) { return model == CoarseGraining::scg ? "scg" : "cvf"; }

double sphere_volume(double radius) { return 4.0 / 3.0 * std::numbers::pi * radius * radius * radius; }

CoarseParticle coarse_grain(CoarseGraining model, double s, double phi, const OriginalParticle& original) {
  if (!(s > 0.0)) throw std::runtime_error("coarse-graining scale factor s must be > 0");
  if (!(phi > 0.0 && phi <= 1.0)) {
    throw std::runtime_error("coarse-graining volume fraction phi must lie in (0, 1]");
  }
  const double s3 = s * s * s;
  const double v0 = sphere_volume(original.radius);
  const double m0 = original.density * v0;
  CoarseParticle out;
  out.mass = s3 * m0;  // both models keep the mass of the s^3 particles replaced
  if (model == CoarseGraining::scg) {
    out.radius = s * original.radius;
    out.volume = s3 * v0;
    out.density = original.density;
    out.total_mass_factor = 1.0;
  } else {
    // Self-consistent CVF radius: (s^3 v0 / phi) must be the sphere volume, so r = s r0 phi^(-1/3).
    out.radius = s * original.radius / std::cbrt(phi);
    out.volume = s3 * v0 / phi;
    out.density = phi * original.density;
    out.total_mass_factor = phi;
  }
  return out;
}

double paper_printed_cvf_radius(double s, double phi, double r0) { return std::cbrt(phi) * s * r0; }

long long coarse_particle_count(const CoarseParticle& coarse, double original_total_mass) {
  return std::llround(coarse.total_mass_factor * original_total_mass / coarse.mass);
}

}  // namespace demfit::cases
