// The uncertainty after the loop: the runs the posterior is fitted to, and the interval-end
// checks (interval_check.hpp) with the local surrogate profile their retries run.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "demfit/rbf_surrogate/optimize.hpp"
#include "study_loop.hpp"

namespace demfit::identify::detail {

RunSample StudyLoop::uncertainty_sample(const Run& best, const Box& final_region) const {
  // The 3P distinct runs nearest the best run (at least 2n + 3; distance in final-subregion
  // widths): the last subregion alone is often so small that the simulation noise swamps every
  // slope, the last few iterations' runs give the regression leverage while staying local.
  const int maximum = std::max(2 * dims_ + 3, 3 * spec_.points_per_iteration);
  const int minimum = maximum;
  std::vector<VectorXd> units;
  for (std::size_t i = 0; i < std::min(decision_runs_, runs_.size()); ++i) units.push_back(runs_[i].unit);
  const std::vector<int> chosen = nearest_distinct(units, best.unit, final_region.width(), minimum, maximum);
  RunSample sample;
  sample.unit_points.resize(chosen.size(), dims_);
  sample.residuals.resize(chosen.size(), objective_.residual_size());
  for (std::size_t r = 0; r < chosen.size(); ++r) {
    sample.unit_points.row(r) = runs_[chosen[r]].unit.transpose();
    sample.residuals.row(r) = objective_.residuals(runs_[chosen[r]].responses).transpose();
  }
  sample.best_unit = best.unit;
  sample.best_residuals = objective_.residuals(best.responses);
  sample.unit_per_physical = unit_per_physical(spec_, variables_, best.unit);
  return sample;
}

VectorXd StudyLoop::profile_point(const VectorXd& best_unit, int variable, double unit_value) const {
  VectorXd point = best_unit;
  point(variable) = unit_value;
  if (dims_ == 1) return point;
  // A local fit around the best point, twice the check's distance wide (at least 5 % of each
  // range): a fit over the whole box let far-away runs bend the valley (pellet study: NORMK 1.10 at
  // SHEARK 0.3285 against 1.38 at 0.3135), and every run so far, the checks included, is used.
  // On noisy runs this profile can still miss (NORMK 1.26-1.31 there), which is why it is only
  // the retry; each distance first runs the others where the end's last run fitted.
  const double half = std::max(2.0 * std::abs(unit_value - best_unit(variable)), 0.05);
  const Box box{(best_unit.array() - half).cwiseMax(0.0).matrix(), (best_unit.array() + half).cwiseMin(1.0).matrix()};
  const auto surrogate = fit(box);
  if (!surrogate) return point;
  // The surrogate's optimum over the other coordinates (inside the box) with this one held.
  const std::uint64_t seed = iteration_seed(spec_.seed, 1000 + variable);
  return minimize_prediction(*surrogate, objective_, box, seed, HeldCoordinate{variable, unit_value}).x;
}

IntervalCheckInput StudyLoop::interval_check_input(const Answer& answer, const RunSample& sample,
                                                   const nlohmann::json& posterior) const {
  const Run& best = answer.run;
  IntervalCheckInput input;
  input.best_unit = best.unit;
  input.best_objective = best.objective;
  input.fitted_runs = sample.unit_points;
  input.first_replicate = answer.nudges_used;  // trajectories the selection did not use
  for (const auto& v : spec_.variables) {
    input.lower.push_back(posterior["variables"][v.name]["lower_95"].get<double>());
    input.upper.push_back(posterior["variables"][v.name]["upper_95"].get<double>());
  }
  // Other runs at (almost) the best point: the run-to-run spread there.
  for (std::size_t i = 0; i < decision_runs_; ++i)
    if (!(runs_[i].iteration == best.iteration && runs_[i].point == best.point) &&
        (runs_[i].unit - best.unit).cwiseAbs().maxCoeff() <= kNearbyRadius)
      input.nearby_objectives.push_back(runs_[i].objective);
  return input;
}

void StudyLoop::check_intervals(const Answer& answer, const RunSample& sample, nlohmann::json& uncertainty) {
  const Run& best = answer.run;
  const int first_iteration = answer.next_free_iteration;
  nlohmann::json& posterior = uncertainty["posterior"];
  const IntervalCheckInput input = interval_check_input(answer, sample, posterior);
  const std::vector<double>&lower = input.lower, &upper = input.upper;
  // Each profile is a fresh fit (profile_point), so a retried end's profile knows the run that missed.
  const auto profile = [&](int variable, double unit_value) { return profile_point(best.unit, variable, unit_value); };
  const auto evaluate = [&](int batch, const MatrixXd& points, const std::vector<std::string>& kinds) {
    if (options_.progress)
      std::fprintf(stderr, "demfit: interval check, step %d: %d runs\n", batch + 1, static_cast<int>(points.rows()));
    evaluate_points(first_iteration + batch, points, kinds);
    VectorXd objectives(points.rows());
    for (int i = 0; i < points.rows(); ++i) {
      const EvaluationRecord* r = store_.find_evaluation(first_iteration + batch, i);
      objectives(i) = r->ok ? r->objective : std::numeric_limits<double>::quiet_NaN();
    }
    return objectives;
  };
  const IntervalCheckOutcome outcome =
      check_interval_ends(spec_.variables, input, spec_.interval_check, profile, evaluate);
  for (std::size_t j = 0; j < spec_.variables.size(); ++j) {
    const auto& v = spec_.variables[j];
    nlohmann::json& entry = posterior["variables"][v.name];
    entry["sampled_lower_95"] = lower[j];
    entry["sampled_upper_95"] = upper[j];
    entry["lower_95"] = outcome.lower[j].end;
    entry["upper_95"] = outcome.upper[j].end;
    entry["widened_by_interval_check"] = outcome.lower[j].widened || outcome.upper[j].widened;
    const double lower_unit = rbf_surrogate::to_unit(variables_[j], outcome.lower[j].end);
    const double upper_unit = rbf_surrogate::to_unit(variables_[j], outcome.upper[j].end);
    if (upper_unit - lower_unit > 0.5) entry["unidentifiable"] = true;  // the posterior's own rule
  }
  posterior["interval_check"] = interval_check_json(outcome, spec_.variables);
  if (options_.progress)
    for (std::size_t j = 0; j < spec_.variables.size(); ++j)
      std::fprintf(stderr, "demfit: interval check: %s [%s, %s] -> [%s, %s] (%s)\n", spec_.variables[j].name.c_str(),
                   format_number(lower[j]).c_str(), format_number(upper[j]).c_str(),
                   format_number(outcome.lower[j].end).c_str(), format_number(outcome.upper[j].end).c_str(),
                   outcome.lower[j].checked || outcome.upper[j].checked
                       ? ("spread threshold " + format_number(outcome.threshold)).c_str()
                       : "not checked: within the runs the posterior was fitted to");
}

}  // namespace demfit::identify::detail
