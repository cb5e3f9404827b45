// A study's variable bounds are checked against the parameter descriptors of its model
// before anything runs or is stored.
#include <catch2/catch.hpp>

#include <atomic>

#include "demfit/identify/analytic_model.hpp"
#include "demfit/identify/experiments.hpp"
#include "demfit/identify/study.hpp"
#include "test_helpers.hpp"

using namespace demfit::identify;

namespace {

// The analytic model declaring that its amplitude must lie in (0, amplitude_max] and its rate in
// [1, 10], its slope in [0, 1].
class BoundedAnalyticModel final : public Model {
 public:
  explicit BoundedAnalyticModel(double amplitude_max = 2.0) : amplitude_max_(amplitude_max) {}
  std::vector<ParameterDescriptor> parameters() const override {
    return {{"amplitude", "-", {0.0, amplitude_max_, true, false}, 1.0, std::nullopt, ""},
            {"rate", "1/s", {1.0, 10.0}, 3.0, std::nullopt, ""},
            {"slope", "-", {0.0, 1.0}, 0.5, std::nullopt, ""}};
  }
  ParameterSet default_parameters() const override { return inner_.default_parameters(); }
  CurveSet evaluate(const ParameterSet& p, const EvaluationContext& c) const override { return inner_.evaluate(p, c); }

 private:
  double amplitude_max_;
  AnalyticCurveModel inner_;
};

// The analytic study as two experiments "wide" and "narrow" on the same target.
StudySpec two_experiment_study(const nlohmann::json& narrow_fixed = nlohmann::json::object()) {
  nlohmann::json single = test::analytic_study(0.0, 1);
  nlohmann::json study = single;
  study.erase("model");
  study.erase("targets");
  nlohmann::json narrow = {{"name", "narrow"}, {"model", {{"case", "analytic"}}}, {"targets", single["targets"]}};
  if (!narrow_fixed.empty()) narrow["model"]["fixed_parameters"] = narrow_fixed;
  study["experiments"] = {{{"name", "wide"}, {"model", {{"case", "analytic"}}}, {"targets", single["targets"]}},
                          narrow};
  return parse_study(study, ".");
}

ExperimentSetModel two_models(const StudySpec& spec) {
  std::vector<std::unique_ptr<Model>> models;
  models.push_back(std::make_unique<BoundedAnalyticModel>(3.0));
  models.push_back(std::make_unique<BoundedAnalyticModel>(1.8));
  return ExperimentSetModel(spec, std::move(models));
}

using test::quiet_options;

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

TEST_CASE("A bound on an open end of the valid range is refused, one just inside it is accepted",
          "[identify][parameters]") {
  nlohmann::json study = test::analytic_study(0.0, 1);
  study["variables"][0]["lower"] = 0.0;  // amplitude's lower end 0 is open
  study["variables"][0]["initial"] = 0.5;
  CHECK_THROWS_WITH(
      run_study(parse_study(study, "."), BoundedAnalyticModel(), quiet_options(test::fresh_dir("bounds_open"))),
      Catch::Contains("(0, 2]"));
  study["variables"][0]["lower"] = 1e-9;
  study["variables"][0]["upper"] = 2.0;  // the closed upper end itself is valid
  CHECK_NOTHROW(
      run_study(parse_study(study, "."), BoundedAnalyticModel(), quiet_options(test::fresh_dir("bounds_inside"))));
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

TEST_CASE("A parameter range says which values it contains and prints its open and closed ends",
          "[identify][parameters]") {
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

TEST_CASE("Several experiments accept a variable only in the intersection of their models' valid ranges",
          "[identify][parameters][experiments]") {
  const StudySpec spec = two_experiment_study();
  const ExperimentSetModel model = two_models(spec);
  const std::vector<ParameterDescriptor> descriptors = model.parameters();
  const ParameterDescriptor* amplitude = find_descriptor(descriptors, "amplitude");
  REQUIRE(amplitude != nullptr);
  CHECK(amplitude->valid.to_string() == "(0, 1.8]");
  const auto dir = test::fresh_dir("bounds_experiments");
  // The study's amplitude bounds [0.5, 2] lie inside "wide" (0, 3] but not inside "narrow" (0, 1.8].
  CHECK_THROWS_WITH(run_study(spec, model, quiet_options(dir)), Catch::Contains("(0, 1.8]"));
  CHECK_FALSE(std::filesystem::exists(dir / "study.db"));
}

TEST_CASE("An experiment's fixed parameter outside its model's valid range is refused naming the experiment",
          "[identify][parameters][experiments]") {
  StudySpec spec = two_experiment_study({{"slope", 1.5}});
  spec.variables[0].upper = 1.5;  // amplitude inside both models
  const ExperimentSetModel model = two_models(spec);
  const auto dir = test::fresh_dir("bounds_experiment_fixed");
  CHECK_THROWS_WITH(run_study(spec, model, quiet_options(dir)),
                    Catch::Contains("experiments[1].model.fixed_parameters.slope = 1.5") && Catch::Contains("[0, 1]"));
  CHECK_FALSE(std::filesystem::exists(dir / "study.db"));
}

namespace {

// The analytic model counting its evaluations (to show a check ran before any of them).
class CountingAnalyticModel final : public Model {
 public:
  std::vector<ParameterDescriptor> parameters() const override { return inner_.parameters(); }
  std::vector<CurveDescriptor> curves() const override { return inner_.curves(); }
  ParameterSet default_parameters() const override { return inner_.default_parameters(); }
  CurveSet evaluate(const ParameterSet& p, const EvaluationContext& c) const override {
    ++evaluations;
    return inner_.evaluate(p, c);
  }
  mutable std::atomic<int> evaluations{0};

 private:
  AnalyticCurveModel inner_;
};

}  // namespace

TEST_CASE("A target naming a curve the model does not declare is refused when the study is loaded, before any run",
          "[identify][curves]") {
  nlohmann::json study = test::analytic_study(0.0, 1);
  study["targets"][0]["curve"] = "respnse";
  const auto dir = test::fresh_dir("curve_undeclared");
  const CountingAnalyticModel model;
  CHECK_THROWS_WITH(run_study(parse_study(study, "."), model, quiet_options(dir)),
                    Catch::Contains("targets[0].curve: 'respnse'") && Catch::Contains("it produces: loop, response"));
  CHECK(model.evaluations == 0);
  CHECK_FALSE(std::filesystem::exists(dir / "study.db"));
}

// The analytic curves with units on "response" (the analytic model's own are dimensionless,
// "x_1", which convert from anything).
class AnalyticModelWithUnits final : public Model {
 public:
  std::vector<ParameterDescriptor> parameters() const override { return inner_.parameters(); }
  std::vector<CurveDescriptor> curves() const override {
    return {{"response", "volume_cm3", "pressure_MPa"}, {"loop", "x_1", "y_1"}};
  }
  ParameterSet default_parameters() const override { return inner_.default_parameters(); }
  CurveSet evaluate(const ParameterSet& p, const EvaluationContext& c) const override { return inner_.evaluate(p, c); }

 private:
  AnalyticCurveModel inner_;
};

TEST_CASE("A target whose column unit is of another quantity than the declared curve's is refused at load",
          "[identify][curves]") {
  StudySpec spec = parse_study(test::analytic_study(0.0, 1), ".");
  spec.targets[0].data.x_label = "time_s";
  const auto dir = test::fresh_dir("curve_units");
  CHECK_THROWS_WITH(run_study(spec, AnalyticModelWithUnits(), quiet_options(dir)),
                    Catch::Contains("targets[0].x_column") && Catch::Contains("time"));
  CHECK_FALSE(std::filesystem::exists(dir / "study.db"));
  spec.targets[0].data.x_label = "volume_mm3";  // same quantity: accepted (converted later)
  CHECK_NOTHROW(run_study(spec, AnalyticModelWithUnits(), quiet_options(test::fresh_dir("curve_units_ok"))));
}

TEST_CASE("Several experiments declare their curves under the experiment's name", "[identify][curves][experiments]") {
  const StudySpec spec = two_experiment_study();
  const ExperimentSetModel model = two_models(spec);
  // BoundedAnalyticModel declares none, so the set declares none (checked at the initial point).
  CHECK(model.curves().empty());
  std::vector<std::unique_ptr<Model>> declaring;
  declaring.push_back(std::make_unique<AnalyticCurveModel>());
  declaring.push_back(std::make_unique<AnalyticCurveModel>());
  const ExperimentSetModel set(spec, std::move(declaring));
  std::vector<std::string> names;
  for (const auto& c : set.curves()) names.push_back(c.name);
  CHECK(names == std::vector<std::string>{"wide/response", "wide/loop", "narrow/response", "narrow/loop"});
}
