// Why a study stopped (see stop_reason.hpp).
#include "demfit/identify/stop_reason.hpp"

#include <cmath>
#include <cstdio>

namespace demfit::identify {
namespace {

bool same_unit_point(const std::vector<double>& a, const std::vector<double>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (std::abs(a[i] - b[i]) > 1e-9) return false;
  return true;
}

}  // namespace

int distinct_successful_points(const std::vector<EvaluationRecord>& runs) {
  std::vector<const std::vector<double>*> distinct;
  for (const auto& r : runs) {
    if (!r.ok) continue;
    bool seen = false;
    for (const auto* d : distinct) seen = seen || same_unit_point(*d, r.unit_x);
    if (!seen) distinct.push_back(&r.unit_x);
  }
  return static_cast<int>(distinct.size());
}

StopReason stop_reason(bool tolerances_met, int max_iterations, const std::vector<EvaluationRecord>& runs,
                       int variables) {
  int failed = 0;
  for (const auto& r : runs) failed += r.ok ? 0 : 1;
  const int total = static_cast<int>(runs.size());
  char text[240];
  if (total > 0 && failed > kMaxFailedShareForConvergence * total) {
    std::snprintf(text, sizeof text,
                  "NOT converged: %d of %d runs failed (more than %.0f %%); read the first error in evaluations.csv",
                  failed, total, 100.0 * kMaxFailedShareForConvergence);
    return {false, text};
  }
  const int distinct = distinct_successful_points(runs);
  if (distinct < variables + 1) {
    std::snprintf(text, sizeof text,
                  "NOT converged: the design collapsed onto %d distinct successful point%s for %d variable%s; widen "
                  "the initial region or check the variables' bounds",
                  distinct, distinct == 1 ? "" : "s", variables, variables == 1 ? "" : "s");
    return {false, text};
  }
  if (tolerances_met) return {true, "converged (design and objective change below tolerance)"};
  std::snprintf(text, sizeof text, "iteration limit reached (%d) without converging", max_iterations);
  return {false, text};
}

}  // namespace demfit::identify
