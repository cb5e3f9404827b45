// The answer chosen by round-off replicates of the best runs (final_selection.hpp), or the run at
// the surrogate's final predicted optimum (PredictedOptimumSelection).
#include <algorithm>
#include <cstdio>
#include <limits>
#include <type_traits>
#include <variant>

#include "demfit/identify/final_selection.hpp"
#include "demfit/identify/roundoff_replicates.hpp"
#include "study_loop.hpp"

namespace demfit::identify::detail {

std::vector<int> StudyLoop::selection_candidates(int count) const {
  std::vector<int> order;
  for (int i = 0; i < static_cast<int>(std::min(decision_runs_, runs_.size())); ++i)
    if (!runs_[i].replicate) order.push_back(i);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return runs_[a].objective < runs_[b].objective; });
  std::vector<int> chosen;
  for (const int i : order) {
    if (static_cast<int>(chosen.size()) == count) break;
    // A point run twice (a verification at a known point) is one candidate.
    if (std::none_of(chosen.begin(), chosen.end(), [&](int c) { return same_point(runs_[c].unit, runs_[i].unit); }))
      chosen.push_back(i);
  }
  return chosen;
}

Run StudyLoop::select_by_replicates(const ReplicateSelection& selection, int iteration, nlohmann::json& record) {
  return replicate_and_choose(selection_candidates(selection.candidates), selection.replicates, iteration, record);
}

Run StudyLoop::replicate_and_choose(const std::vector<int>& candidates, int replicates, int iteration,
                                    nlohmann::json& record) {
  MatrixXd points(static_cast<Eigen::Index>(candidates.size()) * replicates, dims_);
  for (std::size_t c = 0; c < candidates.size(); ++c)
    for (int r = 0; r < replicates; ++r)
      points.row(static_cast<Eigen::Index>(c) * replicates + r) =
          replicate_point(runs_[candidates[c]].unit, r).transpose();
  if (options_.progress)
    std::fprintf(stderr, "demfit: final selection: the %d best runs, %d round-off replicates each\n",
                 static_cast<int>(candidates.size()), replicates);
  evaluate_points(iteration, points, std::vector<std::string>(points.rows(), "replicate"));
  std::vector<SelectionCandidate> scored;
  record = {{"replicates", replicates}, {"iteration", iteration}, {"candidates", nlohmann::json::array()}};
  for (std::size_t c = 0; c < candidates.size(); ++c) {
    SelectionCandidate s{runs_[candidates[c]].objective, {}};
    nlohmann::json objectives = nlohmann::json::array();
    for (int r = 0; r < replicates; ++r) {
      const EvaluationRecord* e = store_.find_evaluation(iteration, static_cast<int>(c) * replicates + r);
      s.replicate_objectives.push_back(e->ok ? e->objective : std::numeric_limits<double>::quiet_NaN());
      objectives.push_back(e->ok ? nlohmann::json(e->objective) : nlohmann::json(nullptr));
    }
    const Run& run = runs_[candidates[c]];
    record["candidates"].push_back({{"iteration", run.iteration},
                                    {"point", run.point},
                                    {"objective", run.objective},
                                    {"replicate_objectives", objectives},
                                    {"mean_objective", candidate_mean(s)}});
    scored.push_back(std::move(s));
  }
  const int chosen = choose_by_replicate_means(scored);
  record["chosen"] = chosen;
  if (options_.progress)
    std::fprintf(stderr, "demfit: final selection: run %d/%d (mean objective %s over %d runs) instead of %d/%d (%s)\n",
                 runs_[candidates[chosen]].iteration, runs_[candidates[chosen]].point,
                 format_number(candidate_mean(scored[chosen])).c_str(), replicates + 1, runs_[candidates[0]].iteration,
                 runs_[candidates[0]].point, format_number(candidate_mean(scored[0])).c_str());
  return runs_[candidates[chosen]];
}

Answer StudyLoop::answer(int verification_iteration) {
  const int after_verification = verification_iteration + 1;
  return std::visit(
      [&](const auto& method) {
        using Method = std::decay_t<decltype(method)>;
        Answer answer;
        if constexpr (std::is_same_v<Method, LowestRunSelection>) {
          answer.run = *best_run();
          answer.next_free_iteration = after_verification;
        } else if constexpr (std::is_same_v<Method, ReplicateSelection>) {
          answer.run = select_by_replicates(method, after_verification, answer.record);
          answer.next_free_iteration = after_verification + 1;
          answer.nudges_used = method.replicates;
        } else {  // a new method fails to compile here until it is handled
          static_assert(std::is_same_v<Method, PredictedOptimumSelection>);
          answer.run = predicted_optimum_run(verification_iteration, answer.record);
          answer.next_free_iteration = after_verification;
          if (answer.record.contains("much_worse")) {  // the answer rule: measure both, keep the better mean
            answer.run = settle_much_worse_answer(after_verification, answer.record);
            answer.next_free_iteration = after_verification + 1;
            answer.nudges_used = kAnswerRuleReplicates;
          }
        }
        return answer;
      },
      spec_.final_selection);
}

Run StudyLoop::predicted_optimum_run(int verification_iteration, nlohmann::json& record) const {
  const Run& lowest = *best_run();
  record = {{"method", PredictedOptimumSelection::name},
            {"best_run", {{"iteration", lowest.iteration}, {"point", lowest.point}, {"objective", lowest.objective}}}};
  // Failed runs are not in runs_: no match means the verification run failed.
  const auto verification = std::find_if(runs_.begin(), runs_.end(), [&](const Run& r) {
    return r.iteration == verification_iteration && r.point == 0 && !r.replicate;
  });
  if (verification == runs_.end()) {
    record["fallback"] = "the verification run at the predicted optimum failed: the best run is the answer";
    return lowest;
  }
  record["iteration"] = verification->iteration;
  record["point"] = verification->point;
  record["objective"] = verification->objective;
  if (much_worse_than_best(verification->objective, lowest.objective)) record["much_worse"] = true;
  return *verification;
}

// The answer rule (final_selection.hpp): the verification run's own objective is much worse than
// the best run's. One draw each cannot tell a lucky best run from a bad predicted optimum, so both
// points are re-run as round-off replicates and the lower mean is the answer; the record says why
// in one line.
Run StudyLoop::settle_much_worse_answer(int iteration, nlohmann::json& record) {
  const auto is_run = [&](int iteration_of, int point_of) {
    for (int i = 0; i < static_cast<int>(std::min(decision_runs_, runs_.size())); ++i)
      if (runs_[i].iteration == iteration_of && runs_[i].point == point_of && !runs_[i].replicate) return i;
    return -1;
  };
  const int verification = is_run(record.at("iteration").get<int>(), record.at("point").get<int>());
  const int lowest =
      is_run(record.at("best_run").at("iteration").get<int>(), record.at("best_run").at("point").get<int>());
  nlohmann::json replicated;
  const Run chosen = replicate_and_choose({verification, lowest}, kAnswerRuleReplicates, iteration, replicated);
  const auto& candidates = replicated.at("candidates");
  const double verification_mean = candidates.at(0).at("mean_objective").get<double>();
  const double lowest_mean = candidates.at(1).at("mean_objective").get<double>();
  char why[320];
  std::snprintf(why, sizeof why,
                "the verification run's objective %s was %.3g x the best run's %s (above %.3g x); over %d round-off "
                "replicates each they average %s and %s: the %s is the answer",
                format_number(runs_[verification].objective).c_str(),
                runs_[verification].objective / runs_[lowest].objective,
                format_number(runs_[lowest].objective).c_str(), kMuchWorseRatio, kAnswerRuleReplicates,
                format_number(verification_mean).c_str(), format_number(lowest_mean).c_str(),
                replicated.at("chosen").get<int>() == 0 ? "predicted optimum" : "best run");
  record["answer_rule"] = replicated;
  if (replicated.at("chosen").get<int>() == 0) {
    record["note"] = why;
  } else {
    record["fallback"] = why;
  }
  if (options_.progress) std::fprintf(stderr, "demfit: final selection: %s\n", why);
  return chosen;
}

}  // namespace demfit::identify::detail
