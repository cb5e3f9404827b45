#pragma once
// The identification loop: design -> evaluate -> fit RBF networks -> minimise the
// predicted composite objective -> reduce the region (SRSM) -> repeat until the docs/spec.md 3 stopping
// rule. Every evaluation is committed to a SQLite store as it finishes; --resume replays it.
#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "demfit/identify/evaluator.hpp"
#include "demfit/identify/model.hpp"
#include "demfit/identify/reported_interval.hpp"
#include "demfit/identify/study_spec.hpp"

namespace demfit::identify {

class Evaluator;

// One evaluation of the study's initial point and the complete parameters it was run with.
struct InitialRun {
  ParameterSet parameters;
  EvaluationOutcome outcome;
};

struct RunOptions {
  int jobs = 1;                      // simulations evaluated at once (threads of the evaluator pool)
  int threads_per_job = 1;           // OpenMP threads given to each simulation (EvaluationContext)
  bool resume = false;               // continue the study found in output_dir/study.db
  std::filesystem::path output_dir;  // results + study.db; created if missing
  bool plots = true;                 // PNG plots via gnuplot (skipped with a warning if missing)
  bool progress = true;              // progress lines on stderr
  // Test hook: called (serialised) after each evaluation has been committed to the store, with
  // the number of evaluations done in this process. An exception thrown here stops the study
  // at once and propagates out of run_study (simulates a kill after k runs).
  std::function<void(int evaluations_done)> after_evaluation;
  // Where the runs are evaluated: nullptr = a ThreadPoolEvaluator of `jobs` threads in this
  // process; otherwise this evaluator (e.g. an MPI evaluator), which must outlive the
  // call. Results do not depend on the choice.
  Evaluator* evaluator = nullptr;
  // What is simulated, resolved (DEM: the case with defaults filled in; see model_fingerprint.hpp).
  // Recorded in a new store; --resume refuses a store whose recorded model differs. null = none.
  nlohmann::json resolved_model;
  // The initial point's run when the caller has already evaluated it (preflight_study): stored as
  // run 0/0 instead of evaluating it again, if its parameters are exactly those of that run.
  std::optional<InitialRun> initial_run;
  // The model of the study's cheap level (study_spec.hpp CheapLevelSpec; the caller builds it from
  // cheap_level_study(spec)), run on a pool of `jobs` threads of this process. Required when the
  // study declares a cheap level, ignored otherwise; must outlive the call.
  const Model* cheap_model = nullptr;
};

struct StudyResult {
  ParameterSet best;  // all model parameters of the best evaluated run
  double best_objective = 0.0;
  int runs = 0;  // evaluations in the store (finished + failed), the interval check's included
  int failed_runs = 0;
  int interval_check_runs = 0;  // of `runs`: replicates and interval-end checks after the loop
  int cheap_runs = 0;           // runs of the cheap level (not in `runs`; failed ones included)
  int iterations = 0;
  // The interval every output reports (reported_interval.hpp: posterior marginal, else linearised).
  std::map<std::string, ReportedInterval> intervals;
  // The linearised estimate (conditional on the other variables), kept for comparison and tests.
  std::map<std::string, double> ci_half_width;  // ~95 % confidence half-width per variable
  std::map<std::string, double> standard_error;
  std::vector<std::string> unidentifiable;  // variables the data cannot pin down (linearised)
  // Centre of the local least-squares fit of the runs near the best one (uncertainty.hpp),
  // per variable; empty when too few runs.
  std::map<std::string, double> least_squares_estimate;
  std::vector<std::vector<double>> correlation;  // variables x variables, study order
  double wall_seconds = 0.0;
  CurveSet best_curves;    // the best run's curves as simulated
  bool converged = false;  // stopped by the tolerances with enough distinct, successful runs (stop_reason.hpp)
  std::string stop_reason;  // one line: why the study stopped
};

// Runs (or resumes) a study. Throws std::runtime_error when every run failed, when the store
// belongs to another study, or when a store exists and resume is false.
StudyResult run_study(const StudySpec& spec, const Model& model, const RunOptions& options);

}  // namespace demfit::identify
