// The identification loop of docs/spec.md 3 (LS-OPT-like): iteration 0 is a space-filling design over the
// initial region including the initial point; every later iteration evaluates the previous
// predicted optimum plus maximin points in the SRSM subregion (or adaptive infill points),
// refits the RBF networks and minimises the predicted composite objective. Every run is looked
// up in the store first, so a resumed study regenerates the same points (all randomness is
// seeded from the study seed and the iteration) and repeats no finished run.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <string>

#include "demfit/identify/report.hpp"
#include "demfit/identify/safe_output.hpp"
#include "demfit/rbf_surrogate/adaptive_infill.hpp"
#include "demfit/rbf_surrogate/design.hpp"
#include "study_loop.hpp"

namespace demfit::identify {
namespace detail {

EvaluationRecord StudyLoop::make_record(int iteration, int point, const std::string& kind, const VectorXd& unit,
                                        const ParameterSet& parameters, const EvaluationOutcome& outcome) const {
  EvaluationRecord r;
  r.iteration = iteration;
  r.point = point;
  r.kind = kind;
  r.unit_x.assign(unit.data(), unit.data() + unit.size());
  r.parameters = parameters;
  r.wall_seconds = outcome.wall_seconds;
  r.ok = outcome.ok;
  r.error = outcome.error;
  r.objective = std::numeric_limits<double>::quiet_NaN();
  if (r.ok) {
    try {  // a curve that cannot be compared (missing, NaN, non-monotone) fails the run
      r.objective = objective_.objective(objective_.responses(outcome.curves));
      r.curves = outcome.curves;
      if (!std::isfinite(r.objective)) throw std::runtime_error("objective is not finite");
    } catch (const std::exception& e) {
      r.ok = false;
      r.error = e.what();
      r.curves.clear();
    }
  }
  return r;
}

void StudyLoop::evaluate_points(int iteration, const MatrixXd& points, const std::vector<std::string>& kinds) {
  evaluate_missing(iteration, points, kinds, model_, evaluator_);
  collect(iteration, points);
}

void StudyLoop::evaluate_missing(int iteration, const MatrixXd& points, const std::vector<std::string>& kinds,
                                 const Model& model, Evaluator& evaluator) {
  const int count = static_cast<int>(points.rows());
  std::vector<ParameterSet> pending;
  std::vector<int> pending_point;
  for (int i = 0; i < count; ++i) {
    const VectorXd unit = points.row(i).transpose();
    if (const EvaluationRecord* stored = store_.find_evaluation(iteration, i)) {
      if (stored->unit_x != std::vector<double>(unit.data(), unit.data() + unit.size()))
        throw std::runtime_error("study store: " + run_name(iteration, i) +
                                 " differs from the regenerated design; the store was written by another "
                                 "demfit build, start the study in a new --out folder");
      continue;  // finished (or failed) before: never repeated
    }
    ParameterSet parameters = detail::model_parameters(spec_, model, variables_, unit);
    if (iteration == 0 && kinds[i] == "initial" && options_.initial_run &&
        options_.initial_run->parameters == parameters) {
      record_evaluation(make_record(iteration, i, kinds[i], unit, parameters, options_.initial_run->outcome), i,
                        count, " (the initial-point check's run)");
      continue;  // evaluated by preflight_study with exactly these parameters
    }
    pending.push_back(std::move(parameters));
    pending_point.push_back(i);
  }
  if (pending.empty()) return;
  // One job per (point, experiment): the experiments of a point run in parallel too. A point is
  // recorded when its last experiment finishes.
  evaluator.evaluate_points(model, pending, [&](std::size_t p, const EvaluationOutcome& outcome) {
    const int i = pending_point[p];
    record_evaluation(make_record(iteration, i, kinds[i], points.row(i).transpose(), pending[p], outcome), i, count,
                      "");
  });
}

std::string StudyLoop::run_name(int iteration, int point) {
  if (iteration == kCheapLevelIteration) return "cheap level run " + std::to_string(point);
  return "run " + std::to_string(iteration) + "/" + std::to_string(point);
}

void StudyLoop::record_evaluation(const EvaluationRecord& record, int point, int points, const char* note) {
  store_.add_evaluation(record);
  ++evaluated_here_;
  if (record.iteration != kCheapLevelIteration) {
    ++study_runs_here_;
    evaluated_wall_ += record.wall_seconds;
  }
  if (options_.progress) {
    // The cheap level's runs are numbered within it; the study's within their iteration.
    const std::string where = record.iteration == kCheapLevelIteration
                                  ? "cheap level run " + std::to_string(point + 1) + "/" + std::to_string(points)
                                  : "iteration " + std::to_string(record.iteration) + " run " +
                                        std::to_string(point + 1) + "/" + std::to_string(points) + " " + record.kind;
    std::fprintf(stderr, "demfit: %s %s%s (%.2f s%s; %d runs in this process)\n", where.c_str(),
                 record.ok ? "objective " : "FAILED: ",
                 record.ok ? detail::format_number(record.objective).c_str() : record.error.c_str(),
                 record.wall_seconds, note, evaluated_here_);
  }
  if (options_.after_evaluation) options_.after_evaluation(evaluated_here_);
}

void StudyLoop::collect(int iteration, const MatrixXd& points) {
  // Collect this batch in point order (independent of the order runs finished in).
  VectorXd objectives(points.rows());
  for (int i = 0; i < points.rows(); ++i) {
    const EvaluationRecord* r = store_.find_evaluation(iteration, i);
    objectives[i] = r->ok ? r->objective : std::numeric_limits<double>::quiet_NaN();
    ++total_runs_;
    all_points_.push_back(points.row(i).transpose());
    if (!r->ok) {
      ++failed_runs_;
      if (first_error_.empty()) first_error_ = r->error;
      continue;
    }
    Run run{
        iteration, i, points.row(i).transpose(), objective_.responses(r->curves), r->objective, r->kind == "replicate"};
    runs_.push_back(std::move(run));
  }
  if (ask_tell_) ask_tell_->tell(points, objectives);
  if (runs_.empty())
    throw std::runtime_error("every run failed (" + std::to_string(total_runs_) + " runs); first error: " +
                             first_error_ + "; fix the model settings or narrow the variable bounds");
}

Box StudyLoop::fit_box(const Box& region) const {
  if (spec_.strategy != SamplingStrategy::srsm) return Box::unit(dims_);
  // Twice the subregion, shifted inside the unit box: neighbours just outside the subregion
  // still shape the fit, far-away early runs do not spoil the conditioning.
  Box box{region.lower, region.upper};
  for (int j = 0; j < dims_; ++j) {
    const double width = std::min(1.0, 2.0 * (region.upper(j) - region.lower(j)));
    double lower = 0.5 * (region.lower(j) + region.upper(j)) - 0.5 * width;
    lower = std::clamp(lower, 0.0, 1.0 - width);
    box.lower(j) = lower;
    box.upper(j) = lower + width;
  }
  return box;
}

std::optional<detail::ResponseSurrogate> StudyLoop::fit(const Box& box) const {
  // Runs inside the fit box, topped up with the nearest others to at least 2P (and n + 2).
  const int minimum = std::max(2 * spec_.points_per_iteration, dims_ + 2);
  const int maximum = std::max(minimum, 300);
  std::vector<VectorXd> units;
  std::vector<int> index;
  for (int i = 0; i < static_cast<int>(runs_.size()); ++i)
    if (!runs_[i].replicate) {
      units.push_back(runs_[i].unit);
      index.push_back(i);
    }
  // Within the box = within half its width of its centre; a re-run of the same point adds
  // nothing and would break the fit, so repeated points count once.
  const std::vector<int> chosen = detail::nearest_distinct(units, box.center(), 0.5 * box.width(), minimum, maximum);
  if (static_cast<int>(chosen.size()) < dims_ + 2) return std::nullopt;
  MatrixXd x(chosen.size(), dims_), y(chosen.size(), objective_.response_size());
  for (std::size_t r = 0; r < chosen.size(); ++r) {
    x.row(r) = runs_[index[chosen[r]]].unit.transpose();
    y.row(r) = runs_[index[chosen[r]]].responses.transpose();
  }
  try {
    return detail::ResponseSurrogate(x, y, box, spec_);
  } catch (const std::exception& e) {
    if (options_.progress)
      std::fprintf(stderr, "demfit: warning: surrogate fit failed (%s); using the best run\n", e.what());
    return std::nullopt;
  }
}

bool StudyLoop::budget_reached() {
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  char text[200];
  if (spec_.max_runs > 0 && total_runs_ + spec_.points_per_iteration > spec_.max_runs) {
    std::snprintf(text, sizeof text, "run budget reached (%d runs; stopping.max_runs %d)", total_runs_,
                  spec_.max_runs);
    budget_stop_kind_ = StopKind::run_budget;
  } else if (spec_.max_wall_seconds > 0.0 && wall >= spec_.max_wall_seconds) {
    std::snprintf(text, sizeof text, "wall-time budget reached (%.0f s; stopping.max_wall_seconds %.0f)", wall,
                  spec_.max_wall_seconds);
    budget_stop_kind_ = StopKind::wall_time_budget;
  } else {
    return false;
  }
  budget_stop_ = text;
  return true;
}

const Run* StudyLoop::best_run() const {
  const Run* best = nullptr;
  for (std::size_t i = 0; i < std::min(decision_runs_, runs_.size()); ++i)
    if (!best || runs_[i].objective < best->objective) best = &runs_[i];
  return best;
}

void StudyLoop::progress_iteration(int iteration, const IterationRecord& record, const Box& region) const {
  if (!options_.progress) return;
  const double mean_here = study_runs_here_ ? evaluated_wall_ / study_runs_here_ : 0.0;
  const int remaining = (spec_.max_iterations - iteration - 1) * spec_.points_per_iteration + 1;
  const double eta = mean_here * remaining / std::max(1, evaluator_.concurrency());
  std::fprintf(stderr,
               "demfit: iteration %d done: best objective %s, predicted %s, subregion size %.3g (mean range), "
               "runs %d (%d failed), ETA <= %s\n",
               iteration, detail::format_number(record.best_objective).c_str(),
               detail::format_number(record.predicted_objective).c_str(), region.width().mean(), total_runs_,
               failed_runs_, detail::format_duration(eta).c_str());
}

MatrixXd StudyLoop::infill(const VectorXd& optimum, int count, const Box& region, std::uint64_t seed,
                           int iteration) const {
  // Points already run (failed ones too: they are not worth repeating) plus the optimum about
  // to be run; SRSM spreads the new points by maximin distance to those inside the subregion.
  std::vector<VectorXd> existing;
  for (const VectorXd& p : all_points_)
    if (spec_.strategy != SamplingStrategy::srsm || region.contains(p, 1e-12)) existing.push_back(p);
  existing.push_back(optimum);
  MatrixXd existing_rows(existing.size(), dims_);
  for (std::size_t i = 0; i < existing.size(); ++i) existing_rows.row(i) = existing[i].transpose();
  if (spec_.strategy == SamplingStrategy::srsm)
    return rbf_surrogate::space_filling_augment(existing_rows, count, region, seed);
  // Adaptive infill: a scalar RBF model of the evaluated objective over the whole box.
  std::vector<int> unique;
  for (int i = 0; i < static_cast<int>(runs_.size()); ++i) {
    bool duplicate = false;
    for (int u : unique) duplicate = duplicate || detail::same_point(runs_[u].unit, runs_[i].unit);
    if (!duplicate) unique.push_back(i);
  }
  if (static_cast<int>(unique.size()) < dims_ + 2)
    return rbf_surrogate::space_filling_augment(existing_rows, count, region, seed);
  MatrixXd x(unique.size(), dims_), y(unique.size(), 1);
  for (std::size_t r = 0; r < unique.size(); ++r) {
    x.row(r) = runs_[unique[r]].unit.transpose();
    y(r, 0) = runs_[unique[r]].objective;
  }
  const auto model = rbf_surrogate::RbfNetwork::fit(x, y, detail::rbf_options(spec_));
  return rbf_surrogate::adaptive_infill(model, existing_rows, count, region, seed, iteration);
}

StudyResult StudyLoop::finish(int verification_iteration, bool converged, const Box& final_region) {
  decision_runs_ = runs_.size();
  // The answer holds a copy of its run: the selection and the interval check append to runs_.
  const Answer answer = this->answer(verification_iteration);
  const Run& best = answer.run;
  StudyResult result;
  result.best = store_.find_evaluation(best.iteration, best.point)->parameters;
  result.best_objective = best.objective;
  result.best_curves = store_.find_evaluation(best.iteration, best.point)->curves;
  result.iterations = verification_iteration;
  // The tolerance rule alone does not make a study converged (stop_reason.hpp).
  StopReason stopped = stop_reason(converged, spec_.max_iterations, store_.evaluations(), dims_);
  if (budget_stop_kind_) stopped = with_budget_stop(stopped, *budget_stop_kind_, budget_stop_);
  // The stable-answer rule says what it measured: the verification's gap to its prediction.
  if (const std::string note = stable_answer_note(); !note.empty())
    stopped.text = stopped.converged ? "converged (" + note + ")" : stopped.text + "; " + note;
  result.converged = stopped.converged;
  result.stop_reason = stopped.text;
  nlohmann::json uncertainty = nullptr;
  // Uncertainty at the best run: Jacobian and simulation noise from a linear
  // regression of the evaluated residuals over the runs near the optimum (see uncertainty.hpp).
  {
    const RunSample sample = uncertainty_sample(best, final_region);
    const auto estimate = estimate_uncertainty_from_runs(sample, spec_.variables);
    uncertainty = detail::uncertainty_json(spec_, estimate);
    std::string posterior_warning;  // Marginal intervals that stay right with poorly pinned parameters
    uncertainty["posterior"] =
        detail::posterior_json(spec_, sample, options_.output_dir, options_.plots, posterior_warning);
    if (options_.progress && !posterior_warning.empty())
      std::fprintf(stderr, "demfit: warning: posterior: %s\n", posterior_warning.c_str());
    const int runs_before_check = total_runs_;  // after the selection: its replicates lead to the answer
    if (spec_.interval_check.max_steps > 0 && uncertainty["posterior"].is_object())
      check_intervals(answer, sample, uncertainty);
    result.interval_check_runs = total_runs_ - runs_before_check;
    for (std::size_t j = 0; j < spec_.variables.size(); ++j) {
      const std::string& name = spec_.variables[j].name;
      result.ci_half_width[name] = estimate.ci_half_width[j];
      result.standard_error[name] = estimate.standard_error[j];
      if (estimate.unidentifiable[j]) result.unidentifiable.push_back(name);
      if (!estimate.least_squares_estimate.empty())
        result.least_squares_estimate[name] = estimate.least_squares_estimate[j];
    }
    for (const auto& v : spec_.variables)
      result.intervals[v.name] = reported_interval(uncertainty, v.name, result.best.at(v.name));
    result.correlation.assign(dims_, std::vector<double>(dims_));
    for (int i = 0; i < dims_; ++i)
      for (int j = 0; j < dims_; ++j) result.correlation[i][j] = estimate.correlation(i, j);
  }
  result.runs = total_runs_;  // the interval check's runs included
  result.failed_runs = failed_runs_;
  result.cheap_runs = spec_.cheap_level ? spec_.cheap_level->runs : 0;
  result.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  store_.put_result({{"best_iteration", best.iteration},
                     {"best_point", best.point},
                     {"best_objective", best.objective},
                     {"best_parameters", result.best},
                     {"best_variables", detail::variable_values(spec_, variables_, best.unit)},
                     {"runs", result.runs},
                     {"failed_runs", result.failed_runs},
                     {"iterations", result.iterations},
                     {"converged", stopped.converged},
                     {"stop_reason", stopped.text},
                     {"stop_kind", to_string(stopped.kind)},
                     {"final_selection", answer.record},
                     {"wall_seconds", result.wall_seconds},
                     {"cheap_level", cheap_level_summary()},
                     {"uncertainty", uncertainty}});
  const ReportSummary report = write_report(store_, options_.output_dir, options_.plots);
  if (options_.progress) {
    if (!report.plot_warning.empty()) std::fprintf(stderr, "demfit: warning: %s\n", report.plot_warning.c_str());
    std::fprintf(stderr, "demfit: study done: the answer's objective %s after %d runs (%d failed), %s; results in %s\n",
                 detail::format_number(best.objective).c_str(), result.runs, result.failed_runs, stopped.text.c_str(),
                 options_.output_dir.string().c_str());
  }
  return result;
}

MatrixXd StudyLoop::design(int iteration, const Box& region, const VectorXd& previous_optimum, std::uint64_t seed,
                           std::vector<std::string>& kinds) const {
  const int P = spec_.points_per_iteration;
  MatrixXd points(P, dims_);
  kinds.assign(P, "design");
  if (iteration == 0) {  // the initial point plus a maximin Latin hypercube over the initial region
    points.row(0) = rbf_surrogate::to_unit(variables_, detail::initial_values(spec_)).transpose();
    points.bottomRows(P - 1) = rbf_surrogate::latin_hypercube_maximin(P - 1, dims_, seed, region);
    kinds[0] = "initial";
  } else {  // the previous predicted optimum plus space-filling / infill points
    // When too few runs allowed a surrogate, the "optimum" is the best run itself: running it
    // again would repeat a deterministic result, so the whole batch goes to new points.
    const bool optimum_is_new = std::none_of(all_points_.begin(), all_points_.end(), [&](const VectorXd& p) {
      return detail::same_point(p, previous_optimum);
    });
    const int fresh = optimum_is_new ? P - 1 : P;
    if (optimum_is_new) {
      points.row(0) = previous_optimum.transpose();
      kinds[0] = "optimum";
    }
    points.bottomRows(fresh) = ask_tell_ ? ask_tell_->ask(fresh, previous_optimum.transpose(), seed)
                                         : infill(previous_optimum, fresh, region, seed, iteration);
  }
  return points;
}

IterationRecord StudyLoop::optimise(int iteration, const Box& region, const rbf_surrogate::SrsmState& state,
                                    std::uint64_t seed, const VectorXd& previous_optimum,
                                    double& predicted_at_previous) const {
  predicted_at_previous = std::numeric_limits<double>::quiet_NaN();
  IterationRecord record;
  record.iteration = iteration;
  record.region_center = detail::to_std(state.region.center);
  record.region_range = detail::to_std(state.region.range);
  VectorXd optimum;
  if (const auto surrogate = fit(fit_box(region))) {
    const auto result = detail::minimize_prediction(*surrogate, objective_, region, seed);
    optimum = result.x;
    record.predicted_objective = result.value;
    if (previous_optimum.size() == dims_) predicted_at_previous = surrogate->predicted_objective(previous_optimum, objective_);
  } else {  // too few successful runs to fit: stay at the best run
    optimum = best_run()->unit;
    record.predicted_objective = best_run()->objective;
  }
  record.predicted_optimum = detail::to_std(optimum);
  record.predicted_parameters = detail::variable_values(spec_, variables_, optimum);
  record.best_objective = best_run()->objective;
  record.runs_done = total_runs_;
  return record;
}

}  // namespace detail

StudyResult run_study(const StudySpec& spec, const Model& model, const RunOptions& options) {
  detail::check_parameter_names(spec, model);
  detail::check_declared_curves(spec, model);
  detail::check_experiments(spec, model);
  detail::StudyLoop loop(spec, model, options);
  // The resolved input beside the results (targets inline, defaults filled in).
  write_file_atomically(options.output_dir / "study_resolved.json", to_json(spec).dump(2) + "\n");
  return loop.run();
}

}  // namespace demfit::identify
