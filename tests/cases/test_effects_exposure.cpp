// The effects catalogue is exposed by the case models: every catalogue parameter is an
// identified parameter (names, --set, round trip) and its upper bound changes the curves (tiny,
// fast case variants; the base variants are at every effect's off value already).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <set>
#include <string>

#include "case_test_options.hpp"
#include "demfit/cases/case_runner.hpp"
#include "demfit/cases/case_spec.hpp"
#include "demfit/cases/effect_catalogue.hpp"
#include "demfit/cases/model_factory.hpp"

using namespace demfit;
using namespace demfit::cases;
using nlohmann::json;

namespace {

using test::test_options;

// Base variants with every catalogue effect at its off value (wall FRICS and FRICR are effects
// here, so they are 0), small and soft so that one evaluation takes a fraction of a second.
json tiny_overrides(const std::string& case_name) {
  const json off = {{"wall_contact", {{"frics", 0.0}}}, {"contact", {{"fricr", 0.0}, {"normk", 0.05}}}};
  json o = off;
  if (case_name == "pellet_compression") {
    o["pellet"] = {{"particle_count", 150}, {"container_diameter", 0.024}, {"settle_time", 0.3}, {"piston_speed", 0.2},
                   {"max_pressure", 0.3e6}, {"max_travel", 0.004},         {"unload", true},     {"curve_points", 20}};
  } else {
    o["drum"] = {{"scale_factor", 4.0},    {"duration", 0.15},       {"densify_time", 0.3}, {"torque_interval", 0.01},
                 {"surface_window", 0.05}, {"surface_snapshots", 2}, {"surface_points", 21}};
  }
  return o;
}

CaseSpec tiny_case(const std::string& case_name) {
  json document = read_case_json(std::string(DEMFIT_SOURCE_DIR) + "/cases/" + case_name + ".json");
  document.merge_patch(tiny_overrides(case_name));
  return parse_case(document);
}

// Largest change of any curve's y, relative to that curve's max |y| (curves of different length
// count as changed).
double largest_change(const identify::CurveSet& a, const identify::CurveSet& b) {
  double worst = 0.0;
  for (const auto& [name, curve] : a) {
    const auto& other = b.at(name);
    if (other.y.size() != curve.y.size()) return 1.0;
    double scale = 0.0, change = 0.0;
    for (std::size_t i = 0; i < curve.y.size(); ++i) {
      scale = std::max(scale, std::fabs(curve.y[i]));
      change = std::max(change, std::fabs(curve.y[i] - other.y[i]));
    }
    if (scale > 0.0) worst = std::max(worst, change / scale);
  }
  return worst;
}

void check_effects_on_case(const std::string& case_name) {
  const CaseSpec spec = tiny_case(case_name);
  const identify::CurveSet base = run_case(spec, {}, test_options()).curves;
  for (const EffectInfo& effect : effects_for_case(case_name)) {
    for (const EffectParameterInfo& p : effect.parameters) {
      INFO(case_name << ": effect " << effect.name << ", parameter " << p.name);
      const identify::CurveSet on = run_case(spec, {{p.name, p.upper}}, test_options()).curves;
      CHECK(largest_change(base, on) > 1e-3);  // the effect acts (at least 0.1 % of a curve's scale)
    }
  }
}

}  // namespace

TEST_CASE("Every catalogue parameter is an identified parameter of the cases it applies to, with sane bounds") {
  const auto pellet = make_model("pellet_compression", json::object(), DEMFIT_SOURCE_DIR);
  const auto drum = make_model("rotary_drum", json::object(), DEMFIT_SOURCE_DIR);
  std::set<std::string> all_effects;
  for (const std::string case_name : {"pellet_compression", "rotary_drum"})
    for (const EffectInfo& effect : effects_for_case(case_name)) all_effects.insert(effect.name);
  REQUIRE(all_effects.size() == 6);
  for (const std::string case_name : {"pellet_compression", "rotary_drum"}) {
    const auto& model = case_name == "pellet_compression" ? pellet : drum;
    const auto names = model->parameter_names();
    for (const EffectInfo& effect : effects_for_case(case_name)) {
      REQUIRE(effect.cases == std::vector<std::string>{case_name});
      for (const EffectParameterInfo& p : effect.parameters) {
        INFO(case_name << ": " << effect.name << " / " << p.name);
        CHECK(std::find(names.begin(), names.end(), p.name) != names.end());
        CHECK(!parameter_path(p.name).empty());
        CHECK(p.lower <= p.off_value);
        CHECK(p.off_value < p.upper);
        // --set name=upper reaches the field and survives the to_json/parse round trip.
        json document = json::parse(
            to_json(parse_case(read_case_json(std::string(DEMFIT_SOURCE_DIR) + "/cases/" + case_name + ".json")))
                .dump());
        apply_setting(document, p.name + "=" + std::to_string(p.upper));
        const CaseSpec spec = parse_case(document);
        const std::string path = parameter_path(p.name);
        const json resolved = to_json(spec);
        const auto dot = path.find('.');
        CHECK(resolved.at(path.substr(0, dot)).at(path.substr(dot + 1)).get<double>() == Approx(p.upper));
        CHECK(to_json(parse_case(resolved)) == resolved);
      }
    }
  }
  // The new effect parameters default to their off values in the shipped cases.
  for (const char* name : {"unloading_stiffness_ratio", "surface_energy", "stiffness_exponent", "radius_spread"}) {
    const double off =
        std::string(name) == "unloading_stiffness_ratio" || std::string(name) == "stiffness_exponent" ? 1.0 : 0.0;
    CHECK(pellet->default_parameters().at(name) == off);
    CHECK(drum->default_parameters().at(name) == off);
  }
  // Plasticity needs unloading, which only the pellet case has.
  const auto drum_effects = effects_for_case("rotary_drum");
  CHECK(std::none_of(drum_effects.begin(), drum_effects.end(),
                     [](const EffectInfo& e) { return e.name == "plasticity"; }));
  CHECK_THROWS_WITH(effects_for_case("hopper"), Catch::Contains("hopper"));
}

TEST_CASE("The cohesion upper bound is a pull-off force of five particle weights in the pellet, one in the drum") {
  // Two equal spheres: F_c = 1.5 pi gamma R/2; weight rho 4/3 pi R^3 g.
  for (const std::string case_name : {"pellet_compression", "rotary_drum"}) {
    const CaseSpec spec = parse_case(read_case_json(std::string(DEMFIT_SOURCE_DIR) + "/cases/" + case_name + ".json"));
    const double r = spec.material.radius;
    const double weight = spec.material.density * 4.0 / 3.0 * std::numbers::pi * r * r * r * 9.81;
    for (const EffectInfo& e : effects_for_case(case_name)) {
      if (e.name != "cohesion") continue;
      const double gamma = e.parameters.at(0).upper;
      const double weights = case_name == "pellet_compression" ? 5.0 : 1.0;
      CHECK(1.5 * std::numbers::pi * gamma * 0.5 * r == Approx(weights * weight).epsilon(1e-12));
    }
  }
}

TEST_CASE("A coarse-grained drum's cohesion bound follows its simulated particle: s^2 times the original's for SCG") {
  double original = 0.0, coarse = 0.0;
  for (const EffectInfo& e : effects_for_case("rotary_drum"))
    if (e.name == "cohesion") original = e.parameters.at(0).upper;
  for (const EffectInfo& e : effects_for_case("rotary_drum", {{"drum", {{"scale_factor", 4.0}}}}))
    if (e.name == "cohesion") coarse = e.parameters.at(0).upper;
  CHECK(coarse == Approx(16.0 * original).epsilon(1e-12));
  // A whole case document gives the same bounds as the built-in name with the same overrides.
  json document = read_case_json(std::string(DEMFIT_SOURCE_DIR) + "/cases/rotary_drum.json");
  document.merge_patch({{"drum", {{"scale_factor", 4.0}}}});
  for (const EffectInfo& e : effects_for_case(parse_case(document)))
    if (e.name == "cohesion") CHECK(e.parameters.at(0).upper == coarse);
}

TEST_CASE("A polydisperse coarse-grained drum fill settles and rotates (its densification once never ended)") {
  // The s = 4 drum with a 5 % radius spread: the refriction phase of the densification ended a
  // round-off short of its end time, which no step covered (dem_core settle loop); ctest's
  // timeout fails this test if that comes back.
  json document = read_case_json(std::string(DEMFIT_SOURCE_DIR) + "/cases/rotary_drum.json");
  document.merge_patch(
      {{"drum", {{"scale_factor", 4.0}, {"duration", 0.05}, {"surface_window", 0.0}, {"surface_snapshots", 1}}}});
  const CaseResult result = run_case(parse_case(document), {{"radius_spread", 0.05}}, test_options());
  CHECK(result.curves.at("free_surface").x.size() >= 2);
}

TEST_CASE("Cache keys of cases without effects do not mention the effects, and do with an effect on") {
  CaseSpec spec = tiny_case("pellet_compression");
  json key = to_key_json(spec);
  CHECK_FALSE(key.at("particle").contains("radius_spread"));
  for (const char* name : {"unloading_stiffness_ratio", "surface_energy", "stiffness_exponent"})
    CHECK_FALSE(key.at("contact").contains(name));
  json full = to_json(spec);  // the resolved case lists every field
  CHECK(full.at("particle").contains("radius_spread"));
  CHECK(full.at("contact").contains("surface_energy"));
  spec.material.radius_spread = 0.1;
  spec.contact.surface_energy = 0.2;
  key = to_key_json(spec);
  CHECK(key.at("particle").at("radius_spread") == 0.1);
  CHECK(key.at("contact").at("surface_energy") == 0.2);
}

TEST_CASE("Pellet case: each effect's upper bound changes the curves") { check_effects_on_case("pellet_compression"); }

TEST_CASE("Drum case: each effect's upper bound changes the curves") { check_effects_on_case("rotary_drum"); }
