// make_model: built-in cases equal the shipped files, overrides are checked, and a short
// identification on a coarse pellet variant recovers its generating values.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdlib>
#include <string>

#include "builtin_cases.hpp"
#include "demfit/cases/case_spec.hpp"
#include "demfit/cases/model_factory.hpp"
#include "demfit/identify/study.hpp"
#include "demfit/identify/study_spec.hpp"

using namespace demfit;
using nlohmann::json;

TEST_CASE("Built-in cases are the shipped case files") {
  CHECK(json::parse(cases::detail::kBuiltinPelletCompression) ==
        cases::read_case_json(std::string(DEMFIT_SOURCE_DIR) + "/cases/pellet_compression.json"));
  CHECK(json::parse(cases::detail::kBuiltinRotaryDrum) ==
        cases::read_case_json(std::string(DEMFIT_SOURCE_DIR) + "/cases/rotary_drum.json"));
}

TEST_CASE(
    "A case model exposes the twelve contact parameters, six effect parameters, restitution and two fill amounts with "
    "the case's values as defaults") {
  const auto model = cases::make_model("pellet_compression", json::object(), DEMFIT_SOURCE_DIR);
  CHECK(model->parameter_names().size() == 21);
  CHECK(model->default_parameters().size() == 16);  // LS-DYNA pellet: no restitution, no drum fill
  CHECK(model->default_parameters().at("unloading_stiffness_ratio") == 1.0);  // effects off by default
  CHECK(model->default_parameters().at("surface_energy") == 0.0);
  CHECK(model->default_parameters().at("normk") == 0.875046);
  CHECK(model->default_parameters().at("wall_damp") == 0.5);
  const auto drum =
      cases::make_model("cases/rotary_drum.json", json{{"drum", {{"scale_factor", 4}}}}, DEMFIT_SOURCE_DIR);
  CHECK(drum->default_parameters().at("sheark") == 0.0029);
}

TEST_CASE("Unknown override keys and unknown references are errors naming them") {
  CHECK_THROWS_WITH(cases::make_model("pellet_compression", json{{"pellet", {{"speed", 1}}}}, "."),
                    Catch::Contains("pellet.speed"));
  CHECK_THROWS_WITH(cases::make_model("no_such_case.json", json::object(), "."), Catch::Contains("no_such_case.json"));
  CHECK_THROWS_WITH(cases::make_model("analytic", json{{"pointz", 3}}, "."), Catch::Contains("pointz"));
}

TEST_CASE("A short Table 1 identification on a coarse pellet variant recovers NORMK", "[slow]") {
  setenv("DEMFIT_CACHE_DIR", (std::string(DEMFIT_BINARY_DIR) + "/test_cache").c_str(), 1);
  // Coarse, fast variant: 150 pellets in a 24 mm cylinder, loaded to 1 MPa.
  const json overrides = {{"pellet",
                           {{"particle_count", 150},
                            {"container_diameter", 0.024},
                            {"settle_time", 0.3},
                            {"max_pressure", 1.0e6},
                            {"max_travel", 0.006},
                            {"curve_points", 30}}}};
  const auto model = cases::make_model("pellet_compression", overrides, DEMFIT_SOURCE_DIR);
  const double true_normk = 0.5, true_sheark = 0.3;
  const identify::CurveSet measured = model->evaluate({{"normk", true_normk}, {"sheark", true_sheark}}, {});
  const identify::Curve& target = measured.at("pressure_volume");
  const json study = {
      {"demfit_study_version", 1},
      {"model", {{"case", "pellet_compression"}, {"overrides", overrides}}},
      {"variables",
       json::array({{{"name", "normk"}, {"lower", 0.1}, {"upper", 2.0}, {"initial", 0.2}, {"log_scale", true}},
                    {{"name", "sheark"}, {"lower", 0.1}, {"upper", 0.6}, {"initial", 2.0 / 7.0}}})},
      {"targets", json::array({{{"curve", "pressure_volume"},
                                {"x_column", "volume_cm3"},
                                {"y_column", "pressure_MPa"},
                                {"x", target.x},
                                {"y", target.y}}})},
      {"sampling", {{"points_per_iteration", 6}}},
      {"stopping", {{"max_iterations", 5}}}};
  const identify::StudySpec spec = identify::parse_study(study, DEMFIT_BINARY_DIR);
  identify::RunOptions options;
  options.jobs = 2;
  options.output_dir = std::string(DEMFIT_BINARY_DIR) + "/test_cases_table1_study";
  options.plots = false;
  options.progress = false;
  std::filesystem::remove_all(options.output_dir);
  const identify::StudyResult result = identify::run_study(spec, *model, options);
  // Target from the same model: NORMK within 3 %. SHEARK is not asserted: a different SHEARK
  // changes the particle trajectories (a ~1 % RMS "numerical noise" on the curve, measured:
  // objective 1e-4 at the best run) more than it changes the curve's trend, so the compression
  // curve does not pin it down (docs/cases.md).
  INFO("normk " << result.best.at("normk") << " sheark " << result.best.at("sheark") << " objective "
                << result.best_objective << " runs " << result.runs);
  CHECK(result.best.at("normk") == Approx(true_normk).epsilon(0.03));
  CHECK(result.runs <= 31);
}

TEST_CASE("The GranuDrum case model exposes the Hertz parameters and its particle count, and reads its size classes") {
  const auto model = cases::make_model("cases/granudrum_mcc.json", json::object(), DEMFIT_SOURCE_DIR);
  const auto defaults = model->default_parameters();
  CHECK(defaults.at("particle_count") == 29185.0);
  CHECK(defaults.at("frics") == 0.5);
  CHECK(defaults.at("fricr") == 0.2);
  CHECK(defaults.at("restitution") == 0.3);
  CHECK(defaults.count("normk") == 0);
  const cases::CaseSpec spec = cases::resolve_case("cases/granudrum_mcc.json", json::object(), DEMFIT_SOURCE_DIR);
  CHECK(spec.drum.size_distribution.diameters.size() == 10);
  CHECK(spec.wall.frics == spec.contact.frics);
}

TEST_CASE("The GranuDrum case can take the measured Solidsizer sizes instead of the classes") {
  const json csv{{"drum",
                  {{"size_distribution",
                    {{"csv", "../data/granudrum_mcc/solidsizer_mcc.csv"},
                     {"column", "xFmax"},
                     {"unit", "um"},
                     {"diameter_kind", "max_feret"},
                     {"min_size", 1050.0},
                     {"max_size", 1500.0},
                     {"radius", nullptr},
                     {"number_fraction", nullptr}}}}}};
  const cases::CaseSpec spec = cases::resolve_case("cases/granudrum_mcc.json", csv, DEMFIT_SOURCE_DIR);
  CHECK(spec.drum.size_distribution.diameters.size() > 5000);  // of the 7,685 measured sizes
  CHECK(spec.drum.size_distribution.min_diameter() >= 1.05e-3);
  CHECK(spec.drum.size_distribution.max_diameter() <= 1.5e-3);
}
