// The stable-answer rule of the study loop (stopping.verification_tolerance): the study stops
// when the run at the predicted optimum agrees with the prediction and the optimum has stopped
// moving, and only after the verification run agrees too; a verification far from its
// prediction joins the data and the loop goes on; the run budget still ends the loop first.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>
#include <vector>

#include "demfit/identify/analytic_model.hpp"
#include "demfit/identify/evaluator.hpp"
#include "demfit/identify/stop_reason.hpp"
#include "demfit/identify/study.hpp"
#include "demfit/identify/study_store.hpp"
#include "test_helpers.hpp"

using namespace demfit::identify;

namespace {

// sqrt(2/N) for the analytic target's N = 41 points: the objective's own relative noise.
const double kTolerance = std::sqrt(2.0 / 41.0);

StudySpec stable_study(int max_iterations, int max_runs = 0) {
  auto json = test::analytic_study(0.01, max_iterations);
  json["stopping"] = {{"max_iterations", max_iterations},
                      {"design_tolerance", 0.0},
                      {"objective_tolerance", 0.0},
                      {"verification_tolerance", kTolerance}};
  if (max_runs > 0) json["stopping"]["max_runs"] = max_runs;
  return parse_study(json, ".");
}

// The analytic model in this process, but the first `disturbed` single-run batches (the loop's
// verification runs; design batches hold several points) come back with the response curve
// raised by 10 % of its largest value: a run far from any prediction, as a chaotic simulation
// can produce.
class DisturbedVerificationEvaluator final : public Evaluator {
 public:
  DisturbedVerificationEvaluator(const Model& model, int disturbed) : model_(model), disturbed_(disturbed) {}
  std::vector<EvaluationOutcome> evaluate_jobs(const std::vector<EvaluationJob>& batch,
                                               const DoneCallback& on_done) override {
    const bool disturb = batch.size() == 1 && disturbed_ > 0;
    if (disturb) --disturbed_;
    std::vector<EvaluationOutcome> outcomes(batch.size());
    for (std::size_t k = 0; k < batch.size(); ++k) {
      outcomes[k] = evaluate_safely(model_, batch[k].parameters, {});
      if (disturb && outcomes[k].ok) {
        Curve& response = outcomes[k].curves.at("response");
        double largest = 0.0;
        for (double y : response.y) largest = std::max(largest, std::abs(y));
        for (double& y : response.y) y += 0.1 * largest;
      }
      if (on_done) on_done(k, outcomes[k]);
    }
    return outcomes;
  }
  int concurrency() const override { return 1; }

 private:
  const Model& model_;
  int disturbed_;
};

std::vector<EvaluationRecord> verification_runs(const std::filesystem::path& dir) {
  std::vector<EvaluationRecord> found;
  for (const auto& r : StudyStore::open_existing(dir / "study.db").evaluations())
    if (r.kind == "verification") found.push_back(r);
  return found;
}

}  // namespace

TEST_CASE("A stable answer stops the study before the iteration limit, converged and verified", "[identify][stopping]") {
  const auto spec = stable_study(20);
  const auto dir = test::fresh_dir("stable_answer_stops");
  const auto result = run_study(spec, AnalyticCurveModel(), test::quiet_options(dir));
  INFO("stopped after " << result.iterations << " iterations, " << result.runs << " runs: " << result.stop_reason);
  CHECK(result.converged);
  CHECK(result.iterations < 20);
  CHECK(result.runs < 20 * spec.points_per_iteration + 1);
  CHECK(stop_kind_of(StudyStore::open_existing(dir / "study.db").result().value()) == StopKind::converged);
  CHECK(result.stop_reason.rfind("converged (the verification run's objective is", 0) == 0);
  // One verification, the last run, and the answer it verified lies near the truth (1 % noise).
  const auto verifications = verification_runs(dir);
  REQUIRE(verifications.size() == 1);
  CHECK(verifications[0].iteration == result.iterations);
  CHECK(std::abs(result.best.at("amplitude") / 1.3 - 1.0) < 0.02);
  CHECK(std::abs(result.best.at("rate") / 4.2 - 1.0) < 0.05);
}

TEST_CASE("A verification run far from its prediction joins the data and the loop goes on", "[identify][stopping]") {
  const auto spec = stable_study(20);
  const AnalyticCurveModel model;
  const auto undisturbed = run_study(spec, model, test::quiet_options(test::fresh_dir("stable_answer_reference")));
  DisturbedVerificationEvaluator evaluator(model, 1);
  const auto dir = test::fresh_dir("stable_answer_disturbed");
  auto options = test::quiet_options(dir);
  options.evaluator = &evaluator;
  const auto result = run_study(spec, model, options);
  const auto verifications = verification_runs(dir);
  REQUIRE(verifications.size() == 2);
  // The disturbed verification is where the undisturbed study stopped; the study went on past it.
  CHECK(verifications[0].iteration == undisturbed.iterations);
  CHECK(verifications[0].objective > 2.0 * undisturbed.best_objective);
  CHECK(result.iterations > undisturbed.iterations + 1);
  CHECK(verifications[1].iteration == result.iterations);
  CHECK(result.converged);
  CHECK(result.best_objective < verifications[0].objective);
  // The disturbed run is data: the iteration after it has a record and full design runs.
  const auto store = StudyStore::open_existing(dir / "study.db");
  int later_design_runs = 0;
  for (const auto& r : store.evaluations())
    later_design_runs += r.iteration > verifications[0].iteration && r.kind != "verification" ? 1 : 0;
  CHECK(later_design_runs >= spec.points_per_iteration);
}

TEST_CASE("A verification far from its prediction at the iteration limit ends the study unconverged, saying so",
          "[identify][stopping]") {
  const auto spec = stable_study(20);
  const AnalyticCurveModel model;
  DisturbedVerificationEvaluator evaluator(model, 1000);  // every verification disturbed
  auto options = test::quiet_options(test::fresh_dir("stable_answer_never"));
  options.evaluator = &evaluator;
  const auto result = run_study(spec, model, options);
  CHECK_FALSE(result.converged);
  CHECK(result.stop_reason.rfind("iteration limit reached (20) without converging; the verification run", 0) == 0);
  CHECK(result.stop_reason.find("outside stopping.verification_tolerance") != std::string::npos);
}

TEST_CASE("The run budget ends a study under the stable-answer rule before it is stable", "[identify][stopping]") {
  // One iteration's runs: stability needs a second iteration (a run at a prediction), so the cap
  // ends the loop first.
  const int cap = stable_study(20).points_per_iteration;
  const auto spec = stable_study(20, cap);
  const auto dir = test::fresh_dir("stable_answer_budget");
  const auto result = run_study(spec, AnalyticCurveModel(), test::quiet_options(dir));
  CHECK_FALSE(result.converged);
  CHECK(stop_kind_of(StudyStore::open_existing(dir / "study.db").result().value()) == StopKind::run_budget);
  CHECK(result.stop_reason.rfind("run budget reached", 0) == 0);
  CHECK(result.runs <= cap + 1);  // the verification comes after the cap, as always
}

TEST_CASE("stopping.verification_tolerance is kept in the resolved study and refused outside 0 to 10, naming it",
          "[identify][stopping]") {
  const auto spec = stable_study(5);
  CHECK(parse_study(to_json(spec), ".").verification_tolerance == kTolerance);
  CHECK_FALSE(to_json(parse_study(test::analytic_study(), ".")).at("stopping").contains("verification_tolerance"));
  auto json = test::analytic_study();
  json["stopping"]["verification_tolerance"] = -0.1;
  CHECK_THROWS_WITH(parse_study(json, "."), Catch::Contains("verification_tolerance") && Catch::Contains("must be 0"));
}

TEST_CASE("A study store keeps its verification tolerance but may be resumed with more iterations",
          "[identify][stopping]") {
  const auto plain = parse_study(test::analytic_study(0.01, 5), ".");
  CHECK(study_hash(stable_study(5)) == study_hash(stable_study(20)));
  CHECK(study_hash(stable_study(5)) != study_hash(plain));
  CHECK(study_hash(plain) == study_hash(parse_study(test::analytic_study(0.01, 20), ".")));
}
