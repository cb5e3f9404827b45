// A study says "converged" only when the tolerances were met with enough distinct, successful
// runs (stop_reason.hpp): most runs failed, or the design collapsed onto a point, is a warning.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>
#include <vector>

#include "demfit/identify/stop_reason.hpp"

using namespace demfit::identify;

namespace {

EvaluationRecord evaluated_run(std::vector<double> unit, bool ok) {
  EvaluationRecord r;
  r.unit_x = std::move(unit);
  r.ok = ok;
  r.objective = ok ? 1.0 : NAN;
  return r;
}

std::vector<EvaluationRecord> spread_runs(int count) {
  std::vector<EvaluationRecord> runs;
  for (int i = 0; i < count; ++i) runs.push_back(evaluated_run({0.1 * i, 0.05 * i}, true));
  return runs;
}

}  // namespace

TEST_CASE("met tolerances over distinct successful runs are reported as converged") {
  const StopReason r = stop_reason(true, 10, spread_runs(13), 2);
  CHECK(r.converged);
  CHECK(r.kind == StopKind::converged);
  CHECK(r.text.rfind("converged", 0) == 0);
}

TEST_CASE("the iteration limit is reported with the limit, not as converged") {
  const StopReason r = stop_reason(false, 7, spread_runs(13), 2);
  CHECK_FALSE(r.converged);
  CHECK(r.kind == StopKind::iteration_limit);
  CHECK(r.text == "iteration limit reached (7) without converging");
}

TEST_CASE("a study with 11 of 13 runs failed never says converged") {
  auto runs = spread_runs(13);
  for (int i = 0; i < 11; ++i) runs[i].ok = false;
  const StopReason r = stop_reason(true, 10, runs, 2);
  CHECK_FALSE(r.converged);
  CHECK(r.kind == StopKind::failed_runs);
  CHECK(r.text.find("11 of 13 runs failed") != std::string::npos);
}

TEST_CASE("a failed share at the stated limit still converges, one run above it does not") {
  auto runs = spread_runs(10);
  runs[0].ok = runs[1].ok = false;  // 20 %: at the limit
  CHECK(stop_reason(true, 10, runs, 2).converged);
  runs[2].ok = false;  // 30 %
  CHECK_FALSE(stop_reason(true, 10, runs, 2).converged);
}

TEST_CASE("a design collapsed onto the start point never says converged") {
  std::vector<EvaluationRecord> runs(9, evaluated_run({0.3, 0.7}, true));
  runs.push_back(evaluated_run({0.3 + 1e-12, 0.7}, true));  // round-off apart: the same point
  CHECK(distinct_successful_points(runs) == 1);
  const StopReason r = stop_reason(true, 10, runs, 2);
  CHECK_FALSE(r.converged);
  CHECK(r.kind == StopKind::collapsed_design);
  CHECK(r.text.find("collapsed onto 1 distinct successful point") != std::string::npos);
}

TEST_CASE("a user budget replaces the iteration-limit stop but never a failed or collapsed study") {
  const StopReason limit = stop_reason(false, 7, spread_runs(13), 2);
  const StopReason budget = with_budget_stop(limit, StopKind::run_budget, "run budget reached (13 runs)");
  CHECK(budget.kind == StopKind::run_budget);
  CHECK(budget.text == "run budget reached (13 runs) without converging");
  auto runs = spread_runs(13);
  for (int i = 0; i < 11; ++i) runs[i].ok = false;
  const StopReason failed = stop_reason(false, 7, runs, 2);
  CHECK(with_budget_stop(failed, StopKind::wall_time_budget, "wall-time budget reached").kind == StopKind::failed_runs);
  const StopReason converged = stop_reason(true, 7, spread_runs(13), 2);
  CHECK(with_budget_stop(converged, StopKind::run_budget, "run budget reached").converged);
}

TEST_CASE("every stop kind is stored by a name that reads back as the same kind") {
  for (StopKind kind : {StopKind::converged, StopKind::iteration_limit, StopKind::run_budget,
                        StopKind::wall_time_budget, StopKind::failed_runs, StopKind::collapsed_design}) {
    CHECK(stop_kind_from_string(to_string(kind)) == kind);
    CHECK(stop_kind_of(nlohmann::json{{"stop_kind", to_string(kind)}, {"stop_reason", "text not read"}}) == kind);
  }
  CHECK_FALSE(stop_kind_from_string("budget reached").has_value());
}

TEST_CASE("a result stored without a stop kind is read by the text its stop reason begins with") {
  const auto kind_of = [](const char* text) { return stop_kind_of(nlohmann::json{{"stop_reason", text}}); };
  CHECK(kind_of("run budget reached (9 runs; stopping.max_runs 9) without converging") == StopKind::run_budget);
  CHECK(kind_of("wall-time budget reached (60 s; stopping.max_wall_seconds 60) without converging") ==
        StopKind::wall_time_budget);
  CHECK(kind_of("iteration limit reached (7) without converging") == StopKind::iteration_limit);
  CHECK(kind_of("NOT converged: 7 of 13 runs failed") == StopKind::failed_runs);
  CHECK(kind_of("NOT converged: the design collapsed onto 1 distinct successful point") == StopKind::collapsed_design);
  CHECK_FALSE(kind_of("something else").has_value());
}
