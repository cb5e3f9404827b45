#include <catch2/catch.hpp>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <iterator>
#include <random>

#include "demfit/identify/analytic_model.hpp"
#include "demfit/identify/evaluator.hpp"
#include "demfit/identify/report.hpp"
#include "demfit/identify/reported_interval.hpp"
#include "demfit/identify/study.hpp"
#include "demfit/identify/study_store.hpp"
#include "test_helpers.hpp"

using namespace demfit::identify;

namespace {

using test::quiet_options;

// The analytic model, failing (like an unstable simulation) when amplitude > 1.8.
class FailingModel final : public Model {
 public:
  std::vector<ParameterDescriptor> parameters() const override { return inner_.parameters(); }
  ParameterSet default_parameters() const override { return inner_.default_parameters(); }
  CurveSet evaluate(const ParameterSet& p, const EvaluationContext& c) const override {
    if (p.at("amplitude") > fail_above) throw std::runtime_error("unstable: time step too large");
    return inner_.evaluate(p, c);
  }
  double fail_above = 1.8;

 private:
  AnalyticCurveModel inner_;
};

// The analytic model plus a parameter "ignored" that no curve depends on.
class ExtraParameterModel final : public Model {
 public:
  std::vector<ParameterDescriptor> parameters() const override {
    return unbounded_descriptors({"amplitude", "rate", "slope", "ignored"});
  }
  ParameterSet default_parameters() const override {
    auto p = inner_.default_parameters();
    p["ignored"] = 0.5;
    return p;
  }
  CurveSet evaluate(const ParameterSet& p, const EvaluationContext& c) const override {
    auto q = p;
    q.erase("ignored");
    return inner_.evaluate(q, c);
  }

 private:
  AnalyticCurveModel inner_;
};

// The analytic model with DEM-like simulation noise: every parameter set gives a slightly
// different smooth curve (as a different packing history would), sigma = 0.5 % of max|y|. Plus
// "weak", which moves the curve by at most 0.1 % of max|y| over its bounds (below the noise),
// and "ignored", which does nothing.
class NoisySimulationModel final : public Model {
 public:
  std::vector<ParameterDescriptor> parameters() const override {
    return unbounded_descriptors({"amplitude", "rate", "slope", "weak", "ignored"});
  }
  ParameterSet default_parameters() const override {
    auto p = inner_.default_parameters();
    p["weak"] = 0.5;
    p["ignored"] = 0.5;
    return p;
  }
  CurveSet evaluate(const ParameterSet& p, const EvaluationContext& c) const override {
    auto q = p;
    q.erase("weak");
    q.erase("ignored");
    CurveSet curves = inner_.evaluate(q, c);
    Curve& response = curves.at("response");
    // Deterministic in the parameters (same input -> same curve), chaotic between them.
    std::uint64_t seed = 1469598103934665603ull;
    for (const auto& [name, value] : p) seed = (seed ^ std::hash<double>{}(value)) * 1099511628211ull;
    std::mt19937_64 rng(seed);
    std::normal_distribution<double> normal(0.0, 1.0);
    const double g1 = normal(rng), g2 = normal(rng), g3 = normal(rng);
    const double sigma = 0.005 * 1.8;  // max|y| of the target is about 1.8
    for (std::size_t i = 0; i < response.x.size(); ++i) {
      const double x = response.x[i];
      response.y[i] += 0.0018 * (p.at("weak") - 0.5) * x +
                       sigma * (g1 * x + g2 * std::sin(6.283185307179586 * x) + g3 * (2.0 * x * x - 1.0)) / 1.7;
    }
    return curves;
  }

 private:
  AnalyticCurveModel inner_;
};

}  // namespace

TEST_CASE("Identification recovers the analytic parameters to 1e-3 relative without noise", "[identify][loop]") {
  const auto spec = parse_study(test::analytic_study(0.0, 12), ".");
  const auto result = run_study(spec, AnalyticCurveModel(), quiet_options(test::fresh_dir("recover")));
  CHECK(std::abs(result.best.at("amplitude") / 1.3 - 1.0) < 1e-3);
  CHECK(std::abs(result.best.at("rate") / 4.2 - 1.0) < 1e-3);
  CHECK(result.best.at("slope") == 0.5);  // not varied: the model default
  CHECK(result.failed_runs == 0);
  CHECK(result.runs == 12 * spec.points_per_iteration + 1);
  CHECK(result.best_curves.count("response") == 1);
}

TEST_CASE("With 1 % noise the true parameters lie inside the reported confidence intervals", "[identify][loop]") {
  const auto spec = parse_study(test::analytic_study(0.01, 10), ".");
  const auto result = run_study(spec, AnalyticCurveModel(), quiet_options(test::fresh_dir("noise")));
  const double a = result.best.at("amplitude"), r = result.best.at("rate");
  INFO("amplitude " << a << " +- " << result.ci_half_width.at("amplitude") << ", rate " << r << " +- "
                    << result.ci_half_width.at("rate"));
  CHECK(std::abs(a - 1.3) <= result.ci_half_width.at("amplitude"));
  CHECK(std::abs(r - 4.2) <= result.ci_half_width.at("rate"));
  // The intervals are informative: much narrower than the bounds, so nothing is flagged.
  CHECK(result.ci_half_width.at("amplitude") < 0.1 * 1.5);
  CHECK(result.unidentifiable.empty());
  CHECK(result.correlation.size() == 2);
}

TEST_CASE("A variable that does not affect the curve is flagged unidentifiable", "[identify][loop]") {
  auto study = test::analytic_study(0.01, 6);
  study["variables"].push_back({{"name", "ignored"}, {"lower", 0.0}, {"upper", 1.0}, {"initial", 0.5}});
  const auto result = run_study(parse_study(study, "."), ExtraParameterModel(), quiet_options(test::fresh_dir("flag")));
  CHECK(result.unidentifiable == std::vector<std::string>{"ignored"});
  CHECK(std::abs(result.best.at("amplitude") - 1.3) <= result.ci_half_width.at("amplitude"));
}

TEST_CASE("A failed evaluation is recorded with its error and left out of the fit", "[identify][loop]") {
  const auto dir = test::fresh_dir("failures");
  const auto spec = parse_study(test::analytic_study(0.0, 6), ".");
  const auto result = run_study(spec, FailingModel(), quiet_options(dir));
  CHECK(result.failed_runs > 0);
  CHECK(result.best.at("amplitude") <= 1.8);
  CHECK(std::abs(result.best.at("amplitude") / 1.3 - 1.0) < 1e-2);
  const auto store = StudyStore::open_existing(dir / "study.db");
  int failed = 0;
  for (const auto& r : store.evaluations()) {
    if (r.ok) continue;
    ++failed;
    CHECK(r.error == "unstable: time step too large");
    CHECK(std::isnan(r.objective));
    CHECK(r.parameters.at("amplitude") > 1.8);
  }
  CHECK(failed == result.failed_runs);
}

TEST_CASE("A study in which every run fails stops with a clear message", "[identify][loop]") {
  FailingModel model;
  model.fail_above = -1.0;
  const auto spec = parse_study(test::analytic_study(0.0, 4), ".");
  CHECK_THROWS_WITH(run_study(spec, model, quiet_options(test::fresh_dir("all_fail"))),
                    Catch::Contains("every run failed") && Catch::Contains("unstable"));
}

TEST_CASE("Results are identical for one and two parallel jobs", "[identify][loop]") {
  const auto spec = parse_study(test::analytic_study(0.01, 5), ".");
  const auto one_dir = test::fresh_dir("jobs1"), two_dir = test::fresh_dir("jobs2");
  const auto one = run_study(spec, AnalyticCurveModel(), quiet_options(one_dir, 1));
  const auto two = run_study(spec, AnalyticCurveModel(), quiet_options(two_dir, 2));
  CHECK(one.best == two.best);  // bit-identical
  CHECK(one.best_objective == two.best_objective);
  CHECK(one.ci_half_width == two.ci_half_width);
  const auto runs_one = StudyStore::open_existing(one_dir / "study.db").evaluations();
  const auto runs_two = StudyStore::open_existing(two_dir / "study.db").evaluations();
  REQUIRE(runs_one.size() == runs_two.size());
  for (std::size_t i = 0; i < runs_one.size(); ++i) {
    CHECK(runs_one[i].unit_x == runs_two[i].unit_x);
    CHECK(runs_one[i].objective == runs_two[i].objective);
  }
}

TEST_CASE("Unknown variable names are refused naming the field", "[identify][loop]") {
  auto study = test::analytic_study(0.0, 2);
  study["variables"][1]["name"] = "normk";
  CHECK_THROWS_WITH(run_study(parse_study(study, "."), AnalyticCurveModel(), quiet_options(test::fresh_dir("names"))),
                    Catch::Contains("variables[1].name") && Catch::Contains("normk"));
}

TEST_CASE("The report is rebuilt from the study store alone", "[identify][report]") {
  const auto dir = test::fresh_dir("report");
  const auto spec = parse_study(test::analytic_study(0.0, 3), ".");
  const auto result = run_study(spec, AnalyticCurveModel(), quiet_options(dir));
  const auto rebuilt = test::fresh_dir("report_rebuilt");
  const auto summary = write_report(StudyStore::open_existing(dir / "study.db"), rebuilt, true);
  for (const char* name : {"best_parameters.json", "evaluations.csv", "iterations.csv", "report.md",
                           "target_response.csv", "best_response.csv"})
    CHECK(std::filesystem::exists(rebuilt / name));
  std::ifstream in(rebuilt / "best_parameters.json");
  const auto best = nlohmann::json::parse(in);
  CHECK(best["variables"]["amplitude"]["value"].get<double>() == result.best.at("amplitude"));
  CHECK(best["objective"].get<double>() == result.best_objective);
  if (summary.plot_warning.empty()) {
    CHECK(std::filesystem::exists(rebuilt / "objective_history.png"));
    CHECK(std::filesystem::exists(rebuilt / "variable_rate.png"));
    CHECK(std::filesystem::exists(rebuilt / "target_response.png"));
  }
}

TEST_CASE("The summary, report.md and best_parameters.json show one and the same 95 % interval, the posterior's",
          "[identify][report][posterior]") {
  const auto dir = test::fresh_dir("one_interval");
  const auto spec = parse_study(test::analytic_study(0.01, 10), ".");
  const auto result = run_study(spec, AnalyticCurveModel(), quiet_options(dir));
  std::ifstream json_in(dir / "best_parameters.json");
  const auto best = nlohmann::json::parse(json_in);
  std::ifstream md_in(dir / "report.md");
  const std::string report((std::istreambuf_iterator<char>(md_in)), std::istreambuf_iterator<char>());
  for (const char* name : {"amplitude", "rate"}) {
    const ReportedInterval& interval = result.intervals.at(name);
    INFO(name << " " << interval_text(interval));
    REQUIRE(interval.available);
    CHECK(interval.method == "posterior");
    CHECK(interval.lower < result.best.at(name));
    CHECK(result.best.at(name) < interval.upper);
    const auto& entry = best["variables"][name];
    CHECK(entry["interval_95"][0].get<double>() == interval.lower);
    CHECK(entry["interval_95"][1].get<double>() == interval.upper);
    CHECK(entry["interval_method"] == "posterior");
    CHECK(report.find(interval_text(interval)) != std::string::npos);
  }
  // Truth (1.3, 4.2) inside, as the coverage tests of uncertainty.hpp measure over many seeds.
  CHECK(result.intervals.at("amplitude").lower <= 1.3);
  CHECK(1.3 <= result.intervals.at("amplitude").upper);
}

TEST_CASE("The reported interval falls back to the linearised one only without a posterior", "[identify][report]") {
  const nlohmann::json linearised = {{"ci_half_width", {{"k", 0.5}}}, {"unidentifiable", nlohmann::json::array({"k"})}};
  const ReportedInterval fallback = reported_interval(linearised, "k", 2.0);
  CHECK(fallback.available);
  CHECK(fallback.method == "linearised");
  CHECK(fallback.lower == 1.5);
  CHECK(fallback.upper == 2.5);
  CHECK_FALSE(fallback.identifiable);
  nlohmann::json both = linearised;
  both["posterior"] = {{"variables", {{"k", {{"lower_95", 1.1}, {"upper_95", 3.2}, {"unidentifiable", false}}}}}};
  const ReportedInterval posterior = reported_interval(both, "k", 2.0);
  CHECK(posterior.method == "posterior");
  CHECK(posterior.lower == 1.1);
  CHECK(posterior.upper == 3.2);
  CHECK(posterior.identifiable);
  CHECK(interval_text(posterior) == "[1.1, 3.2] (posterior)");
  CHECK_FALSE(reported_interval(nullptr, "k", 2.0).available);
  CHECK(interval_text(reported_interval(nullptr, "k", 2.0)) == "-");
}

TEST_CASE("An answer outside the posterior interval widens the reported interval to it and says so",
          "[identify][report]") {
  const nlohmann::json uncertainty = {
      {"posterior",
       {{"variables", {{"fricr", {{"lower_95", 0.0578}, {"upper_95", 0.567}, {"unidentifiable", true}}}}}}}};
  const ReportedInterval below = reported_interval(uncertainty, "fricr", 0.0570);
  CHECK(below.lower == 0.0570);
  CHECK(below.upper == 0.567);
  CHECK(below.method == "posterior, widened to the answer");
  const ReportedInterval above = reported_interval(uncertainty, "fricr", 0.6);
  CHECK(above.lower == 0.0578);
  CHECK(above.upper == 0.6);
  const ReportedInterval inside = reported_interval(uncertainty, "fricr", 0.2);
  CHECK(inside.method == "posterior");
  CHECK(inside.lower == 0.0578);
}

TEST_CASE("Adaptive infill and principal-component responses also identify the analytic parameters",
          "[identify][loop]") {
  auto study = test::analytic_study(0.0, 10);
  study["sampling"] = {{"strategy", "adaptive_infill"}};
  study["surrogate"] = {{"responses", "principal_components"}};
  const auto result =
      run_study(parse_study(study, "."), AnalyticCurveModel(), quiet_options(test::fresh_dir("adaptive")));
  CHECK(std::abs(result.best.at("amplitude") / 1.3 - 1.0) < 2e-2);
  CHECK(std::abs(result.best.at("rate") / 4.2 - 1.0) < 2e-2);
}

TEST_CASE("Curve mapping identifies parameters from a hysteresis loop", "[identify][loop]") {
  AnalyticCurveModel model;
  const Curve loop = model.evaluate({{"amplitude", 1.3}, {"slope", 0.8}}, {}).at("loop");
  nlohmann::json study = test::analytic_study(0.0, 10);
  study["variables"][1] = {{"name", "slope"}, {"lower", 0.0}, {"upper", 2.0}, {"initial", 0.3}};
  study["targets"][0] = {{"curve", "loop"}, {"x_column", "x_1"}, {"y_column", "y_1"},
                         {"x", loop.x},     {"y", loop.y},       {"metric", "curve_mapping"}};
  const auto result = run_study(parse_study(study, "."), model, quiet_options(test::fresh_dir("mapping")));
  CHECK(std::abs(result.best.at("amplitude") / 1.3 - 1.0) < 1e-2);
  CHECK(std::abs(result.best.at("slope") / 0.8 - 1.0) < 2e-2);
}

TEST_CASE("Without gnuplot on the PATH the report skips the plots with a warning", "[identify][report]") {
  const auto dir = test::fresh_dir("no_gnuplot");
  run_study(parse_study(test::analytic_study(0.0, 1), "."), AnalyticCurveModel(), quiet_options(dir));
  const std::string saved = std::getenv("PATH") ? std::getenv("PATH") : "";
  setenv("PATH", "/nonexistent", 1);
  const auto summary = write_report(StudyStore::open_existing(dir / "study.db"), dir / "rebuilt", true);
  setenv("PATH", saved.c_str(), 1);
  CHECK_THAT(summary.plot_warning, Catch::Contains("gnuplot not found"));
  CHECK_FALSE(summary.plots_written);
  CHECK(std::filesystem::exists(dir / "rebuilt" / "report.md"));
  CHECK_FALSE(std::filesystem::exists(dir / "rebuilt" / "objective_history.png"));
}

namespace {
// A plug-in evaluator (the shape of the MPI one): runs the batch backwards, serially.
class BackwardsEvaluator final : public Evaluator {
 public:
  explicit BackwardsEvaluator(const Model& model) : model_(model) {}
  std::vector<EvaluationOutcome> evaluate_jobs(const std::vector<EvaluationJob>& batch,
                                               const DoneCallback& on_done) override {
    std::vector<EvaluationOutcome> outcomes(batch.size());
    for (std::size_t k = batch.size(); k-- > 0;) {
      outcomes[k] = evaluate_safely(model_, batch[k].parameters, {});
      if (on_done) on_done(k, outcomes[k]);
      ++runs;
    }
    return outcomes;
  }
  int concurrency() const override { return 1; }
  int runs = 0;

 private:
  const Model& model_;
};
}  // namespace

TEST_CASE("A plug-in evaluator finishing runs in another order gives the same result", "[identify][loop]") {
  const auto spec = parse_study(test::analytic_study(0.01, 4), ".");
  const AnalyticCurveModel model;
  const auto reference = run_study(spec, model, quiet_options(test::fresh_dir("plugin_reference")));
  BackwardsEvaluator evaluator(model);
  auto options = quiet_options(test::fresh_dir("plugin"));
  options.evaluator = &evaluator;
  const auto result = run_study(spec, model, options);
  CHECK(evaluator.runs == reference.runs);
  CHECK(result.best == reference.best);
  CHECK(result.best_objective == reference.best_objective);
}

TEST_CASE("With simulation noise, variables below it are flagged and the others lie inside their intervals",
          "[identify][loop][uncertainty]") {
  // Regression Jacobian: the runs' trajectory noise must neither give "weak" a narrow
  // interval nor make amplitude and rate look unidentifiable.
  auto study = test::analytic_study(0.01, 10);
  study["variables"].push_back({{"name", "weak"}, {"lower", 0.0}, {"upper", 1.0}, {"initial", 0.3}});
  study["variables"].push_back({{"name", "ignored"}, {"lower", 0.0}, {"upper", 1.0}, {"initial", 0.5}});
  const auto result =
      run_study(parse_study(study, "."), NoisySimulationModel(), quiet_options(test::fresh_dir("simulation_noise")));
  const double a = result.best.at("amplitude"), r = result.best.at("rate"), w = result.best.at("weak");
  INFO("amplitude " << a << " +- " << result.ci_half_width.at("amplitude") << ", rate " << r << " +- "
                    << result.ci_half_width.at("rate") << ", weak " << w << " +- " << result.ci_half_width.at("weak"));
  CHECK(std::abs(a - 1.3) <= result.ci_half_width.at("amplitude"));
  CHECK(std::abs(r - 4.2) <= result.ci_half_width.at("rate"));
  CHECK(result.ci_half_width.at("amplitude") < 0.1 * 1.5);
  // "Says so": the weak and the dummy variable are flagged (a flagged variable's interval is
  // unbounded or wider than half its range by construction, so it covers the truth).
  CHECK(result.unidentifiable == std::vector<std::string>{"weak", "ignored"});
}
