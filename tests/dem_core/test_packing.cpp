// Packing generator and region geometry.
#include <catch2/catch.hpp>

#include <cmath>
#include <functional>
#include <numbers>

#include "demfit/dem_core/packing.hpp"
#include "demfit/dem_core/simulation.hpp"

using namespace demfit::dem_core;

TEST_CASE("Generated packings are seeded, non-overlapping and inside the region", "[dem_core][packing]") {
  PackingRequest q;
  q.region = CylinderRegion{{0, 0, 0}, {0, 0, 1}, 0.018, 0.12};
  q.radius_min = 1.5e-3;
  q.radius_max = 1.86e-3;
  q.count = 600;
  q.seed = 5;
  const Packing a = generate_packing(q);
  const Packing b = generate_packing(q);
  REQUIRE(a.centers.size() == 600);
  CHECK(a.centers == b.centers);
  q.seed = 6;
  const Packing c = generate_packing(q);
  CHECK(c.centers != a.centers);
  double volume = 0.0;
  for (std::size_t i = 0; i < a.centers.size(); ++i) {
    REQUIRE(region_contains(q.region, a.centers[i], a.radii[i]));
    volume += 4.0 / 3.0 * std::numbers::pi * std::pow(a.radii[i], 3);
    for (std::size_t j = i + 1; j < a.centers.size(); ++j)
      REQUIRE(norm(a.centers[j] - a.centers[i]) >= a.radii[i] + a.radii[j]);
  }
  CHECK(a.solid_volume == Approx(volume).epsilon(1e-12));
  CHECK(a.volume_fraction == Approx(volume / (std::numbers::pi * 0.018 * 0.018 * 0.12)).epsilon(1e-12));
  q.count = c.capacity + 1;
  CHECK_THROWS_WITH(generate_packing(q), Catch::Contains("count"));
}

TEST_CASE("Drum fill height and segment volume agree with the circle-segment formula", "[dem_core][packing]") {
  const double r = 0.05, length = 0.025;
  CHECK(drum_fill_height(r, 0.5) == Approx(0.0).margin(1e-12));
  const double h = drum_fill_height(r, 0.3);
  // Independent: segment area below height h from the centre, A = r^2 acos(-h/r)... via the
  // central angle of the empty cap above: cap = r^2/2 (t - sin t), t = 2 acos(h/r).
  const double t = 2.0 * std::acos(h / r);
  const double area = std::numbers::pi * r * r - 0.5 * r * r * (t - std::sin(t));
  CHECK(area == Approx(0.3 * std::numbers::pi * r * r).epsilon(1e-9));
  const Region segment = DrumSegmentRegion{{0, 0, 0}, {0, 1, 0}, r, length, {0, 0, 1}, h};
  CHECK(region_volume(segment) == Approx(area * length).epsilon(1e-9));
  // Below the fill level the bulk volume is the segment itself; a fuller drum cut at the axis
  // holds exactly half the cylinder.
  CHECK(region_volume_below(segment, {0, 0, 1}, 0.0) == Approx(region_volume(segment)).epsilon(1e-12));
  const Region fuller = DrumSegmentRegion{{0, 0, 0}, {0, 1, 0}, r, length, {0, 0, 1}, 0.02};
  CHECK(region_volume_below(fuller, {0, 0, 1}, 0.0) == Approx(0.5 * std::numbers::pi * r * r * length).epsilon(1e-9));
}

namespace {

/// 250 spheres (R = 1 mm) poured into a 18 mm cylinder and settled; returns the volume fraction.
double settled_fraction(bool frictionless, SettleReport& report, std::function<void(double, double)> progress = {},
                        std::vector<Vec3>* positions = nullptr) {
  SimulationSettings settings;
  settings.contact = {0.01, 2.0 / 7.0, 0.5, 0.5, 0.5, -1.0, 0.0, 0.1, 1.0};
  Simulation sim(settings);
  sim.add_material({1.767e9, 1000.0, 0.4});
  const double radius = 0.009;
  WallSpec floor{PlaneGeometry{{0, 0, 0}, {0, 0, 1}}};
  floor.contact = {0.5, 0.0, 0.5, 1.0};
  WallSpec shell{CylinderGeometry{{0, 0, 0}, {0, 0, 1}, radius, 0.2}};
  shell.contact = floor.contact;
  sim.add_wall(floor);
  sim.add_wall(shell);
  const Region region = CylinderRegion{{0, 0, 0}, {0, 0, 1}, radius, 0.2};
  PackingRequest q;
  q.region = region;
  q.radius_min = q.radius_max = 1.0e-3;
  q.count = 250;
  add_packing(sim, generate_packing(q));
  report = settle(sim, {.max_time = 0.5, .frictionless = frictionless, .progress = progress});
  if (positions) positions->assign(sim.positions().begin(), sim.positions().end());
  for (std::size_t i = 0; i < sim.particle_count(); ++i) REQUIRE(region_contains(region, sim.positions()[i], 0.99e-3));
  return packed_volume_fraction(sim, region, {0, 0, 1});
}

}  // namespace

TEST_CASE("Settling brings a poured bed to rest and frictionless densification packs it denser",
          "[dem_core][packing]") {
  SettleReport rough, smooth;
  const double phi_rough = settled_fraction(false, rough);
  const double phi_smooth = settled_fraction(true, smooth);
  INFO("frictional: " << rough.simulated_time << " s, phi " << phi_rough << "; densified: " << smooth.simulated_time
                      << " s, phi " << phi_smooth);
  CHECK(rough.converged);
  CHECK(smooth.converged);
  // Narrow container (D/d = 9) and a bed height taken from the top particles: loose values.
  CHECK(phi_rough > 0.40);
  CHECK(phi_rough < 0.62);
  // Friction stabilises looser structures (random loose vs random close packing).
  CHECK(phi_smooth > phi_rough + 0.02);
}

TEST_CASE("Settling reports its progress after every check and settles the same bed with or without it",
          "[dem_core][packing]") {
  SettleReport quiet, reported;
  std::vector<Vec3> quiet_bed, reported_bed;
  std::vector<std::pair<double, double>> calls;
  settled_fraction(true, quiet, {}, &quiet_bed);
  settled_fraction(
      true, reported, [&](double elapsed, double end) { calls.emplace_back(elapsed, end); }, &reported_bed);
  REQUIRE(!calls.empty());
  for (std::size_t i = 0; i < calls.size(); ++i) {
    CHECK(calls[i].second == 0.5);
    CHECK(calls[i].first <= 0.5);
    if (i > 0) CHECK(calls[i].first > calls[i - 1].first);
  }
  CHECK(calls.back().first == Approx(reported.simulated_time).margin(1e-12));
  // One call per convergence check (every 5 ms of simulated time, SettleOptions::check_interval).
  CHECK(static_cast<double>(calls.size()) == Approx(reported.simulated_time / 0.005).margin(1.0));
  REQUIRE(quiet_bed.size() == reported_bed.size());
  for (std::size_t i = 0; i < quiet_bed.size(); ++i) {
    CHECK(quiet_bed[i].x == reported_bed[i].x);
    CHECK(quiet_bed[i].z == reported_bed[i].z);
  }
}

TEST_CASE("A packing of explicit radii places exactly those radii, in order, without overlaps, inside the region",
          "[dem_core][packing]") {
  PackingRequest q;
  q.region = DrumSegmentRegion{{0, 0, 0}, {0, 0, 1}, 0.042, 0.02, {0, 1, 0}, 0.0};
  for (int k = 0; k < 400; ++k) q.radii.push_back(0.5e-3 + 0.25e-3 * static_cast<double>(k % 7) / 6.0);
  q.lattice = PackingRequest::Lattice::fcc;
  q.gap = 0.03;
  const Packing p = generate_packing(q);
  REQUIRE(p.radii == q.radii);
  for (std::size_t i = 0; i < p.centers.size(); ++i) {
    REQUIRE(region_contains(q.region, p.centers[i], p.radii[i]));
    for (std::size_t j = i + 1; j < p.centers.size(); ++j)
      REQUIRE(norm(p.centers[i] - p.centers[j]) >= p.radii[i] + p.radii[j]);
  }
  CHECK(generate_packing(q).centers == p.centers);  // seeded
}

TEST_CASE("An fcc lattice holds sqrt(2) times the sites of the cubic one at the same neighbour distance",
          "[dem_core][packing]") {
  // A box of 40 x 40 x 40 neighbour distances: boundary losses are a few per cent, the bulk ratio
  // is exactly sqrt(2) (4 sites per a^3 with a = sqrt(2) d, against 1 per d^3).
  PackingRequest q;
  q.radius_min = q.radius_max = 1e-3;
  q.gap = 0.0;
  q.region = BoxRegion{{0, 0, 0}, {0.08, 0.08, 0.08}};
  q.count = 1;
  const double cubic = static_cast<double>(generate_packing(q).capacity);
  q.lattice = PackingRequest::Lattice::fcc;
  const double fcc = static_cast<double>(generate_packing(q).capacity);
  CHECK(fcc / cubic == Approx(std::sqrt(2.0)).epsilon(0.05));
}
