// The cheap level of a study (study_spec.hpp CheapLevelSpec): its runs before iteration 0. They
// are stored under iteration kCheapLevelIteration, so a resumed study replays them like every
// other run, and they never join runs_: the answer, its posterior, its intervals and the warnings
// are the study model's alone. What they give is the landscape the expected-improvement strategy
// starts from (rbf_surrogate ExpensiveOptions::lower_fidelity).
#include <stdexcept>
#include <string>
#include <vector>

#include "demfit/rbf_surrogate/design.hpp"
#include "study_loop.hpp"

namespace demfit::identify::detail {

rbf_surrogate::FidelityLevel StudyLoop::run_cheap_level() {
  if (!spec_.cheap_level) return {};
  if (!options_.cheap_model)
    throw std::runtime_error(
        "study: cheap_level: this command does not build the cheap level's model; run the study with "
        "demfit identify, or remove cheap_level");
  const Model& cheap = *options_.cheap_model;
  const int count = spec_.cheap_level->runs;
  // Over the whole box: the expected improvement may look anywhere, so the cheap level maps it all.
  const MatrixXd points = rbf_surrogate::latin_hypercube_maximin(
      count, dims_, detail::iteration_seed(spec_.seed, kCheapLevelIteration), Box::unit(dims_));
  // Its own pool: a thread pool evaluates the model it was built for (evaluator.hpp).
  ThreadPoolEvaluator pool(cheap, options_.jobs, options_.threads_per_job, static_cast<unsigned long>(spec_.seed));
  evaluate_missing(kCheapLevelIteration, points, std::vector<std::string>(count, "cheap"), cheap, pool);
  std::vector<int> succeeded;
  std::string first_error;
  for (int i = 0; i < count; ++i) {
    const EvaluationRecord* r = store_.find_evaluation(kCheapLevelIteration, i);
    if (r->ok)
      succeeded.push_back(i);
    else if (first_error.empty())
      first_error = r->error;
  }
  if (static_cast<int>(succeeded.size()) < dims_ + 2)
    throw std::runtime_error("study: cheap_level: only " + std::to_string(succeeded.size()) + " of " +
                             std::to_string(count) + " cheap runs succeeded (at least " + std::to_string(dims_ + 2) +
                             " are needed); first error: " + first_error + "; fix cheap_level.overrides");
  rbf_surrogate::FidelityLevel level{MatrixXd(succeeded.size(), dims_), VectorXd(succeeded.size())};
  for (std::size_t k = 0; k < succeeded.size(); ++k) {
    level.points.row(static_cast<Eigen::Index>(k)) = points.row(succeeded[k]);
    level.values(static_cast<Eigen::Index>(k)) = store_.find_evaluation(kCheapLevelIteration, succeeded[k])->objective;
  }
  return level;
}

nlohmann::json StudyLoop::cheap_level_summary() const {
  if (!spec_.cheap_level) return nullptr;
  int failed = 0;
  double wall = 0.0;
  for (const EvaluationRecord& r : store_.cheap_evaluations()) {
    failed += r.ok ? 0 : 1;
    wall += r.wall_seconds;
  }
  return {{"runs", spec_.cheap_level->runs}, {"failed_runs", failed}, {"run_wall_seconds", wall}};
}

}  // namespace demfit::identify::detail
