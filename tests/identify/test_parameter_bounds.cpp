// A study's variable bounds are checked against the parameter descriptors of its model
// (issue 12 item 1) before anything runs or is stored.
#include <catch2/catch.hpp>

#include "demfit/identify/analytic_model.hpp"
#include "demfit/identify/study.hpp"
#include "test_helpers.hpp"

using namespace demfit::identify;

namespace {

// The analytic model declaring that its amplitude must lie in (0, 2] and its rate in [1, 10].
class BoundedAnalyticModel final : public Model {
 public:
  std::vector<std::string> parameter_names() const override { return inner_.parameter_names(); }
  std::vector<ParameterDescriptor> parameters() const override {
    return {{"amplitude", "-", {0.0, 2.0, true, false}, 1.0, std::nullopt, ""},
            {"rate", "1/s", {1.0, 10.0}, 3.0, std::nullopt, ""},
            {"slope", "-", {}, 0.5, std::nullopt, ""}};
  }
  ParameterSet default_parameters() const override { return inner_.default_parameters(); }
  CurveSet evaluate(const ParameterSet& p, const EvaluationContext& c) const override { return inner_.evaluate(p, c); }

 private:
  AnalyticCurveModel inner_;
};

RunOptions quiet_options(const std::filesystem::path& dir) {
  RunOptions options;
  options.output_dir = dir;
  options.plots = false;
  options.progress = false;
  return options;
}

}  // namespace

TEST_CASE("A study whose variable bounds leave the model's valid range is refused before the store is created",
          "[identify][parameters]") {
  const auto dir = test::fresh_dir("bounds_refused");
  nlohmann::json study = test::analytic_study(0.0, 2);
  study["variables"][0]["upper"] = 2.5;  // amplitude: valid (0, 2]
  const StudySpec spec = parse_study(study, ".");
  try {
    run_study(spec, BoundedAnalyticModel(), quiet_options(dir));
    FAIL("the study ran");
  } catch (const std::runtime_error& e) {
    const std::string message = e.what();
    CHECK(message.find("'amplitude'") != std::string::npos);
    CHECK(message.find("[0.5, 2.5]") != std::string::npos);
    CHECK(message.find("(0, 2]") != std::string::npos);
    CHECK(message.find('\n') == std::string::npos);
  }
  CHECK_FALSE(std::filesystem::exists(dir / "study.db"));
}

TEST_CASE("A bound on an open end of the valid range is refused, one just inside it is accepted", "[identify][parameters]") {
  nlohmann::json study = test::analytic_study(0.0, 1);
  study["variables"][0]["lower"] = 0.0;  // amplitude's lower end 0 is open
  study["variables"][0]["initial"] = 0.5;
  CHECK_THROWS_WITH(run_study(parse_study(study, "."), BoundedAnalyticModel(), quiet_options(test::fresh_dir("bounds_open"))),
                    Catch::Contains("(0, 2]"));
  study["variables"][0]["lower"] = 1e-9;
  study["variables"][0]["upper"] = 2.0;  // the closed upper end itself is valid
  CHECK_NOTHROW(run_study(parse_study(study, "."), BoundedAnalyticModel(), quiet_options(test::fresh_dir("bounds_inside"))));
}

TEST_CASE("A fixed parameter value outside the model's valid range is refused naming it", "[identify][parameters]") {
  nlohmann::json study = test::analytic_study(0.0, 1);
  study["model"]["fixed_parameters"] = {{"slope", 0.5}};
  CHECK_NOTHROW(run_study(parse_study(study, "."), BoundedAnalyticModel(), quiet_options(test::fresh_dir("fixed_ok"))));
  nlohmann::json bad = test::analytic_study(0.0, 1);
  bad["variables"].erase(1);
  bad["model"]["fixed_parameters"] = {{"rate", 20.0}};
  const auto dir = test::fresh_dir("fixed_refused");
  CHECK_THROWS_WITH(run_study(parse_study(bad, "."), BoundedAnalyticModel(), quiet_options(dir)),
                    Catch::Contains("fixed_parameters.rate = 20") && Catch::Contains("[1, 10]"));
  CHECK_FALSE(std::filesystem::exists(dir / "study.db"));
}

TEST_CASE("A parameter range says which values it contains and prints its open and closed ends", "[identify][parameters]") {
  const ParameterRange damping{0.0, 1.0, false, true};
  CHECK(damping.contains(0.0));
  CHECK(damping.contains(0.999));
  CHECK_FALSE(damping.contains(1.0));
  CHECK_FALSE(damping.contains(-1e-12));
  CHECK_FALSE(damping.contains(std::nan("")));
  CHECK(damping.to_string() == "[0, 1)");
  const ParameterRange positive{0.0, std::numeric_limits<double>::infinity(), true, true};
  CHECK(positive.to_string() == "(0, inf)");
  CHECK(positive.contains_interval(1e-3, 1e9));
  CHECK_FALSE(positive.contains_interval(0.0, 1.0));
  CHECK_FALSE(positive.contains_interval(2.0, 1.0));
}
