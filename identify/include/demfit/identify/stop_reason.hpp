#pragma once
// Why a study stopped, in one line, and whether it may call itself converged. The tolerance rule
// (design change and objective change both below tolerance) is necessary but not sufficient: a
// study whose runs mostly failed, or whose design points all fell onto one or two points, meets
// the tolerances without having searched. Such a study ends with a warning, never "converged".
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "demfit/identify/study_store.hpp"

namespace demfit::identify {

// Largest share of failed runs with which a study may still say "converged" (20 %).
inline constexpr double kMaxFailedShareForConvergence = 0.2;

// What ended a study. The warnings and the report dispatch on the kind; the text is for people.
enum class StopKind {
  converged,         // tolerances met with enough successful, distinct runs
  iteration_limit,   // stopping.max_iterations reached
  run_budget,        // the user's cap stopping.max_runs
  wall_time_budget,  // the user's cap stopping.max_wall_seconds
  failed_runs,       // too many failed runs to call anything converged
  collapsed_design,  // fewer distinct successful points than variables + 1
};

// The kind's name as stored in the study result ("stop_kind"): "converged", "iteration_limit",
// "run_budget", "wall_time_budget", "failed_runs", "collapsed_design".
std::string_view to_string(StopKind kind);
std::optional<StopKind> stop_kind_from_string(std::string_view name);
// The stop kind of a stored study result: its "stop_kind" field, or for a result written before
// that field existed, the kind its stop_reason text begins with.
std::optional<StopKind> stop_kind_of(const nlohmann::json& result);

struct StopReason {
  StopKind kind = StopKind::iteration_limit;
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
// A user budget ended the loop before the tolerances were met: unless the runs themselves make the
// study "NOT converged", the stop is the budget's, with its text and the words "without converging".
StopReason with_budget_stop(StopReason stopped, StopKind budget, const std::string& budget_text);

}  // namespace demfit::identify
