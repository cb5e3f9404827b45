// Effects library (contact_effects.hpp), the bookkeeping around the physics of
// test_effects.cpp: polydisperse radii, thread-count determinism with every effect on, and the
// refusal of out-of-range effect parameters. Every expected number is derived here.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "demfit/dem_core/contact_law_linear.hpp"
#include "demfit/dem_core/packing.hpp"
#include "demfit/dem_core/simulation.hpp"
#include "test_particles.hpp"

using namespace demfit::dem_core;
using namespace demfit::dem_core::test;

TEST_CASE("Polydispersity: radii uniform in [R(1-s), R(1+s)], mean volume R^3 (1+s^2), solid volume kept",
          "[dem_core][effects]") {
  // Statistical tolerances: 4 standard errors of the sample means (u uniform in [-1, 1]:
  // var(1+su) = s^2/3; var((1+su)^3) <= max|f'|^2 E[u^2] = 3 s^2 (1+s)^4); the solid volume
  // overshoots its target by less than one sphere.
  const double r = 1.0e-3, s = 0.25;
  PackingRequest q;
  q.region = BoxRegion{{0, 0, 0}, {0.04, 0.04, 0.04}};
  q.radius_min = q.radius_max = r;
  q.radius_spread = s;
  q.solid_volume = 1500 * 4.0 / 3.0 * std::numbers::pi * r * r * r;
  q.seed = 5;
  const Packing packing = generate_packing(q);
  const auto n = static_cast<double>(packing.radii.size());
  double sum = 0.0, sum3 = 0.0, volume = 0.0, lo = 1.0, hi = 0.0;
  for (double x : packing.radii) {
    sum += x / r;
    sum3 += std::pow(x / r, 3);
    volume += 4.0 / 3.0 * std::numbers::pi * x * x * x;
    lo = std::min(lo, x / r);
    hi = std::max(hi, x / r);
  }
  CHECK(lo >= 1.0 - s);
  CHECK(hi <= 1.0 + s);
  CHECK(hi - lo > 1.8 * s);  // the whole range is used
  CHECK(sum / n == Approx(1.0).margin(4.0 * s / std::sqrt(3.0 * n)));
  // E[(1+su)^3] = 1 + s^2 (odd moments of u vanish).
  CHECK(sum3 / n ==
        Approx(mean_volume_factor(s)).margin(4.0 * std::sqrt(3.0) * s * std::pow(1.0 + s, 2) / std::sqrt(n)));
  CHECK(volume >= q.solid_volume);
  CHECK(volume - q.solid_volume < 4.0 / 3.0 * std::numbers::pi * std::pow(r * (1 + s), 3));
  CHECK(n < 1500.0);  // larger mean volume: fewer spheres for the same solid volume
  // No overlaps (the lattice spacing follows the largest radius).
  double worst = 1.0;
  for (std::size_t i = 0; i < packing.radii.size(); ++i)
    for (std::size_t j = i + 1; j < packing.radii.size(); ++j)
      worst = std::min(worst, norm(packing.centers[j] - packing.centers[i]) / (packing.radii[i] + packing.radii[j]));
  CHECK(worst >= 1.0);
  // Seeded: the same request gives the same packing.
  const Packing again = generate_packing(q);
  CHECK(std::memcmp(again.radii.data(), packing.radii.data(), packing.radii.size() * sizeof(double)) == 0);
  q.radius_max = 1.1e-3;
  CHECK_THROWS_AS(generate_packing(q), std::runtime_error);  // the spread needs one nominal radius
}

TEST_CASE("Runs with every effect on are bit-identical between 1 and 2 threads", "[dem_core][effects]") {
  // The plastic memory (largest overlap) is carried across list rebuilds like the tangential one.
  auto run = [](int threads) {
    SimulationSettings settings;
    settings.threads = threads;
    settings.gravity = {0, 0, -200.0};  // strong, so that the bed compacts within few steps
    settings.contact = {0.01, 2.0 / 7.0, 0.3, 0.3, 0.4, 0.3, 0.0, 0.05, 1.0};
    settings.contact.unloading_stiffness_ratio = 2.0;
    settings.contact.surface_energy = 0.02;
    settings.contact.stiffness_exponent = 1.5;
    Simulation sim(settings);
    sim.add_material(kTestMaterial);
    const double half = 0.008;
    for (const Vec3& n : {Vec3{1, 0, 0}, Vec3{-1, 0, 0}, Vec3{0, 1, 0}, Vec3{0, -1, 0}, Vec3{0, 0, 1}}) {
      WallSpec w{PlaneGeometry{-half * n, n}};
      w.contact = {0.4, 0.05, 0.3, 1.0};
      sim.add_wall(w);
    }
    PackingRequest request;
    request.region = BoxRegion{{-half, -half, -half}, {half, half, 3 * half}};
    request.radius_min = request.radius_max = 0.8e-3;
    request.radius_spread = 0.2;
    request.count = 150;
    request.seed = 3;
    request.gap = 0.05;
    add_packing(sim, generate_packing(request));
    sim.run_steps(2000);
    std::vector<Vec3> state(sim.positions().begin(), sim.positions().end());
    state.insert(state.end(), sim.velocities().begin(), sim.velocities().end());
    state.push_back({sim.wall_force(4).z, sim.elastic_energy(), static_cast<double>(sim.contact_count())});
    return state;
  };
  const std::vector<Vec3> one = run(1), two = run(2);
  CHECK(one.back().z > 0.0);  // contacts happened
  REQUIRE(one.size() == two.size());
  CHECK(std::memcmp(one.data(), two.data(), one.size() * sizeof(Vec3)) == 0);
}

TEST_CASE("Effect parameters out of range are refused with the field's name", "[dem_core][effects]") {
  auto message = [](ContactParameters c, ContactLawKind law = ContactLawKind::lsdyna_linear) -> std::string {
    try {
      SimulationSettings s;
      s.contact = c;
      s.law = law;
      Simulation sim(s);
    } catch (const std::runtime_error& e) { return e.what(); }
    return "";
  };
  ContactParameters c;
  c.unloading_stiffness_ratio = 0.9;
  CHECK(message(c).find("unloading_stiffness_ratio") != std::string::npos);
  c = {};
  c.surface_energy = -1.0;
  CHECK(message(c).find("surface_energy") != std::string::npos);
  c = {};
  c.stiffness_exponent = 2.5;
  CHECK(message(c).find("stiffness_exponent") != std::string::npos);
  c = {};
  c.surface_energy = 0.1;
  CHECK(message(c, ContactLawKind::hertz_mindlin).find("lsdyna_linear") != std::string::npos);
  CHECK(message(ContactParameters{}, ContactLawKind::hertz_mindlin).empty());
}
