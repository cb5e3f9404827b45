// Choice among replicated candidates (see final_selection.hpp).
#include "demfit/identify/final_selection.hpp"

#include <cmath>

namespace demfit::identify {

double candidate_mean(const SelectionCandidate& candidate) {
  double sum = candidate.objective;
  int count = 1;
  for (const double o : candidate.replicate_objectives)
    if (std::isfinite(o)) {
      sum += o;
      ++count;
    }
  return sum / count;
}

int choose_by_replicate_means(const std::vector<SelectionCandidate>& candidates) {
  int chosen = -1;
  double lowest = 0.0;
  for (int c = 0; c < static_cast<int>(candidates.size()); ++c) {
    const double mean = candidate_mean(candidates[c]);
    if (chosen < 0 || mean < lowest) {
      chosen = c;
      lowest = mean;
    }
  }
  return chosen;
}

}  // namespace demfit::identify
