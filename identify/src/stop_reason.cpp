// Why a study stopped (see stop_reason.hpp).
#include "demfit/identify/stop_reason.hpp"

#include <cmath>
#include <cstdio>
#include <utility>

namespace demfit::identify {
namespace {

bool same_unit_point(const std::vector<double>& a, const std::vector<double>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (std::abs(a[i] - b[i]) > 1e-9) return false;
  return true;
}

constexpr std::pair<StopKind, std::string_view> kKindNames[] = {
    {StopKind::converged, "converged"},     {StopKind::iteration_limit, "iteration_limit"},
    {StopKind::run_budget, "run_budget"},   {StopKind::wall_time_budget, "wall_time_budget"},
    {StopKind::failed_runs, "failed_runs"}, {StopKind::collapsed_design, "collapsed_design"},
};

}  // namespace

std::string_view to_string(StopKind kind) {
  for (const auto& [k, name] : kKindNames)
    if (k == kind) return name;
  return "unknown";
}

std::optional<StopKind> stop_kind_from_string(std::string_view name) {
  for (const auto& [k, n] : kKindNames)
    if (n == name) return k;
  return std::nullopt;
}

std::optional<StopKind> stop_kind_of(const nlohmann::json& result) {
  if (!result.is_object()) return std::nullopt;
  const auto kind = result.find("stop_kind");
  if (kind != result.end() && kind->is_string()) return stop_kind_from_string(kind->get<std::string>());
  // Results stored before "stop_kind" existed: the texts this file and the loop wrote then.
  const std::string text = result.value("stop_reason", std::string());
  const auto starts = [&](std::string_view prefix) { return text.rfind(prefix, 0) == 0; };
  if (starts("converged")) return StopKind::converged;
  if (starts("iteration limit")) return StopKind::iteration_limit;
  if (starts("run budget")) return StopKind::run_budget;
  if (starts("wall-time budget")) return StopKind::wall_time_budget;
  if (starts("NOT converged: the design collapsed")) return StopKind::collapsed_design;
  if (starts("NOT converged")) return StopKind::failed_runs;
  return std::nullopt;
}

StopReason with_budget_stop(StopReason stopped, StopKind budget, const std::string& budget_text) {
  if (stopped.converged || stopped.kind == StopKind::failed_runs || stopped.kind == StopKind::collapsed_design)
    return stopped;
  return {budget, false, budget_text + " without converging"};
}

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
    return {StopKind::failed_runs, false, text};
  }
  const int distinct = distinct_successful_points(runs);
  if (distinct < variables + 1) {
    std::snprintf(text, sizeof text,
                  "NOT converged: the design collapsed onto %d distinct successful point%s for %d variable%s; widen "
                  "the initial region or check the variables' bounds",
                  distinct, distinct == 1 ? "" : "s", variables, variables == 1 ? "" : "s");
    return {StopKind::collapsed_design, false, text};
  }
  if (tolerances_met) return {StopKind::converged, true, "converged (design and objective change below tolerance)"};
  std::snprintf(text, sizeof text, "iteration limit reached (%d) without converging", max_iterations);
  return {StopKind::iteration_limit, false, text};
}

}  // namespace demfit::identify
