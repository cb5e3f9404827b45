#pragma once
// The stable-answer rule of the study loop (stopping.verification_tolerance, study_spec.hpp).
// Every iteration after the first runs the previous predicted optimum, so each iteration tests
// the surrogate where it matters: the answer is stable when that run agrees with its prediction
// and the new optimum has stopped moving. Then one more run, the verification at the new
// optimum, must agree too before the study calls itself converged.
//
// "Agrees" means a relative gap |f(run) - f_predicted| / f_predicted at most the tolerance. The
// objective is a mean of N squared residuals; at the optimum they are the data's noise, so the
// objective is sigma^2 chi^2_N / N with relative standard deviation sqrt(2/N). A gap below that
// is smaller than what another draw of the same measurement would change, which is why
// docs/study_format.md recommends sqrt(2/N) (0.18 for the 60-point pellet curve). A move of the
// optimum whose predicted gain is below the same fraction cannot be told apart by runs either: it
// counts as no move, so a variable the targets pin only weakly (a flat valley) does not keep the
// loop going.
#include <algorithm>
#include <cmath>

namespace demfit::identify::detail {

// |evaluated - predicted| relative to |predicted|, but to no less than `floor` (objective
// differences far below the study's first objectives are round-off, not news).
inline double relative_gap(double evaluated, double predicted, double floor) {
  return std::abs(evaluated - predicted) / std::max(std::abs(predicted), floor);
}

// Whether a run at a predicted optimum agrees with the prediction within `tolerance`.
inline bool agrees_with_prediction(double evaluated, double predicted, double floor, double tolerance) {
  return std::isfinite(evaluated) && std::isfinite(predicted) && relative_gap(evaluated, predicted, floor) <= tolerance;
}

// Whether the optimum stopped moving: it moved less than `design_tolerance` (fraction of every
// range), or the surrogate predicts the previous optimum within `tolerance` (relative) of the new
// one, so runs could not tell the two apart.
inline bool optimum_settled(double design_change, double design_tolerance, double predicted_at_previous,
                            double predicted_at_new, double floor, double tolerance) {
  if (design_change < design_tolerance) return true;
  return std::isfinite(predicted_at_previous) && std::isfinite(predicted_at_new) &&
         (predicted_at_previous - predicted_at_new) / std::max(std::abs(predicted_at_new), floor) <= tolerance;
}

}  // namespace demfit::identify::detail
