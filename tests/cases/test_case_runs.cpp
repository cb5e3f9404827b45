// Small variants of the shipped cases run end to end and obey the statics they must obey.
#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>

#include "demfit/cases/case_runner.hpp"
#include "demfit/cases/case_spec.hpp"
#include "demfit/cases/coarse_graining.hpp"

using namespace demfit::cases;
using nlohmann::json;

namespace {

CaseRunOptions test_options() {
  CaseRunOptions options;
  options.cache_dir = std::string(DEMFIT_BINARY_DIR) + "/test_cache";
  return options;
}

// 120 pellets in a 24 mm cylinder; frictionless walls so that statics are exact.
CaseSpec small_pellet_case() {
  json document = read_case_json(std::string(DEMFIT_SOURCE_DIR) + "/cases/pellet_compression.json");
  document["pellet"]["particle_count"] = 120;
  document["pellet"]["container_diameter"] = 0.024;
  document["pellet"]["settle_time"] = 0.3;
  document["pellet"]["max_pressure"] = 0.5e6;
  document["pellet"]["max_travel"] = 0.006;
  document["wall_contact"]["frics"] = 0.0;
  return parse_case(document);
}

}  // namespace

TEST_CASE("A small pellet compression runs and, with frictionless walls, the bottom plate carries piston force plus weight") {
  const CaseSpec spec = small_pellet_case();
  const CaseResult result = run_case(spec, {}, test_options());
  const CurveTable& history = result.tables.at("history");
  REQUIRE(history.columns.at(5) == "bottom_force_N");
  const double mass = 120 * spec.material.density * sphere_volume(spec.material.radius);
  // Quasi-static loading: piston force + weight = bottom force at the end of loading (2 %).
  const auto& piston = history.values[4];
  const auto& bottom = history.values[5];
  std::size_t end = 0;
  for (std::size_t i = 0; i < piston.size(); ++i) {
    if (piston[i] > piston[end]) end = i;
  }
  CHECK(bottom[end] == Approx(piston[end] + mass * 9.81).epsilon(0.02));
  const auto& curve = result.curves.at("pressure_volume");
  CHECK(curve.x_label == "volume_cm3");
  CHECK(curve.y_label == "pressure_MPa");
  REQUIRE(curve.x.size() == 60);
  for (std::size_t i = 1; i < curve.x.size(); ++i) CHECK(curve.x[i] < curve.x[i - 1]);  // piston moves down
  // Initial bed volume = container area x bed height (piston starts at the highest pellet top).
  const double area = std::numbers::pi * 0.012 * 0.012;
  CHECK(curve.x.front() > 120 * sphere_volume(spec.material.radius) * 1e6);
  CHECK(curve.x.front() < area * 0.3 * 1e6);
}

TEST_CASE("A small CVF s = 4 drum runs, holds the Table 2 particle count and radius, and resists the rotation") {
  json document = read_case_json(std::string(DEMFIT_SOURCE_DIR) + "/cases/rotary_drum.json");
  document["drum"]["scale_factor"] = 4.0;
  document["drum"]["coarse_graining"] = "cvf";
  document["drum"]["duration"] = 0.3;
  document["drum"]["densify_time"] = 0.6;
  document["drum"]["surface_window"] = 0.05;
  document["drum"]["torque_interval"] = 0.05;
  const CaseSpec spec = parse_case(document);
  const CaseResult result = run_case(spec, {}, test_options());
  // Expected count from Table 2: phi M0 / (s^3 m0), M0 = rho0 phi V_fill.
  const double drum_volume = std::numbers::pi * 0.05 * 0.05 * 0.025;
  const double m0 = 2500.0 * sphere_volume(0.001);
  const long long expected = std::llround(0.64 * (2500.0 * 0.64 * 0.3 * drum_volume) / (64.0 * m0));
  CHECK(result.tables.at("particles_end").values[0].size() == static_cast<std::size_t>(expected));
  CHECK(result.tables.at("particles_end").values[3].front() == Approx(4.0 / std::cbrt(0.64)).epsilon(1e-12));
  const auto& torque = result.curves.at("torque");
  REQUIRE(torque.x.size() >= 5);
  CHECK(torque.x[1] - torque.x[0] == Approx(0.05).epsilon(0.05));
  const auto& surface = result.curves.at("free_surface");
  REQUIRE(surface.x.size() >= 5);
  // The drum lifts the bed on its rising side (x > 0 for counter-clockwise rotation about +z):
  // the surface rises with x, and the bed's weight resists the rotation (drive torque > 0).
  CHECK(surface.y.back() > surface.y.front());
  double mean_torque = 0.0;
  for (double t : torque.y) mean_torque += t / static_cast<double>(torque.y.size());
  CHECK(mean_torque > 0.0);
}
