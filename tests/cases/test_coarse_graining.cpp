// Table 2 (docs/spec.md 2.3): every row for s = 1, 2, 4 and both models, derived here from r0, rho0,
// s and phi, and the rows checked against each other (mass = density x volume, ...).
#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>

#include "demfit/cases/coarse_graining.hpp"

using namespace demfit::cases;

namespace {
constexpr double kPhi = 0.64;
const OriginalParticle kOriginal{1.0e-3, 2500.0};
double v0() { return 4.0 / 3.0 * std::numbers::pi * 1.0e-9; }
double m0() { return 2500.0 * v0(); }
}  // namespace

TEST_CASE("SCG rows of Table 2 follow r = s r0, v = s^3 v0, m = s^3 m0, rho = rho0, M = M0") {
  for (double s : {1.0, 2.0, 4.0}) {
    const CoarseParticle p = coarse_grain(CoarseGraining::scg, s, kPhi, kOriginal);
    CHECK(p.radius == Approx(s * 1.0e-3).epsilon(1e-14));
    CHECK(p.volume == Approx(s * s * s * v0()).epsilon(1e-14));
    CHECK(p.mass == Approx(s * s * s * m0()).epsilon(1e-14));
    CHECK(p.density == Approx(2500.0).epsilon(1e-14));
    CHECK(p.total_mass_factor == Approx(1.0).epsilon(1e-14));
  }
}

TEST_CASE("CVF rows of Table 2 follow v = s^3 v0 / phi, m = s^3 m0, rho = phi rho0, M = phi M0") {
  for (double s : {1.0, 2.0, 4.0}) {
    const CoarseParticle p = coarse_grain(CoarseGraining::cvf, s, kPhi, kOriginal);
    CHECK(p.radius == Approx(s * 1.0e-3 * std::pow(kPhi, -1.0 / 3.0)).epsilon(1e-14));
    CHECK(p.volume == Approx(s * s * s * v0() / kPhi).epsilon(1e-14));
    CHECK(p.mass == Approx(s * s * s * m0()).epsilon(1e-14));
    CHECK(p.density == Approx(kPhi * 2500.0).epsilon(1e-14));
    CHECK(p.total_mass_factor == Approx(kPhi).epsilon(1e-14));
  }
}

TEST_CASE("Every Table 2 row agrees with the others: sphere volume of the radius, mass = density x volume") {
  for (CoarseGraining model : {CoarseGraining::scg, CoarseGraining::cvf}) {
    for (double s : {1.0, 2.0, 4.0}) {
      const CoarseParticle p = coarse_grain(model, s, kPhi, kOriginal);
      CHECK(4.0 / 3.0 * std::numbers::pi * std::pow(p.radius, 3) == Approx(p.volume).epsilon(1e-12));
      CHECK(p.density * p.volume == Approx(p.mass).epsilon(1e-12));
    }
  }
}

TEST_CASE("Coarse particle counts carry the model's total mass: M0 for SCG, phi M0 for CVF") {
  const double total_mass_original = 9000 * m0();
  for (double s : {1.0, 2.0, 4.0}) {
    const CoarseParticle scg = coarse_grain(CoarseGraining::scg, s, kPhi, kOriginal);
    const CoarseParticle cvf = coarse_grain(CoarseGraining::cvf, s, kPhi, kOriginal);
    const long long n_scg = coarse_particle_count(scg, total_mass_original);
    const long long n_cvf = coarse_particle_count(cvf, total_mass_original);
    CHECK(n_scg == std::llround(9000.0 / (s * s * s)));
    // Rounding to whole particles: the represented mass is within half a particle of the target.
    CHECK(std::fabs(n_scg * scg.mass - total_mass_original) <= 0.5 * scg.mass);
    CHECK(std::fabs(n_cvf * cvf.mass - kPhi * total_mass_original) <= 0.5 * cvf.mass);
  }
}

TEST_CASE("The paper's printed CVF radius contradicts its own volume row unless phi = 1") {
  const double printed = paper_printed_cvf_radius(2.0, kPhi, 1.0e-3);
  const CoarseParticle cvf = coarse_grain(CoarseGraining::cvf, 2.0, kPhi, kOriginal);
  // Sphere volume from the printed radius is phi s^3 v0, off from s^3 v0 / phi by phi^2.
  CHECK(sphere_volume(printed) == Approx(kPhi * kPhi * cvf.volume).epsilon(1e-12));
  CHECK(paper_printed_cvf_radius(2.0, 1.0, 1.0e-3) ==
        Approx(coarse_grain(CoarseGraining::cvf, 2.0, 1.0, kOriginal).radius).epsilon(1e-14));
}

TEST_CASE("Coarse graining rejects a non-positive scale factor and a volume fraction outside 0 < phi <= 1") {
  CHECK_THROWS(coarse_grain(CoarseGraining::scg, 0.0, kPhi, kOriginal));
  CHECK_THROWS(coarse_grain(CoarseGraining::cvf, 2.0, 1.5, kOriginal));
  CHECK_THROWS(parse_coarse_graining("SCG2"));
  CHECK(parse_coarse_graining("cvf") == CoarseGraining::cvf);
}
