// SJKR cohesion of the Hertz–Mindlin law (hertz_cohesion.hpp): the force against the exact
// sphere-intersection area, the sjkr2 area, a sphere hanging on by cohesion at its equilibrium
// overlap, and the refusals (negative, NaN, too large for the time step, wrong law).
#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>
#include <string>

#include "demfit/dem_core/simulation.hpp"
#include "test_particles.hpp"

using namespace demfit::dem_core;
using namespace demfit::dem_core::test;

namespace {

/// 4/3 E* sqrt(R*) delta^(3/2), computed in long double.
long double hertz_force(long double e_star, long double r_star, long double delta) {
  return 4.0L / 3.0L * e_star * std::sqrt(r_star) * delta * std::sqrt(delta);
}

/// Exact lens-rim radius^2 by the other route: the rim lies at x = (d^2 + R_i^2 - R_j^2)/(2d)
/// from centre i, a^2 = R_i^2 - x^2 (long double, so its cancellation stays far below 1e-12).
long double lens_radius2(long double r_i, long double r_j, long double delta) {
  const long double d = r_i + r_j - delta;
  const long double x = (d * d + r_i * r_i - r_j * r_j) / (2.0L * d);
  return r_i * r_i - x * x;
}

/// Normal force [N] on particle 0 of a pair at overlap `delta` along x (positive = repulsive),
/// evaluated by the simulation's pair loop: one step of 1e-15 s from rest without gravity moves
/// nothing measurable (e = 1: no damping).
double pair_normal_force(double r_i, double r_j, double delta, double k_c, CohesionModel model) {
  SimulationSettings settings;
  settings.law = ContactLawKind::hertz_mindlin;
  settings.contact.restitution = 1.0;
  settings.contact.cohesion_energy_density = k_c;
  settings.contact.cohesion_model = model;
  settings.gravity = {0, 0, 0};
  settings.time_step = 1e-15;
  settings.reorder_particles = false;
  Simulation sim(settings);
  sim.add_material(kHertzMaterial);
  sim.add_particle({0, 0, 0}, r_i);
  sim.add_particle({r_i + r_j - delta, 0, 0}, r_j);
  sim.step();
  return -sim.particles().force[0].x;
}

const long double kPairModulus =
    kHertzYoung / (2.0L * (1.0L - kHertzPoisson * kHertzPoisson));  // E* of two equal materials

}  // namespace

TEST_CASE("SJKR pulls two unequal spheres together with k_c times the exact area of their intersection circle",
          "[dem_core][cohesion]") {
  const double r_i = 1.0e-3, r_j = 2.5e-3, k_c = 2.0e4;
  const long double r_star = static_cast<long double>(r_i) * r_j / (static_cast<long double>(r_i) + r_j);
  for (const double fraction : {0.001, 0.01, 0.04}) {  // overlap / R_i
    const double delta = fraction * r_i;
    const long double area = std::numbers::pi_v<long double> * lens_radius2(r_i, r_j, delta);
    const long double elastic = hertz_force(kPairModulus, r_star, delta);
    const long double expected = elastic - k_c * area;
    const double got = pair_normal_force(r_i, r_j, delta, k_c, CohesionModel::sjkr);
    INFO("delta/R_i " << fraction << ": got " << got << " N, expected " << static_cast<double>(expected)
                      << " N (cohesion " << static_cast<double>(k_c * area) << " N)");
    CHECK(std::fabs(got - static_cast<double>(expected)) <= 1e-12 * static_cast<double>(k_c * area + elastic));
    // The cohesive part alone, against the same area, to 1e-12 of itself.
    const double cohesive = pair_normal_force(r_i, r_j, delta, 0.0, CohesionModel::sjkr) - got;
    CHECK(cohesive == Approx(static_cast<double>(k_c * area)).epsilon(1e-12 * (1.0 + elastic / (k_c * area))));
  }
}

TEST_CASE("SJKR2 pulls two unequal spheres together with k_c 2 pi delta 2R*", "[dem_core][cohesion]") {
  const double r_i = 1.0e-3, r_j = 2.5e-3, k_c = 2.0e4;
  const long double r_star = static_cast<long double>(r_i) * r_j / (static_cast<long double>(r_i) + r_j);
  for (const double fraction : {0.001, 0.01, 0.04}) {
    const double delta = fraction * r_i;
    const long double area = 2.0L * std::numbers::pi_v<long double> * delta * 2.0L * r_star;
    const long double elastic = hertz_force(kPairModulus, r_star, delta);
    const double got = pair_normal_force(r_i, r_j, delta, k_c, CohesionModel::sjkr2);
    INFO("delta/R_i " << fraction << ": got " << got << " N");
    CHECK(std::fabs(got - static_cast<double>(elastic - k_c * area)) <=
          1e-12 * static_cast<double>(k_c * area + elastic));
  }
}

TEST_CASE("A sphere on a floor settles where Hertz minus SJKR cohesion carries its weight (1e-3)",
          "[dem_core][cohesion]") {
  // Equilibrium: 4/3 E* sqrt(R) delta^(3/2) - k_c pi (2 R delta - delta^2) = m g, rigid floor
  // (E* = E/(1 - nu^2), R* = R), solved by bisection; the simulation damps out (e = 0.3).
  const double r = 1.0e-3, k_c = 5.0e4, g = 9.81;
  const double weight = kHertzDensity * 4.0 / 3.0 * std::numbers::pi * r * r * r * g;
  const double e_star = kHertzYoung / (1.0 - kHertzPoisson * kHertzPoisson);
  auto excess = [&](double d) {
    return 4.0 / 3.0 * e_star * std::sqrt(r) * d * std::sqrt(d) - k_c * std::numbers::pi * (2.0 * r * d - d * d) -
           weight;
  };
  double lo = 1e-12, hi = 0.05 * r;  // excess(lo) < 0 < excess(hi)
  REQUIRE(excess(lo) < 0.0);
  REQUIRE(excess(hi) > 0.0);
  for (int i = 0; i < 200; ++i) (excess(0.5 * (lo + hi)) > 0.0 ? hi : lo) = 0.5 * (lo + hi);
  const double expected = 0.5 * (lo + hi);
  // Without cohesion the sphere would sit higher: the test sees the cohesion.
  const double hertz_only = std::pow(weight / (4.0 / 3.0 * e_star * std::sqrt(r)), 2.0 / 3.0);
  REQUIRE(expected > 1.5 * hertz_only);

  SimulationSettings settings;
  settings.law = ContactLawKind::hertz_mindlin;
  settings.contact.restitution = 0.3;
  settings.contact.cohesion_energy_density = k_c;
  settings.gravity = {0, 0, -g};
  Simulation sim(settings);
  sim.add_material(kHertzMaterial);
  sim.add_wall({PlaneGeometry{{0, 0, 0}, {0, 0, 1}}});
  sim.add_particle({0, 0, r}, r);  // touching, at rest
  sim.run_until(0.03);
  const double delta = r - sim.positions()[0].z;
  INFO("overlap " << delta << " m, bisection " << expected << " m, Hertz alone " << hertz_only << " m");
  CHECK(delta == Approx(expected).epsilon(1e-3));
  CHECK(std::fabs(sim.velocities()[0].z) < 1e-9);  // damped out
}

TEST_CASE("A cohesion energy density that is negative or not a number is refused, naming the field",
          "[dem_core][cohesion]") {
  for (const double bad : {-1.0, std::nan("")}) {
    SimulationSettings settings;
    settings.law = ContactLawKind::hertz_mindlin;
    settings.contact.cohesion_energy_density = bad;
    CHECK_THROWS_WITH(Simulation(settings), Catch::Contains("contact.cohesion_energy_density"));
  }
}

TEST_CASE("SJKR cohesion or the epsd2 rolling spring with the LS-DYNA linear law is refused with the fix",
          "[dem_core][cohesion]") {
  SimulationSettings settings;
  settings.contact.cohesion_energy_density = 1000.0;
  CHECK_THROWS_WITH(Simulation(settings), Catch::Contains("hertz_mindlin") && Catch::Contains("surface_energy"));
  settings.contact = {};
  settings.contact.rolling_model = RollingModel::elastic_plastic;
  CHECK_THROWS_WITH(Simulation(settings), Catch::Contains("epsd2") && Catch::Contains("hertz_mindlin"));
}

TEST_CASE("A cohesion above the time step's limit is refused with the limit; just below it runs",
          "[dem_core][cohesion]") {
  // Limit (independent derivation): the cohesive force must not exceed the Hertz force at an
  // overlap of 5 % of the radius. Two equal spheres, R = 1 (the ratio does not depend on R):
  // R* = 1/2, a^2 = delta - delta^2/4; a sphere on a rigid floor: R* = 1, a^2 = 2 delta - delta^2,
  // E* twice the pair's. The pair limit is the lower one.
  const double delta = 0.05;
  const double pair =
      static_cast<double>(hertz_force(kPairModulus, 0.5L, delta)) / (std::numbers::pi * (delta - 0.25 * delta * delta));
  const double floor = static_cast<double>(hertz_force(2.0L * kPairModulus, 1.0L, delta)) /
                       (std::numbers::pi * (2.0 * delta - delta * delta));
  REQUIRE(pair < floor);
  auto run = [&](double k_c) {
    SimulationSettings settings;
    settings.law = ContactLawKind::hertz_mindlin;
    settings.contact.restitution = 0.5;
    settings.contact.cohesion_energy_density = k_c;
    Simulation sim(settings);
    sim.add_material(kHertzMaterial);
    sim.add_wall({PlaneGeometry{{0, 0, 0}, {0, 0, 1}}});
    sim.add_particle({0, 0, 1.0e-3}, 1.0e-3);
    sim.step();
  };
  CHECK_NOTHROW(run(0.999 * pair));
  char limit[32];
  std::snprintf(limit, sizeof limit, "%.4g", pair);
  CHECK_THROWS_WITH(run(1.001 * pair), Catch::Contains("contact.cohesion_energy_density") &&
                                           Catch::Contains(std::string("limit ") + limit + " J/m^3"));
}
