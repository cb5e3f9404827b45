// The initial-point check (study_preflight.hpp) on --resume: when the store already holds the
// study's run 0/0 as a success of the same model, seed and parameters, the check reads its curves
// from the store instead of running the model (for a DEM study a whole simulation); the resumed
// study gives what it gives after a check that evaluates.
#include <catch2/catch.hpp>

#include <atomic>
#include <cmath>
#include <stdexcept>
#include <string>

#include "demfit/identify/analytic_model.hpp"
#include "demfit/identify/evaluator.hpp"
#include "demfit/identify/study.hpp"
#include "demfit/identify/study_preflight.hpp"
#include "demfit/identify/study_store.hpp"
#include "test_helpers.hpp"

using namespace demfit::identify;

namespace {

using test::SimulatedKill;

// The analytic model counting its evaluations; with `fail_initial`, a run at the study's initial
// values (amplitude 1, rate 3) fails like a diverged simulation.
class CountingModel final : public Model {
 public:
  explicit CountingModel(bool fail_initial = false) : fail_initial_(fail_initial) {}
  std::vector<ParameterDescriptor> parameters() const override { return exact_.parameters(); }
  std::vector<CurveDescriptor> curves() const override { return exact_.curves(); }
  ParameterSet default_parameters() const override { return exact_.default_parameters(); }
  CurveSet evaluate(const ParameterSet& parameters, const EvaluationContext& context) const override {
    ++calls_;
    if (fail_initial_ && std::abs(parameters.at("amplitude") - 1.0) < 1e-12 &&
        std::abs(parameters.at("rate") - 3.0) < 1e-12)
      throw std::runtime_error("the simulation diverged");
    return exact_.evaluate(parameters, context);
  }
  int calls() const { return calls_; }

 private:
  AnalyticCurveModel exact_;
  bool fail_initial_;
  mutable std::atomic<int> calls_{0};
};

StudySpec short_study() { return parse_study(test::analytic_study(0.01, 3), "."); }

// The options demfit identify runs a study with: the resolved model recorded in the store.
RunOptions run_options(const std::filesystem::path& dir, bool resume) {
  RunOptions options = test::quiet_options(dir);
  options.resolved_model = {{"analytic", nlohmann::json::object()}};
  options.resume = resume;
  return options;
}

// The front ends' sequence (cases::run_study_file): the check on the loop's pool, then the loop.
// `check_calls` = the model's evaluations in the check.
StudyResult checked_run(const StudySpec& parsed, const CountingModel& model, RunOptions options, int& check_calls) {
  ThreadPoolEvaluator pool(model, options.jobs, options.threads_per_job, static_cast<unsigned long>(parsed.seed));
  const int before = model.calls();
  const StudySpec spec = preflight_study(parsed, model, pool, options);
  check_calls = model.calls() - before;
  options.evaluator = &pool;
  return run_study(spec, model, options);
}

std::string stored_runs_json(const std::filesystem::path& dir) {
  nlohmann::json runs = nlohmann::json::array();
  for (const EvaluationRecord& r : StudyStore::open_existing(dir / "study.db").evaluations()) {
    nlohmann::json run = to_json(r);
    run["curves"] = r.curves.at("response").y;
    runs.push_back(run);
  }
  return runs.dump();
}

}  // namespace

TEST_CASE("A fresh study's initial-point check evaluates the model once and the loop takes that run",
          "[identify][preflight]") {
  const StudySpec spec = short_study();
  const CountingModel model;
  int check_calls = -1;
  const auto dir = test::fresh_dir("preflight_fresh");
  const StudyResult result = checked_run(spec, model, run_options(dir, false), check_calls);
  CHECK(check_calls == 1);
  // run 0/0 is the check's run: every stored run was evaluated exactly once
  CHECK(model.calls() == static_cast<int>(StudyStore::open_existing(dir / "study.db").evaluations().size()));
  CHECK(model.calls() == result.runs);
}

TEST_CASE("Resuming a finished study runs no model evaluation, the initial-point check included",
          "[identify][preflight][resume]") {
  const StudySpec spec = short_study();
  const auto dir = test::fresh_dir("preflight_resume_finished");
  int check_calls = -1;
  const CountingModel first;
  const StudyResult reference = checked_run(spec, first, run_options(dir, false), check_calls);
  const std::string stored_before = stored_runs_json(dir);

  const CountingModel again;
  const StudyResult resumed = checked_run(spec, again, run_options(dir, true), check_calls);
  CHECK(check_calls == 0);
  CHECK(again.calls() == 0);
  CHECK(resumed.runs == reference.runs);
  CHECK(resumed.best == reference.best);  // bit-identical
  CHECK(resumed.best_objective == reference.best_objective);
  CHECK(resumed.ci_half_width == reference.ci_half_width);
  CHECK(stored_runs_json(dir) == stored_before);
}

TEST_CASE("Resuming a killed study does not evaluate the stored initial point for the check",
          "[identify][preflight][resume]") {
  const StudySpec spec = short_study();
  int check_calls = -1;
  const CountingModel uninterrupted;
  const StudyResult reference =
      checked_run(spec, uninterrupted, run_options(test::fresh_dir("preflight_resume_reference"), false), check_calls);

  const auto dir = test::fresh_dir("preflight_resume_killed");
  RunOptions killed = run_options(dir, false);
  const int kill_after = spec.points_per_iteration + 2;  // in iteration 1
  killed.after_evaluation = [&](int done) {
    if (done == kill_after) throw SimulatedKill{};
  };
  const CountingModel first;
  CHECK_THROWS_AS(checked_run(spec, first, killed, check_calls), SimulatedKill);
  CHECK(check_calls == 1);

  const CountingModel again;
  const StudyResult resumed = checked_run(spec, again, run_options(dir, true), check_calls);
  CHECK(check_calls == 0);
  CHECK(again.calls() == reference.runs - kill_after);  // only the runs the store lacks
  CHECK(resumed.runs == reference.runs);
  CHECK(resumed.best == reference.best);  // bit-identical
  CHECK(resumed.best_objective == reference.best_objective);
  CHECK(resumed.ci_half_width == reference.ci_half_width);
}

TEST_CASE("On resume, a stored initial run that failed is evaluated again for the check",
          "[identify][preflight][resume]") {
  const StudySpec spec = short_study();
  const auto dir = test::fresh_dir("preflight_resume_failed");
  RunOptions first_options = run_options(dir, false);
  const int kill_after = 3;
  first_options.after_evaluation = [&](int done) {
    if (done == kill_after) throw SimulatedKill{};
  };
  // Run 0/0 failed (no check before it: the check would have refused the study).
  const CountingModel failing(true);
  CHECK_THROWS_AS(run_study(spec, failing, first_options), SimulatedKill);
  REQUIRE_FALSE(StudyStore::open_existing(dir / "study.db").find_evaluation(0, 0)->ok);

  int check_calls = -1;
  const CountingModel healthy;
  const StudyResult resumed = checked_run(spec, healthy, run_options(dir, true), check_calls);
  CHECK(check_calls == 1);
  // the failed run stays in the store as it was: a finished run is never repeated
  CHECK_FALSE(StudyStore::open_existing(dir / "study.db").find_evaluation(0, 0)->ok);
  CHECK(resumed.failed_runs == 1);
  CHECK(healthy.calls() == 1 + resumed.runs - kill_after);
}

TEST_CASE("On resume, a stored initial run of another model or seed is not taken for the check",
          "[identify][preflight][resume]") {
  const StudySpec spec = short_study();
  const auto dir = test::fresh_dir("preflight_resume_other");
  RunOptions first_options = run_options(dir, false);
  first_options.after_evaluation = [&](int done) {
    if (done == 2) throw SimulatedKill{};
  };
  int check_calls = -1;
  const CountingModel first;
  CHECK_THROWS_AS(checked_run(spec, first, first_options, check_calls), SimulatedKill);
  REQUIRE(StudyStore::open_existing(dir / "study.db").find_evaluation(0, 0)->ok);

  // Another resolved model (same parameter names): the check evaluates, the loop refuses the store.
  RunOptions other_model = run_options(dir, true);
  other_model.resolved_model = {{"analytic", {{"points", 9}}}};
  const CountingModel changed;
  CHECK_THROWS_WITH(checked_run(spec, changed, other_model, check_calls), Catch::Contains("the model changed"));
  CHECK(check_calls == 1);

  // Another seed (a model's stochastic set-up receives it): likewise.
  auto reseeded = test::analytic_study(0.01, 3);
  reseeded["seed"] = 12;
  const CountingModel other_seed;
  CHECK_THROWS_WITH(checked_run(parse_study(reseeded, "."), other_seed, run_options(dir, true), check_calls),
                    Catch::Contains("another study"));
  CHECK(check_calls == 1);
}
