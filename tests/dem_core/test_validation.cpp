// Bad input at the API: one-line std::runtime_error messages naming the field.
#include <catch2/catch.hpp>

#include <limits>
#include <stdexcept>
#include <string>

#include "demfit/dem_core/simulation.hpp"

using namespace demfit::dem_core;

namespace {

/// Message of the runtime_error thrown by f ("" if none); checks it is one line.
template <class F>
std::string refusal_message(F&& f) {
  try {
    f();
  } catch (const std::runtime_error& e) {
    const std::string m = e.what();
    CHECK(m.find('\n') == std::string::npos);
    return m;
  }
  return "";
}

}  // namespace

TEST_CASE("Invalid particles and materials are refused with a message naming the field", "[dem_core][validation]") {
  Simulation sim;
  CHECK_THAT(refusal_message([&] { sim.add_material({1e9, 0.0, 0.3}); }), Catch::Contains("density"));
  CHECK_THAT(refusal_message([&] { sim.add_material({-1.0, 2500.0, 0.3}); }), Catch::Contains("bulk_modulus"));
  CHECK_THAT(refusal_message([&] { sim.add_particle({0, 0, 0}, 1e-3); }), Catch::Contains("material"));
  sim.add_material({1e9, 2500.0, 0.3});
  CHECK_THAT(refusal_message([&] { sim.add_particle({0, 0, 0}, -1e-3); }), Catch::Contains("radius"));
  CHECK_THAT(refusal_message([&] { sim.add_particle({0, 0, 0}, 0.0); }), Catch::Contains("radius"));
  const double nan = std::numeric_limits<double>::quiet_NaN();
  CHECK_THAT(refusal_message([&] { sim.add_particle({nan, 0, 0}, 1e-3); }), Catch::Contains("position"));
  CHECK_THAT(refusal_message([&] { sim.add_particle({0, 0, 0}, 1e-3, 0, {0, nan, 0}); }), Catch::Contains("velocity"));
  CHECK(sim.particle_count() == 0);
}

TEST_CASE("Invalid contact and wall parameters are refused with a message naming the field", "[dem_core][validation]") {
  ContactParameters c;
  c.normk = -0.01;
  CHECK_THAT(refusal_message([&] { Simulation s(SimulationSettings{.contact = c}); }), Catch::Contains("NORMK"));
  c = {};
  c.ndamp = std::numeric_limits<double>::quiet_NaN();
  CHECK_THAT(refusal_message([&] { Simulation s(SimulationSettings{.contact = c}); }), Catch::Contains("NDAMP"));
  Simulation sim;
  WallSpec w{CylinderGeometry{{0, 0, 0}, {0, 0, 1}, -1.0, 1.0}};
  CHECK_THAT(refusal_message([&] { sim.add_wall(w); }), Catch::Contains("cylinder.radius"));
  WallSpec p{PlaneGeometry{{0, 0, 0}, {0, 0, 0}}};
  CHECK_THAT(refusal_message([&] { sim.add_wall(p); }), Catch::Contains("plane.normal"));
  WallSpec d{DiskGeometry{{0, 0, 0}, {0, 0, 1}, 1.0}};
  d.contact.damp = 1.5;
  CHECK_THAT(refusal_message([&] { sim.add_wall(d); }), Catch::Contains("DAMP"));
}

TEST_CASE("A user time step above the stable limit is refused naming both numbers", "[dem_core][validation]") {
  SimulationSettings settings;
  settings.time_step = 1.0e-3;  // s; the limit for R = 1 mm, K = 1 GPa, NORMK = 0.01 is ~6.5e-5 s
  Simulation sim(settings);
  sim.add_material({1e9, 2500.0, 0.3});
  sim.add_particle({0, 0, 0}, 1e-3);
  const double limit = sim.stable_time_step();
  const std::string m = refusal_message([&] { sim.step(); });
  INFO(m);
  CHECK_THAT(m, Catch::Contains("time_step = 0.001 s"));
  std::ostringstream limit_text;
  limit_text.precision(4);
  limit_text << limit;
  CHECK_THAT(m, Catch::Contains("stable limit " + limit_text.str() + " s"));
  // Two-body velocity-Verlet bound 2 sqrt(m*/k_n), here m*/k_n = m/k_i (equal spheres).
  const double m_over_k = 2500.0 * 4.0 / 3.0 * 3.141592653589793 * 1e-9 / (0.01 * 1e9 * 1e-3);
  CHECK(limit == Approx(2.0 * std::sqrt(m_over_k)).epsilon(1e-12));
  sim.set_time_step(0.0);  // automatic: 0.15 * 2 pi sqrt(m*/k_n)
  CHECK(sim.time_step() == Approx(0.15 * 2.0 * 3.141592653589793 * std::sqrt(m_over_k)).epsilon(1e-12));
  CHECK_NOTHROW(sim.step());
}
