// The Hertz–Mindlin law's options in case files: SJKR cohesion (contact.cohesion_energy_density,
// contact.cohesion_model) and the rolling model (contact.rolling_model), their refusals, their
// cache keys, and the effect candidates of a Hertz case.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <string>

#include "../../cases/src/dem_setup.hpp"
#include "case_test_options.hpp"
#include "demfit/cases/case_spec.hpp"
#include "demfit/cases/effect_catalogue.hpp"
#include "demfit/cases/parameter_table.hpp"
#include "demfit/dem_core/hertz_cohesion.hpp"

using namespace demfit;
using namespace demfit::cases;
using nlohmann::json;

namespace {

json hertz_drum_document() {
  return json{{"case", "rotary_drum"},
              {"particle", {{"radius", 0.001}, {"density", 2500.0}, {"youngs_modulus", 5e6}, {"poisson_ratio", 0.3}}},
              {"contact", {{"law", "hertz_mindlin"}, {"restitution", 0.5}, {"frics", 0.4}, {"fricr", 0.1}}},
              {"wall_contact", {{"youngs_modulus", 5e6}, {"poisson_ratio", 0.3}, {"friction_as_particles", true}}},
              {"drum", {{"diameter", 0.1}, {"length", 0.02}}}};
}

json lsdyna_drum_document() {
  json document = hertz_drum_document();
  document["contact"] = {{"normk", 0.01}, {"frics", 0.4}};
  document["wall_contact"] = {{"frics", 0.3}};
  document["particle"]["youngs_modulus"] = 5e6;
  return document;
}

}  // namespace

TEST_CASE("A Hertz case file selects SJKR cohesion and the epsd2 rolling spring and writes them back",
          "[cases][hertz]") {
  json document = hertz_drum_document();
  document["contact"]["cohesion_energy_density"] = 2.0e4;
  document["contact"]["cohesion_model"] = "sjkr2";
  document["contact"]["rolling_model"] = "epsd2";
  const CaseSpec spec = parse_case(document);
  CHECK(spec.contact.cohesion_energy_density == 2.0e4);
  CHECK(spec.contact.cohesion_model == dem_core::CohesionModel::sjkr2);
  CHECK(spec.contact.rolling_model == dem_core::RollingModel::elastic_plastic);
  const json written = to_json(spec);
  CHECK(written["contact"]["cohesion_model"] == "sjkr2");
  CHECK(written["contact"]["rolling_model"] == "epsd2");
  const CaseSpec again = parse_case(written);
  CHECK(again.contact.cohesion_energy_density == 2.0e4);
  CHECK(again.contact.rolling_model == dem_core::RollingModel::elastic_plastic);
  // The simulation settings carry them to dem_core.
  CHECK(detail::simulation_settings(spec).contact.cohesion_model == dem_core::CohesionModel::sjkr2);
}

TEST_CASE("A Hertz case at the default options keeps its cache key (no cohesion or model keys)", "[cases][hertz]") {
  const json key = to_key_json(parse_case(hertz_drum_document()));
  for (const char* k : {"cohesion_energy_density", "cohesion_model", "rolling_model"}) {
    INFO(k);
    CHECK_FALSE(key["contact"].contains(k));
  }
  json with = hertz_drum_document();
  with["contact"]["rolling_model"] = "epsd2";
  CHECK(to_key_json(parse_case(with))["contact"]["rolling_model"] == "epsd2");
}

TEST_CASE("A negative or unknown Hertz option is refused naming its field", "[cases][hertz]") {
  json document = hertz_drum_document();
  document["contact"]["cohesion_energy_density"] = -1.0;
  CHECK_THAT(test::case_refusal(document), Catch::Contains("contact.cohesion_energy_density"));
  document = hertz_drum_document();
  document["contact"]["cohesion_model"] = "jkr";
  CHECK_THAT(test::case_refusal(document), Catch::Contains("'contact.cohesion_model' must be \"sjkr\" or \"sjkr2\""));
  document = hertz_drum_document();
  document["contact"]["rolling_model"] = "epsd";
  CHECK_THAT(test::case_refusal(document), Catch::Contains("'contact.rolling_model' must be \"cdt\" or \"epsd2\""));
}

TEST_CASE("An LS-DYNA case file with epsd2 or SJKR cohesion is refused with the fix; cdt is accepted",
          "[cases][hertz]") {
  json document = lsdyna_drum_document();
  REQUIRE(test::case_refusal(document).empty());
  document["contact"]["rolling_model"] = "epsd2";
  CHECK_THAT(test::case_refusal(document),
             Catch::Contains("'contact.rolling_model'") && Catch::Contains("hertz_mindlin"));
  document["contact"]["rolling_model"] = "cdt";
  CHECK(test::case_refusal(document).empty());
  document["contact"]["cohesion_energy_density"] = 100.0;
  CHECK_THAT(test::case_refusal(document),
             Catch::Contains("'contact.cohesion_energy_density'") && Catch::Contains("surface_energy"));
  // And as an identified parameter of an LS-DYNA case.
  const CaseSpec lsdyna = parse_case(lsdyna_drum_document());
  CHECK_THROWS_WITH(detail::with_parameters(lsdyna, {{"cohesion_energy_density", 100.0}}),
                    Catch::Contains("hertz_mindlin"));
}

TEST_CASE("A Hertz drum's effect candidates are the Hertz law's own, cohesion inside its time-step limit",
          "[cases][hertz][effects]") {
  const CaseSpec tied = parse_case(hertz_drum_document());
  auto names = [](const std::vector<EffectInfo>& effects) {
    std::vector<std::string> out;
    for (const EffectInfo& e : effects) out.push_back(e.name);
    return out;
  };
  const auto effects = effects_for_case(tied);
  // Wall friction released from the tie to the particles'; restitution from the case's 0.5.
  CHECK(names(effects) == std::vector<std::string>{"cohesion", "wall_friction", "rolling_resistance", "restitution"});
  CHECK(effects[1].parameters[0].name == "wall_friction_ratio");
  for (const EffectInfo& e : effects)
    for (const auto& p : e.parameters) {
      INFO(e.name << ": " << p.name);
      CHECK(find_parameter(p.name)->applies_to(tied.law));
      // Every candidate's upper end is a case the Hertz law accepts.
      CHECK_NOTHROW(detail::with_parameters(tied, {{p.name, p.upper}}));
    }
  // E = 5 MPa, nu = 0.3, elastic wall of the same material: the sjkr limit is the wall's,
  // 0.0487 E* with E* = E/(2(1 - nu^2)) = 2.75 MPa, 1.34e5 J/m^3 > 1e5: the full range.
  CHECK(effects[0].parameters[0].upper == 1.0e5);
  // sjkr2 halves the limit (6.5e4 J/m^3 on the wall): the range stops below it.
  json sjkr2 = hertz_drum_document();
  sjkr2["contact"]["cohesion_model"] = "sjkr2";
  const double e_star = 5e6 / (2.0 * (1.0 - 0.09));
  const double wall_limit = dem_core::hertz_cohesion_limit(e_star, dem_core::CohesionModel::sjkr2, true);
  CHECK(effects_for_case(parse_case(sjkr2))[0].parameters[0].upper == Approx(0.99 * wall_limit));
  CHECK(wall_limit == Approx(0.0237254 * e_star).epsilon(1e-5));
  // Untied wall friction is a candidate as wall FRICS itself.
  json untied = hertz_drum_document();
  untied["wall_contact"].erase("friction_as_particles");
  untied["wall_contact"]["frics"] = 0.0;
  const auto untied_effects = effects_for_case(parse_case(untied));
  CHECK(names(untied_effects) ==
        std::vector<std::string>{"cohesion", "wall_friction", "rolling_resistance", "restitution"});
  CHECK(untied_effects[1].parameters[0].name == "wall_frics");
  // The released restitution is off at the case's value, inside its fitting range.
  const auto& e = effects[3].parameters[0];
  CHECK(e.off_value == 0.5);
  CHECK(e.lower == 0.05);
  CHECK(e.upper == 0.95);
}

TEST_CASE("A tied wall friction is released by wall_friction_ratio: wall FRICS = ratio x particle FRICS",
          "[cases][hertz]") {
  const CaseSpec tied = parse_case(hertz_drum_document());  // frics 0.4, tied
  CHECK(tied.wall.frics == 0.4);                            // the ratio 1 is the tie itself
  const CaseSpec half = detail::with_parameters(tied, {{"wall_friction_ratio", 0.5}});
  CHECK(half.wall.frics == Approx(0.2).epsilon(1e-15));
  CHECK(half.wall.fricd == tied.contact.fricr);  // rolling stays tied
  // The ratio is kept while the particles' friction varies (a study with frics as a variable).
  CHECK(detail::with_parameters(tied, {{"wall_friction_ratio", 0.5}, {"frics", 0.6}}).wall.frics ==
        Approx(0.3).epsilon(1e-15));
  // Case file: written back with the tie, and refused without it.
  json document = hertz_drum_document();
  document["wall_contact"]["friction_ratio"] = 0.5;
  const json written = to_json(parse_case(document));
  CHECK(written["wall_contact"]["friction_ratio"] == 0.5);
  CHECK(parse_case(written).wall.frics == Approx(0.2).epsilon(1e-15));
  CHECK_FALSE(to_json(tied)["wall_contact"].contains("friction_ratio"));
  document["wall_contact"].erase("friction_as_particles");
  CHECK_THAT(test::case_refusal(document),
             Catch::Contains("'wall_contact.friction_ratio'") && Catch::Contains("friction_as_particles"));
  // An untied case varies wall_frics itself.
  json untied = hertz_drum_document();
  untied["wall_contact"].erase("friction_as_particles");
  CHECK_THROWS_WITH(detail::with_parameters(parse_case(untied), {{"wall_friction_ratio", 0.5}}),
                    Catch::Contains("vary wall_frics"));
}

TEST_CASE("The shipped GranuDrum case offers cohesion, released wall friction, rolling resistance and released e = 0.3",
          "[cases][hertz][effects]") {
  const CaseSpec spec = parse_case(read_case_json(std::string(DEMFIT_SOURCE_DIR) + "/cases/granudrum_mcc.json"));
  const auto effects = effects_for_case(spec);
  std::vector<std::string> names;
  for (const EffectInfo& e : effects) names.push_back(e.parameters.at(0).name);
  CHECK(names == std::vector<std::string>{"cohesion_energy_density", "wall_friction_ratio", "fricr", "restitution"});
  // E = 5 MPa on an elastic wall of the same material: the full 1e5 J/m^3 range fits the limit.
  CHECK(effects[0].parameters[0].upper == 1.0e5);
  CHECK(effects[1].parameters[0].off_value == 1.0);
  CHECK(effects[3].parameters[0].off_value == 0.3);
  // diagnose keeps a candidate only while its parameter is at its off value in the model: true for
  // cohesion, the wall-friction ratio and the released restitution; the case's rolling friction
  // 0.2 is already part of its base model, so diagnose notes rolling_resistance and leaves it out.
  const auto values = detail::parameters_of(spec);
  for (const std::size_t k : {0u, 1u, 3u}) CHECK(values.at(names[k]) == effects[k].parameters[0].off_value);
  CHECK(values.at("fricr") == 0.2);
}
