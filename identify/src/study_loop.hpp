#pragma once
// The study loop's state (study_loop.cpp: the iterations; study_loop_uncertainty.cpp: the
// uncertainty sample and the interval-end checks after the loop). Private to identify.
#include <chrono>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Dense>
#include <nlohmann/json.hpp>

#include "demfit/identify/evaluator.hpp"
#include "demfit/identify/interval_check.hpp"
#include "demfit/identify/stop_reason.hpp"
#include "demfit/identify/objective.hpp"
#include "demfit/identify/study.hpp"
#include "demfit/identify/study_store.hpp"
#include "demfit/identify/uncertainty.hpp"
#include "demfit/rbf_surrogate/srsm.hpp"
#include "response_surrogate.hpp"
#include "study_strategy.hpp"
#include "study_support.hpp"

namespace demfit::identify::detail {

using Eigen::MatrixXd;
using Eigen::VectorXd;
using rbf_surrogate::Box;

struct Run {
  int iteration = 0, point = 0;
  VectorXd unit;
  VectorXd responses;
  double objective = 0.0;
  bool replicate = false;  // a nudged re-run (selection, interval check): kept out of surrogate fits (a near-duplicate)
};

// The study's answer (final_selection) and what choosing it used up, which the interval check
// after it must not reuse: the selection's iteration and its replicates' round-off nudges.
struct Answer {
  Run run;
  nlohmann::json record = nullptr;  // the choice, for the store (null for lowest_run)
  int next_free_iteration = 0;      // the first iteration after the verification and the selection
  int nudges_used = 0;              // round-off nudges 0 .. nudges_used - 1 went to the selection
};

class StudyLoop {
 public:
  StudyLoop(const StudySpec& spec, const Model& model, const RunOptions& options)
      : spec_(spec),
        model_(model),
        options_(options),
        objective_(spec.targets),
        variables_(detail::rbf_variables(spec)),
        dims_(static_cast<int>(spec.variables.size())),
        pool_(model, options.jobs, options.threads_per_job, static_cast<unsigned long>(spec.seed)),
        evaluator_(options.evaluator ? *options.evaluator : static_cast<Evaluator&>(pool_)),
        store_(StudyStore::open_for_run(options.output_dir / "study.db", spec, options.resume, options.resolved_model)) {}

  StudyResult run();

 private:
  // The cheap level's runs (study_loop_cheap_level.cpp), before iteration 0: a maximin Latin
  // hypercube over the whole box, each run looked up in the store first like every other run.
  // Their successful runs for the expected-improvement strategy (none without a cheap level).
  rbf_surrogate::FidelityLevel run_cheap_level();
  // The cheap level's runs, failures and wall time for the stored result (null without one).
  nlohmann::json cheap_level_summary() const;
  // Runs `points` of `iteration` (their kinds in `kinds`) and collects them into runs_.
  void evaluate_points(int iteration, const MatrixXd& points, const std::vector<std::string>& kinds);
  // The runs of `points` not yet in the store, evaluated on `model` through `evaluator` and stored
  // as each finishes; a stored run is never repeated, and one whose point differs from `points`
  // means another build wrote the store (an error). Iteration 0's initial point takes the
  // initial-point check's run (RunOptions::initial_run) when its parameters are exactly these.
  void evaluate_missing(int iteration, const MatrixXd& points, const std::vector<std::string>& kinds,
                        const Model& model, Evaluator& evaluator);
  // "run 3/2", "cheap level run 4": a stored run in messages.
  static std::string run_name(int iteration, int point);
  void collect(int iteration, const MatrixXd& points);
  // Stores one finished run, prints its progress line, calls the test hook.
  void record_evaluation(const EvaluationRecord& record, int point, int points, const char* note);
  EvaluationRecord make_record(int iteration, int point, const std::string& kind, const VectorXd& unit,
                               const ParameterSet& parameters, const EvaluationOutcome& outcome) const;
  std::optional<detail::ResponseSurrogate> fit(const Box& fit_box) const;
  Box fit_box(const Box& region) const;
  const Run* best_run() const;
  // True (and budget_stop_ says why) when a user cap (stopping.max_runs, max_wall_seconds) ends the loop.
  bool budget_reached();
  MatrixXd design(int iteration, const Box& region, const VectorXd& previous_optimum, std::uint64_t seed,
                  std::vector<std::string>& kinds) const;
  // The iteration's record; `predicted_at_previous` = the new surrogate's objective at
  // `previous_optimum` (NaN when there is none or no surrogate could be fitted).
  IterationRecord optimise(int iteration, const Box& region, const rbf_surrogate::SrsmState& state,
                           std::uint64_t seed, const VectorXd& previous_optimum, double& predicted_at_previous) const;
  // The objective of the latest decision run at `unit` (NaN when none succeeded there).
  double objective_at(const VectorXd& unit) const;
  // The stable-answer rule (study_loop_stopping.hpp): whether the verification run at `optimum`
  // agrees with its prediction (records the gap in verification_gap_), and whether an iteration's
  // answer is stable (the run at the previous prediction agreed, the optimum stopped moving).
  bool verification_agrees(int iteration, const VectorXd& optimum, double predicted);
  bool answer_stable(const IterationRecord& record, const VectorXd& previous_optimum, double previous_predicted,
                     double predicted_at_previous) const;
  // The last verification's gap against stopping.verification_tolerance, for the stop text
  // (empty without the rule or without a successful verification run).
  std::string stable_answer_note() const;
  MatrixXd infill(const VectorXd& optimum, int count, const Box& region, std::uint64_t seed, int iteration) const;
  StudyResult finish(int verification_iteration, bool converged, const Box& final_region);
  // The study's answer by its final_selection method.
  Answer answer(int verification_iteration);
  // The best distinct decision runs, best first (at most `count`).
  std::vector<int> selection_candidates(int count) const;
  // Re-runs the candidates as round-off replicates in `iteration` and returns the one with the
  // lowest mean objective (final_selection.hpp); `record` describes the choice for the store.
  Run select_by_replicates(const ReplicateSelection& selection, int iteration, nlohmann::json& record);
  // Re-runs the runs_ at `candidates` `replicates` times each in `iteration`; the lowest mean wins.
  Run replicate_and_choose(const std::vector<int>& candidates, int replicates, int iteration, nlohmann::json& record);
  // The answer rule when the verification run is much worse than the best run (final_selection.hpp).
  Run settle_much_worse_answer(int iteration, nlohmann::json& record);
  // The verification run (the final predicted optimum), or the best run when it failed; `record`
  // says which (PredictedOptimumSelection).
  Run predicted_optimum_run(int verification_iteration, nlohmann::json& record) const;
  RunSample uncertainty_sample(const Run& best, const Box& final_region) const;
  // Runs at the posterior intervals' ends (interval_check.hpp); widens uncertainty.posterior.
  void check_intervals(const Answer& answer, const RunSample& sample, nlohmann::json& uncertainty);
  IntervalCheckInput interval_check_input(const Answer& answer, const RunSample& sample,
                                          const nlohmann::json& posterior) const;
  VectorXd profile_point(const VectorXd& best_unit, int variable, double unit_value) const;
  void progress_iteration(int iteration, const IterationRecord& record, const Box& region) const;

  const StudySpec& spec_;
  const Model& model_;
  const RunOptions& options_;
  CompositeObjective objective_;
  std::vector<rbf_surrogate::Variable> variables_;
  int dims_;
  ThreadPoolEvaluator pool_;
  Evaluator& evaluator_;
  StudyStore store_;
  // expected_improvement only (study_strategy.hpp); made by run() after the cheap level's runs
  std::unique_ptr<detail::StudyStrategy> ask_tell_;
  std::vector<Run> runs_;                            // successful runs, in (iteration, point) order
  // The first runs_ that decide the answer and its posterior; the interval check's runs come after
  // and only measure the interval.
  std::size_t decision_runs_ = std::numeric_limits<std::size_t>::max();
  std::vector<VectorXd> all_points_;  // every run (failed ones too), in order
  int total_runs_ = 0, failed_runs_ = 0, evaluated_here_ = 0;
  // The study model's runs evaluated in this process and their wall time (the ETA's mean run).
  int study_runs_here_ = 0;
  double evaluated_wall_ = 0.0;
  std::string first_error_;
  std::string budget_stop_;                   // the budget that ended the loop, empty when none did
  std::optional<StopKind> budget_stop_kind_;  // its kind
  // The last verification's relative gap to its prediction (stable-answer rule; NaN before one).
  double verification_gap_ = std::numeric_limits<double>::quiet_NaN();
  double gap_floor_ = std::numeric_limits<double>::min();  // 1e-6 of iteration 0's best objective
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

}  // namespace demfit::identify::detail
