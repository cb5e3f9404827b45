#include <catch2/catch.hpp>

#include <fstream>

#include "demfit/identify/study_spec.hpp"
#include "test_helpers.hpp"

using namespace demfit::identify;

namespace {
std::string parse_error(const nlohmann::json& study) {
  try {
    parse_study(study, ".");
  } catch (const std::runtime_error& e) { return e.what(); }
  return "no error";
}
}  // namespace

TEST_CASE("A valid study parses with the documented defaults", "[identify][study]") {
  const StudySpec spec = parse_study(test::analytic_study(), ".");
  CHECK(spec.variables.size() == 2);
  CHECK(spec.variables[1].log_scale);
  CHECK(spec.points_per_iteration == 6);  // ceil(1.5 * 3 + 1) = 6
  CHECK(spec.strategy == SamplingStrategy::srsm);
  CHECK(spec.gamma_pan == 1.0);
  CHECK(spec.gamma_osc == 0.6);
  CHECK(spec.eta == 0.6);
  CHECK(spec.targets[0].data.x.size() == 41);
  CHECK(spec.seed == 11);
}

TEST_CASE("Default points per iteration follow 1.5(n+1)+1 rounded up (16 for nine variables)", "[identify][study]") {
  CHECK(default_points_per_iteration(9) == 16);
  CHECK(default_points_per_iteration(2) == 6);
  CHECK(default_points_per_iteration(1) == 4);
  CHECK(default_points_per_iteration(3) == 7);
}

TEST_CASE("The resolved study JSON parses back to the same study and hash", "[identify][study]") {
  const StudySpec spec = parse_study(test::analytic_study(), ".");
  const StudySpec again = parse_study(to_json(spec), ".");
  CHECK(study_hash(spec) == study_hash(again));
  CHECK(to_json(spec) == to_json(again));
  auto changed = test::analytic_study();
  changed["variables"][0]["upper"] = 2.5;
  CHECK(study_hash(parse_study(changed, ".")) != study_hash(spec));
  auto longer = test::analytic_study();
  longer["stopping"]["max_iterations"] = 40;  // continuing a study with more iterations is allowed
  CHECK(study_hash(parse_study(longer, ".")) == study_hash(spec));
}

TEST_CASE("Malformed study files give one-line errors naming the field", "[identify][study]") {
  auto unknown = test::analytic_study();
  unknown["variables"][0]["lowr"] = 1;
  CHECK_THAT(parse_error(unknown), Catch::Contains("variables[0].lowr") && Catch::Contains("unknown key"));
  auto misspelt = test::analytic_study();
  misspelt["variables"][0].erase("lower");
  misspelt["variables"][0]["lowr"] = 0.5;
  CHECK_THAT(parse_error(misspelt), Catch::Contains("variables[0].lowr: unknown key; did you mean \"lower\"?"));
  auto top = test::analytic_study();
  top["sead"] = 1;
  CHECK_THAT(parse_error(top), Catch::Contains("study: sead: unknown key"));
  auto type = test::analytic_study();
  type["variables"][1]["upper"] = "8";
  CHECK_THAT(parse_error(type), Catch::Contains("variables[1].upper: expected a number"));
  auto bounds = test::analytic_study();
  bounds["variables"][0]["upper"] = 0.1;
  CHECK_THAT(parse_error(bounds), Catch::Contains("variables[0].upper"));
  auto version = test::analytic_study();
  version.erase("demfit_study_version");
  CHECK_THAT(parse_error(version), Catch::Contains("demfit_study_version"));
  auto metric = test::analytic_study();
  metric["targets"][0]["metric"] = "rms";
  CHECK_THAT(parse_error(metric), Catch::Contains("targets[0].metric"));
  auto strategy = test::analytic_study();
  strategy["sampling"] = {{"strategy", "random"}};
  CHECK_THAT(parse_error(strategy), Catch::Contains("sampling.strategy"));
  auto duplicate = test::analytic_study();
  duplicate["variables"][1]["name"] = "amplitude";
  CHECK_THAT(parse_error(duplicate), Catch::Contains("appears twice"));
  for (const auto& message : {parse_error(unknown), parse_error(type), parse_error(metric)})
    CHECK(message.find('\n') == std::string::npos);
}

TEST_CASE("An interval check is parsed with its defaults and refused out of range naming the field",
          "[identify][study]") {
  auto on = test::analytic_study();
  on["interval_check"] = nlohmann::json::object();
  const StudySpec spec = parse_study(on, ".");
  CHECK(spec.interval_check.max_steps == 6);
  CHECK(spec.interval_check.replicates == 2);
  CHECK(spec.interval_check.first_step == 0.02);
  CHECK(spec.interval_check.all_variables);
  CHECK(parse_study(test::analytic_study(), ".").interval_check.max_steps == 0);  // off unless asked for
  // Added after the loop, so a finished study can be resumed with it: not part of the hash.
  CHECK(study_hash(spec) == study_hash(parse_study(test::analytic_study(), ".")));
  CHECK(to_json(parse_study(to_json(spec), ".")) == to_json(spec));
  auto steps = test::analytic_study();
  steps["interval_check"] = {{"max_steps", -1}};
  CHECK_THAT(parse_error(steps), Catch::Contains("interval_check.max_steps"));
  auto step = test::analytic_study();
  step["interval_check"] = {{"first_step", 0.0}};
  CHECK_THAT(parse_error(step), Catch::Contains("interval_check.first_step"));
  auto unknown = test::analytic_study();
  unknown["interval_check"] = {{"replicate", 3}};
  CHECK_THAT(parse_error(unknown), Catch::Contains("interval_check.replicate") && Catch::Contains("unknown key"));
}

TEST_CASE("A study file reads its target CSV relative to its own folder", "[identify][study]") {
  const auto dir = test::fresh_dir("study_file");
  std::ofstream(dir / "target.csv") << "volume_cm3,pressure_MPa\n1,0.5\n2,1.5\n3,2.5\n";
  nlohmann::json study = test::analytic_study();
  study["targets"][0] = {{"curve", "response"},
                         {"csv", "target.csv"},
                         {"x_column", "volume_cm3"},
                         {"y_column", "pressure_MPa"},
                         {"weight", 2.0}};
  std::ofstream(dir / "study.json") << study.dump(2);
  const StudySpec spec = load_study_file(dir / "study.json");
  CHECK(spec.targets[0].data.y == std::vector<double>{0.5, 1.5, 2.5});
  CHECK(spec.targets[0].weight == 2.0);
  std::ofstream(dir / "broken.json") << "{ \"demfit_study_version\": 1, ";
  CHECK_THROWS_WITH(load_study_file(dir / "broken.json"), Catch::Contains("not valid JSON"));
}
