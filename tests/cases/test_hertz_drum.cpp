// Case files select the contact law (Hertz–Mindlin with a wall material) and the general drum
// (fill amount, size distribution, photo-frame surface).
#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>
#include <string>

#include "../../cases/src/dem_setup.hpp"
#include "case_test_options.hpp"
#include "demfit/cases/case_runner.hpp"
#include "demfit/cases/case_spec.hpp"
#include "demfit/cases/drum_fill.hpp"
#include "demfit/dem_core/simulation.hpp"
#include "demfit/dem_core/time_step.hpp"

using namespace demfit::cases;
using namespace demfit;
using nlohmann::json;

namespace {

json elastic_frictionless_hertz_drum() {
  return json{{"case", "rotary_drum"},
              {"particle", {{"radius", 0.001}, {"density", 2500.0}, {"youngs_modulus", 5e6}, {"poisson_ratio", 0.3}}},
              {"contact", {{"law", "hertz_mindlin"}, {"restitution", 1.0}, {"frics", 0.0}, {"fricr", 0.0}}},
              {"wall_contact", {{"youngs_modulus", 5e6}, {"poisson_ratio", 0.3}, {"friction_as_particles", true}}},
              {"drum", {{"diameter", 0.1}, {"length", 0.02}}}};
}

dem_core::Simulation simulation_of(const CaseSpec& spec) {
  dem_core::SimulationSettings settings = detail::simulation_settings(spec);
  settings.gravity = {0, 0, 0};
  settings.time_step = spec.time_step.value;
  dem_core::Simulation sim(settings);
  sim.add_material(detail::to_material(spec.material));
  return sim;
}

}  // namespace

TEST_CASE("Hertz-Mindlin selected in a case file gives Hertz's elastic contact time for two colliding spheres (1 %)") {
  json document = elastic_frictionless_hertz_drum();
  document["time_step"]["value"] = 1e-7;
  const CaseSpec spec = parse_case(document);
  REQUIRE(spec.law == dem_core::ContactLawKind::hertz_mindlin);
  dem_core::Simulation sim = simulation_of(spec);
  const double r = 0.001, v = 0.5;  // each sphere at 0.5 m/s: approach speed 1 m/s
  sim.add_particle({0, 0, 0}, r, 0, {v, 0, 0});
  sim.add_particle({2.0 * r + 1e-6, 0, 0}, r, 0, {-v, 0, 0});
  double start = -1.0, end = -1.0;
  sim.run_until(0.01, [&](dem_core::Simulation& s) {
    if (start < 0.0 && s.contact_count() > 0) start = s.time();
    if (start >= 0.0 && s.contact_count() == 0) {
      end = s.time();
      return false;
    }
    return true;
  });
  REQUIRE(end > start);
  const double m = 2500.0 * 4.0 / 3.0 * std::numbers::pi * r * r * r;
  const double e_star = 5e6 / (2.0 * (1.0 - 0.09));  // two equal spheres: 1/E* = 2 (1 - nu^2)/E
  const double expected = 2.87 * std::pow((0.5 * m) * (0.5 * m) / (0.5 * r * e_star * e_star * 2.0 * v), 0.2);
  CHECK(end - start == Approx(expected).epsilon(0.01));
  // Elastic: the spheres separate at the approach speed (restitution 1).
  CHECK(sim.velocities()[1].x - sim.velocities()[0].x == Approx(2.0 * v).epsilon(0.01));
}

TEST_CASE("A Hertz case's automatic time step is 0.2 of the Rayleigh time of its particles") {
  const CaseSpec spec = parse_case(elastic_frictionless_hertz_drum());
  dem_core::Simulation sim = simulation_of(spec);
  sim.add_particle({0, 0, 0}, 0.001);
  const double shear_modulus = 5e6 / (2.0 * 1.3);
  const double rayleigh = std::numbers::pi * 0.001 * std::sqrt(2500.0 / shear_modulus) / (0.1631 * 0.3 + 0.8766);
  CHECK(sim.time_step() == Approx(0.2 * rayleigh).epsilon(1e-12));
}

TEST_CASE("A sphere resting on an elastic Hertz wall has the overlap of the two-body E*") {
  // m g = 4/3 E* sqrt(R) delta^{3/2}, 1/E* = (1 - nu^2)/E + (1 - nu_w^2)/E_w.
  const CaseSpec spec = parse_case(elastic_frictionless_hertz_drum());
  json document = elastic_frictionless_hertz_drum();
  document["contact"]["restitution"] = 0.3;  // damped, so the sphere comes to rest
  const CaseSpec damped = parse_case(document);
  dem_core::SimulationSettings settings = detail::simulation_settings(damped);
  dem_core::Simulation sim(settings);
  sim.add_material(detail::to_material(damped.material));
  const double r = 0.001;
  sim.add_particle({0, 0, r}, r);
  sim.add_wall({dem_core::PlaneGeometry{{0, 0, 0}, {0, 0, 1}}, dem_core::FixedMotion{}, damped.wall, {}, "floor"});
  sim.run_until(0.3);
  const double m = sim.masses()[0];
  const double e_star = 1.0 / (2.0 * (1.0 - 0.09) / 5e6);
  const double delta = std::pow(m * 9.81 / (4.0 / 3.0 * e_star * std::sqrt(r)), 2.0 / 3.0);
  CHECK(r - sim.positions()[0].z == Approx(delta).epsilon(0.01));
  CHECK(spec.wall.youngs_modulus == 5e6);
}

TEST_CASE("Hertz case files are parsed strictly and round-trip; LS-DYNA cases keep their old text") {
  json document = elastic_frictionless_hertz_drum();
  document["contact"]["normk"] = 0.5;
  CHECK(test::case_refusal(document).find("contact.normk") != std::string::npos);
  document = elastic_frictionless_hertz_drum();
  document["wall_contact"]["frics"] = 0.3;  // contradicts friction_as_particles
  CHECK(test::case_refusal(document).find("friction_as_particles") != std::string::npos);
  document = elastic_frictionless_hertz_drum();
  document["contact"].erase("restitution");
  CHECK(test::case_refusal(document).find("contact.restitution") != std::string::npos);
  document = elastic_frictionless_hertz_drum();
  document["contact"]["law"] = "hooke";
  CHECK(test::case_refusal(document).find("contact.law") != std::string::npos);
  const CaseSpec spec = parse_case(elastic_frictionless_hertz_drum());
  CHECK(to_json(parse_case(to_json(spec))) == to_json(spec));
  CHECK(spec.wall.frics == spec.contact.frics);
  // The shipped LS-DYNA drum: no law key, the old field set.
  const json drum = to_json(parse_case(read_case_json(std::string(DEMFIT_SOURCE_DIR) + "/cases/rotary_drum.json")));
  CHECK_FALSE(drum["contact"].contains("law"));
  CHECK_FALSE(drum["contact"].contains("restitution"));
  CHECK_FALSE(drum["wall_contact"].contains("youngs_modulus"));
  CHECK(drum["drum"].contains("fill_fraction"));
  CHECK_FALSE(drum["drum"].contains("image"));
}

TEST_CASE("Hertz parameters override the case, and the tied wall friction follows the particles") {
  const CaseSpec spec = parse_case(elastic_frictionless_hertz_drum());
  const CaseSpec evaluated = detail::with_parameters(spec, {{"frics", 0.56}, {"fricr", 0.29}, {"restitution", 0.4}});
  CHECK(evaluated.wall.frics == 0.56);
  CHECK(evaluated.wall.fricd == 0.29);  // wall rolling friction
  CHECK(evaluated.contact.dynamic_friction() == 0.56);
  CHECK(evaluated.contact.restitution == 0.4);
  CHECK_THROWS_WITH(detail::with_parameters(spec, {{"normk", 0.5}}), Catch::Contains("lsdyna_linear"));
  CHECK_THROWS_WITH(detail::with_parameters(spec, {{"wall_frics", 0.2}}), Catch::Contains("friction_as_particles"));
}

TEST_CASE("A drum fill given as bulk volume holds phi V / E[v] original particles, and s^3 fewer coarse ones") {
  json document = elastic_frictionless_hertz_drum();
  document["drum"]["fill_volume_ml"] = 50.0;
  document["drum"]["volume_fraction"] = 0.6;
  const double v0 = 4.0 / 3.0 * std::numbers::pi * 1e-9;
  const double n0 = 0.6 * 50e-6 / v0;
  DrumFillAmount fill = drum_fill_amount(parse_case(document));
  CHECK(fill.original_count == Approx(n0).epsilon(1e-12));
  CHECK(fill.coarse_count == std::llround(n0));
  document["drum"]["scale_factor"] = 2.0;
  CHECK(drum_fill_amount(parse_case(document)).coarse_count == std::llround(n0 / 8.0));
  // Size classes: E[v] is the number-weighted mean class volume.
  document["particle"].erase("radius");
  document["drum"]["scale_factor"] = 1.0;
  document["drum"]["size_distribution"] = {{"diameter", {1.0, 2.0}}, {"unit", "mm"}, {"number_fraction", {0.75, 0.25}}};
  const double mean_v = 0.75 * std::numbers::pi / 6.0 * 1e-9 + 0.25 * std::numbers::pi / 6.0 * 8e-9;
  fill = drum_fill_amount(parse_case(document));
  CHECK(fill.original_count == Approx(0.6 * 50e-6 / mean_v).epsilon(1e-12));
  // Mass gives the same count as the volume it fills.
  document["drum"].erase("fill_volume_ml");
  document["drum"]["fill_mass"] = 2500.0 * 0.6 * 50e-6;
  CHECK(drum_fill_amount(parse_case(document)).original_count == Approx(fill.original_count).epsilon(1e-12));
  // Exactly one fill amount.
  document["drum"]["particle_count"] = 100;
  CHECK(test::case_refusal(document).find("exactly one") != std::string::npos);
}

TEST_CASE("The GranuDrum case's image surface is lifted on the left, as in the photos", "[slow]") {
  json document = read_case_json(std::string(DEMFIT_SOURCE_DIR) + "/cases/granudrum_mcc.json");
  document["drum"]["scale_factor"] = 4.0;  // 456 particles
  document["drum"]["rpm"] = 45.0;
  document["drum"]["duration"] = 0.6;
  document["drum"]["surface_window"] = 0.1;
  document["drum"]["surface_snapshots"] = 3;
  document["drum"]["densify_time"] = 0.3;
  const CaseSpec spec = parse_case(document, std::string(DEMFIT_SOURCE_DIR) + "/cases");
  const CaseResult result = run_case(spec, {}, test::test_options());
  const auto& image = result.curves.at("free_surface_image");
  CHECK(image.x_label == "x_mm");
  CHECK(image.y_label == "z_mm");
  // Mean height over x < -10 mm against x > +10 mm.
  double left = 0.0, right = 0.0;
  int nl = 0, nr = 0;
  for (std::size_t k = 0; k < image.x.size(); ++k) {
    if (image.x[k] < -10.0) {
      left += image.y[k];
      ++nl;
    }
    if (image.x[k] > 10.0) {
      right += image.y[k];
      ++nr;
    }
  }
  REQUIRE(nl > 0);
  REQUIRE(nr > 0);
  INFO("left " << left / nl << " mm, right " << right / nr << " mm");
  CHECK(left / nl > right / nr + 2.0);
}
