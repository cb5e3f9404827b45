#pragma once
// Why a study stopped, in one line, and whether it may call itself converged. The tolerance rule
// (design change and objective change both below tolerance) is necessary but not sufficient: a
// study whose runs mostly failed, or whose design points all fell onto one or two points, meets
// the tolerances without having searched. Such a study ends with a warning, never "converged".
#include <string>
#include <vector>

#include "demfit/identify/study_store.hpp"

namespace demfit::identify {

// Largest share of failed runs with which a study may still say "converged" (20 %).
inline constexpr double kMaxFailedShareForConvergence = 0.2;

struct StopReason {
  bool converged = false;
  std::string text;  // e.g. "converged (design and objective change below tolerance)"
};

// Distinct successful design points among `runs` (points closer than 1e-9 in unit coordinates
// are one point).
int distinct_successful_points(const std::vector<EvaluationRecord>& runs);

// The stop reason from the tolerance rule and the runs so far; `variables` = the study's
// dimension (a design with fewer than variables + 1 distinct successful points has collapsed:
// no surrogate could be fitted through it).
StopReason stop_reason(bool tolerances_met, int max_iterations, const std::vector<EvaluationRecord>& runs,
                       int variables);

}  // namespace demfit::identify
