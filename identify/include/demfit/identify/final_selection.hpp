#pragma once
// The answer of a study on a noisy objective ("final_selection" in a study file): the best
// `candidates` distinct runs are each re-run `replicates` times as round-off replicates
// (roundoff_replicates.hpp) and the answer is the candidate with the lowest mean objective over
// its run and its replicates. Why: a DEM run is chaotic, so a run's objective is one draw of its
// point's spread; the lowest of a study's hundreds of draws is mostly the luckiest one (Table 3:
// the best of 193 runs, 2.77 mm, averaged 6.88 mm over 8 replicates; docs/measurements/2026-12-05-table3-roundoff-replicates-final-selection.md).
#include <vector>

namespace demfit::identify {

struct SelectionCandidate {
  double objective = 0.0;                    // the study's run
  std::vector<double> replicate_objectives;  // NaN for a failed replicate (left out of the mean)
};

// Mean over the run and its finite replicates.
double candidate_mean(const SelectionCandidate& candidate);

// The answer rule: an answer whose own evaluation is more than kMuchWorseRatio times the
// objective of the best evaluated run is "much worse" and is not returned on one draw. With
// PredictedOptimumSelection both points are re-run kAnswerRuleReplicates times as round-off
// replicates and the lower mean is the answer, stated in one line in the report (a chaotic run's
// single objective is one draw of its point's spread; the mean of three is better supported).
inline constexpr double kMuchWorseRatio = 2.0;
inline constexpr int kAnswerRuleReplicates = 2;

// True when `answer_objective` is much worse than `best_objective` (kMuchWorseRatio).
inline bool much_worse_than_best(double answer_objective, double best_objective) {
  return answer_objective > kMuchWorseRatio * best_objective;
}

// Index of the candidate with the lowest candidate_mean (the first on ties); -1 when empty.
int choose_by_replicate_means(const std::vector<SelectionCandidate>& candidates);

}  // namespace demfit::identify
