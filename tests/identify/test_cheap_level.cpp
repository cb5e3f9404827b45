// A study's cheap level (study_spec.hpp CheapLevelSpec): read and written back, its runs made before
// iteration 0 on the cheap model, stored apart from the study's own runs, replayed on resume, and
// used by the expected-improvement strategy; never part of the answer.
#include <catch2/catch.hpp>

#include <atomic>
#include <cmath>
#include <fstream>
#include <iterator>

#include "demfit/identify/analytic_model.hpp"
#include "demfit/identify/objective.hpp"
#include "demfit/identify/study.hpp"
#include "demfit/identify/study_store.hpp"
#include "test_helpers.hpp"

using namespace demfit::identify;

namespace {

using test::SimulatedKill;

// The analytic model with a smooth bias on its curves (a coarser simulation of the same physics),
// counting its evaluations.
class BiasedModel final : public Model {
 public:
  explicit BiasedModel(double bias) : bias_(bias) {}
  std::vector<ParameterDescriptor> parameters() const override { return exact_.parameters(); }
  std::vector<CurveDescriptor> curves() const override { return exact_.curves(); }
  ParameterSet default_parameters() const override { return exact_.default_parameters(); }
  CurveSet evaluate(const ParameterSet& parameters, const EvaluationContext& context) const override {
    ++evaluations_;
    CurveSet curves = exact_.evaluate(parameters, context);
    for (auto& [name, curve] : curves)
      for (std::size_t i = 0; i < curve.y.size(); ++i) curve.y[i] += bias_ * curve.x[i] * curve.x[i];
    return curves;
  }
  int evaluations() const { return evaluations_; }

 private:
  AnalyticCurveModel exact_;
  double bias_;
  mutable std::atomic<int> evaluations_{0};
};

nlohmann::json cheap_study(int iterations, int cheap_runs) {
  auto study = test::analytic_study(0.01, iterations);
  study["sampling"] = {{"strategy", "expected_improvement"}, {"points_per_iteration", 4}};
  study["cheap_level"] = {{"overrides", {{"points", 9}}}, {"runs", cheap_runs}};
  return study;
}

RunOptions with_cheap(RunOptions options, const Model& cheap) {
  options.cheap_model = &cheap;
  return options;
}

}  // namespace

TEST_CASE("A cheap level is read, written back, hashed and checked against the study", "[identify][cheap_level]") {
  const auto spec = parse_study(cheap_study(3, 12), ".");
  REQUIRE(spec.cheap_level);
  CHECK(spec.cheap_level->runs == 12);
  CHECK(to_json(spec)["cheap_level"]["overrides"]["points"] == 9);
  CHECK(parse_study(to_json(spec), ".").cheap_level->runs == 12);
  auto other = cheap_study(3, 13);
  CHECK(study_hash(parse_study(other, ".")) != study_hash(spec));
  auto srsm = cheap_study(3, 12);
  srsm["sampling"]["strategy"] = "srsm";
  CHECK_THROWS_WITH(parse_study(srsm, "."), Catch::Contains("cheap_level") && Catch::Contains("expected_improvement"));
  auto few = cheap_study(3, 3);  // 2 variables need at least 4
  CHECK_THROWS_WITH(parse_study(few, "."), Catch::Contains("cheap_level.runs") && Catch::Contains("4"));
  auto empty = cheap_study(3, 12);
  empty["cheap_level"]["overrides"] = nlohmann::json::object();
  CHECK_THROWS_WITH(parse_study(empty, "."), Catch::Contains("cheap_level.overrides"));
  auto unknown = cheap_study(3, 12);
  unknown["cheap_level"]["level"] = 2;
  CHECK_THROWS_WITH(parse_study(unknown, "."), Catch::Contains("cheap_level.level"));
}

TEST_CASE("The cheap level's study merges its overrides into the model's and drops the level", "[identify][cheap_level]") {
  auto study = cheap_study(3, 12);
  study["model"]["overrides"] = {{"points", 41}, {"other", {{"kept", 1}, {"changed", 2}}}};
  study["cheap_level"]["overrides"] = {{"points", 9}, {"other", {{"changed", 3}}}};
  const auto cheap = cheap_level_study(parse_study(study, "."));
  CHECK_FALSE(cheap.cheap_level);
  CHECK(cheap.model_overrides ==
        nlohmann::json({{"points", 9}, {"other", {{"kept", 1}, {"changed", 3}}}}));
}

TEST_CASE("A study with a cheap level runs it first, stores it apart and never answers with it",
          "[identify][cheap_level]") {
  const auto spec = parse_study(cheap_study(4, 12), ".");
  const AnalyticCurveModel model;
  const BiasedModel cheap(0.3);
  const auto dir = test::fresh_dir("cheap_level_apart");
  const auto result = run_study(spec, model, with_cheap(test::quiet_options(dir), cheap));
  CHECK(cheap.evaluations() == 12);
  CHECK(result.cheap_runs == 12);
  const auto store = StudyStore::open_existing(dir / "study.db");
  const auto cheap_runs = store.cheap_evaluations();
  REQUIRE(cheap_runs.size() == 12);
  for (const auto& r : cheap_runs) {
    CHECK(r.iteration == kCheapLevelIteration);
    CHECK(r.kind == "cheap");
  }
  const auto runs = store.evaluations();
  CHECK(static_cast<int>(runs.size()) == result.runs);  // the study's own runs only
  for (const auto& r : runs) CHECK(r.iteration >= 0);
  const auto stored = store.result().value();
  CHECK(stored["best_iteration"].get<int>() >= 0);
  CHECK(stored["cheap_level"]["runs"] == 12);
  std::ifstream report(dir / "report.md");
  const std::string text((std::istreambuf_iterator<char>(report)), std::istreambuf_iterator<char>());
  CHECK_THAT(text, Catch::Contains("cheap level") && Catch::Contains("12 runs (0 failed)"));
  // The answer is one of the exact model's runs: its objective is that model's at its parameters.
  const CompositeObjective objective(spec.targets);
  CHECK(result.best_objective == objective.objective(objective.responses(model.evaluate(result.best, {}))));
}

TEST_CASE("The cheap level's runs steer the expected improvement", "[identify][cheap_level]") {
  // Same study, same seed: the runs after iteration 0 differ once the cheap runs are known.
  auto one_level_json = cheap_study(3, 12);
  one_level_json.erase("cheap_level");
  const AnalyticCurveModel model;
  const BiasedModel cheap(0.3);
  const auto one_dir = test::fresh_dir("cheap_level_one"), two_dir = test::fresh_dir("cheap_level_two");
  run_study(parse_study(one_level_json, "."), model, test::quiet_options(one_dir));
  run_study(parse_study(cheap_study(3, 12), "."), model, with_cheap(test::quiet_options(two_dir), cheap));
  const auto one = StudyStore::open_existing(one_dir / "study.db").evaluations();
  const auto two = StudyStore::open_existing(two_dir / "study.db").evaluations();
  REQUIRE(one.size() >= 8);
  REQUIRE(two.size() >= 8);
  for (std::size_t i = 0; i < 4; ++i) CHECK(one[i].unit_x == two[i].unit_x);  // iteration 0: the same design
  int differ = 0;
  for (std::size_t i = 5; i < 8; ++i) differ += one[i].unit_x != two[i].unit_x ? 1 : 0;  // iteration 1's EI points
  CHECK(differ == 3);
}

TEST_CASE("A study killed during its cheap level resumes without repeating a cheap run, bit for bit",
          "[identify][cheap_level][resume]") {
  const auto spec = parse_study(cheap_study(3, 12), ".");
  const AnalyticCurveModel model;
  const BiasedModel reference_cheap(0.3);
  const auto reference =
      run_study(spec, model, with_cheap(test::quiet_options(test::fresh_dir("cheap_level_reference")), reference_cheap));
  const auto dir = test::fresh_dir("cheap_level_killed");
  const BiasedModel cheap(0.3);
  auto killed = with_cheap(test::quiet_options(dir), cheap);
  killed.after_evaluation = [](int done) {
    if (done == 5) throw SimulatedKill{};
  };
  CHECK_THROWS_AS(run_study(spec, model, killed), SimulatedKill);
  auto resumed_options = with_cheap(test::quiet_options(dir), cheap);
  resumed_options.resume = true;
  const auto resumed = run_study(spec, model, resumed_options);
  CHECK(cheap.evaluations() == 12);
  CHECK(resumed.runs == reference.runs);
  CHECK(resumed.best == reference.best);
  CHECK(resumed.best_objective == reference.best_objective);
}

TEST_CASE("A study with a cheap level but no cheap model says which setting is missing", "[identify][cheap_level]") {
  const auto spec = parse_study(cheap_study(3, 12), ".");
  CHECK_THROWS_WITH(run_study(spec, AnalyticCurveModel(), test::quiet_options(test::fresh_dir("cheap_level_none"))),
                    Catch::Contains("cheap_level"));
}

TEST_CASE("A cheap level whose runs fail stops the study with the runs' first error", "[identify][cheap_level]") {
  class FailingModel final : public Model {
   public:
    std::vector<ParameterDescriptor> parameters() const override { return exact_.parameters(); }
    std::vector<CurveDescriptor> curves() const override { return exact_.curves(); }
    ParameterSet default_parameters() const override { return exact_.default_parameters(); }
    CurveSet evaluate(const ParameterSet&, const EvaluationContext&) const override {
      throw std::runtime_error("time step above the stability limit");
    }

   private:
    AnalyticCurveModel exact_;
  } failing;
  const auto spec = parse_study(cheap_study(3, 12), ".");
  CHECK_THROWS_WITH(
      run_study(spec, AnalyticCurveModel(), with_cheap(test::quiet_options(test::fresh_dir("cheap_level_fail")), failing)),
      Catch::Contains("cheap_level") && Catch::Contains("0 of 12") && Catch::Contains("stability limit"));
}
