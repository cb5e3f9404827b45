// A real kill -9: a child process runs the study and is killed with SIGKILL mid-iteration; the
// parent resumes from the store the child left behind.
#include <catch2/catch.hpp>

#include <chrono>
#include <csignal>
#include <thread>
#include <sys/wait.h>
#include <unistd.h>

#include "demfit/identify/analytic_model.hpp"
#include "demfit/identify/study.hpp"
#include "demfit/identify/study_store.hpp"
#include "test_helpers.hpp"

using namespace demfit::identify;

namespace {

// The analytic model taking 40 ms per run, so that the kill lands while runs are in flight.
class SlowModel final : public Model {
 public:
  std::vector<ParameterDescriptor> parameters() const override { return inner_.parameters(); }
  ParameterSet default_parameters() const override { return inner_.default_parameters(); }
  CurveSet evaluate(const ParameterSet& p, const EvaluationContext& c) const override {
    std::this_thread::sleep_for(std::chrono::milliseconds(40));
    return inner_.evaluate(p, c);
  }

 private:
  AnalyticCurveModel inner_;
};

std::size_t stored_run_count(const std::filesystem::path& db) {
  try {
    return StudyStore::open_existing(db).evaluations().size();
  } catch (const std::exception&) {
    return 0;  // not created yet
  }
}

}  // namespace

TEST_CASE("A study killed with SIGKILL resumes to the uninterrupted result without repeating runs",
          "[identify][resume]") {
  const auto spec = parse_study(test::analytic_study(0.01, 4), ".");
  const SlowModel model;
  RunOptions options;
  options.plots = false;
  options.progress = false;
  options.jobs = 2;
  options.output_dir = test::fresh_dir("kill_reference");
  const auto reference = run_study(spec, model, options);

  options.output_dir = test::fresh_dir("kill_resumed");
  const auto db = options.output_dir / "study.db";
  const pid_t child = fork();
  REQUIRE(child >= 0);
  if (child == 0) {
    try {
      run_study(spec, model, options);
    } catch (...) {}
    _exit(0);
  }
  const std::size_t kill_after = spec.points_per_iteration + 2;  // inside iteration 1
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (stored_run_count(db) < kill_after && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  kill(child, SIGKILL);
  int status = 0;
  waitpid(child, &status, 0);
  REQUIRE(WIFSIGNALED(status));
  const std::size_t survived = stored_run_count(db);
  CHECK(survived >= kill_after);
  CHECK(survived < static_cast<std::size_t>(reference.runs));

  options.resume = true;
  int evaluated = 0;
  options.after_evaluation = [&](int done) { evaluated = done; };
  const auto resumed = run_study(spec, model, options);
  CHECK(static_cast<std::size_t>(evaluated) == reference.runs - survived);
  CHECK(resumed.best == reference.best);
  CHECK(resumed.best_objective == reference.best_objective);
}
