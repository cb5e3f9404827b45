// Interval-end checks (see interval_check.hpp).
#include "demfit/identify/interval_check.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "demfit/identify/roundoff_replicates.hpp"
#include "study_support.hpp"

namespace demfit::identify {
namespace {

double to_unit(const VariableSpec& v, double value) { return rbf_surrogate::to_unit(detail::rbf_variable(v), value); }

double to_model(const VariableSpec& v, double unit) { return rbf_surrogate::from_unit(detail::rbf_variable(v), unit); }

// One interval end walking outwards from the best point.
struct EndWalk {
  int variable = 0;
  double direction = 1.0;    // +1 upper end, −1 lower end
  double distance = 0.0;     // unit distance from the best point of the next check
  int step = 0;              // distances tried so far
  bool retrying = false;     // the run at this distance fitted worse; one retry with the other attempt follows
  Eigen::VectorXd last_fit;  // the last run of this end that fitted (the best point at first)
  bool active = true;
  Eigen::VectorXd last_point;  // the last run's unit point
  IntervalEndCheck* record = nullptr;
  double end_distance = 0.0;    // unit distance of the posterior's own end from the best point
  double rejected_unit = -1.0;  // back-checking: the first distance's value, which fitted worse
};

constexpr double kSamePoint = 1e-3;  // unit: a retry this close to the rejected run would repeat it

// Closes an end whose run at `unit` fitted worse than the spread: a later distance bounds the
// interval there; at the first distance the posterior's own end stands. Except when that first
// distance lay beyond the end (the end closer to the best point than first_step): the end itself
// has not been run, so the walk reopens once to run it, and decide() extends the interval to `unit`
// if it fits (Table 1 set-up, seed 6: NORMK end 0.886 "confirmed" by runs at 0.813, the generating
// 0.875 between them). An end at or beyond the answer (interval_check.hpp) needs no such run: the
// answer itself is that end's run and fits, so the interval reaches to `unit` at once.
void close_rejected(EndWalk& walk, double unit, const VariableSpec& v) {
  if (walk.step == 0 && walk.rejected_unit < 0.0 && walk.end_distance < walk.distance - 1e-12) {
    if (walk.end_distance < kSamePoint) {
      walk.active = false;
      walk.record->end = to_model(v, unit);
      return;
    }
    walk.rejected_unit = unit;
    walk.distance = walk.end_distance;
    walk.retrying = false;
    return;
  }
  walk.active = false;
  if (walk.step > 0) walk.record->end = to_model(v, unit);
}

// Decides one end after its check run at `unit` (the checked coordinate) with objective `objective`.
// A run that fits worse is retried once at the same distance on the surrogate's profile.
void decide(EndWalk& walk, double unit, double objective, double threshold, int max_steps, const VariableSpec& v) {
  const bool fits = std::isfinite(objective) && objective <= threshold;
  walk.record->values.push_back(to_model(v, unit));
  walk.record->objectives.push_back(objective);
  walk.record->fits.push_back(fits);
  if (!fits) {
    if (walk.retrying) return close_rejected(walk, unit, v);
    walk.retrying = true;
    return;
  }
  walk.retrying = false;
  if (walk.rejected_unit >= 0.0) {  // the posterior's end fits: the interval reaches to the rejected run
    walk.active = false;
    walk.record->end = to_model(v, walk.rejected_unit);
    return;
  }
  walk.last_fit = walk.last_point;  // along a valley: the next distance starts where this one fitted
  const bool at_bound = unit <= 0.0 || unit >= 1.0;
  if (at_bound || walk.step + 1 >= max_steps) {  // never fitted worse: the data do not close this end
    walk.active = false;
    walk.record->end = walk.direction > 0 ? v.upper : v.lower;  // the bound itself, not its round trip
    return;
  }
  ++walk.step;
  walk.distance *= 2.0;
}

}  // namespace

IntervalCheckOutcome check_interval_ends(const std::vector<VariableSpec>& variables, const IntervalCheckInput& input,
                                         const IntervalCheckSpec& settings, const ProfilePoint& profile,
                                         const EvaluateBatch& evaluate) {
  const int n = static_cast<int>(variables.size());
  const Eigen::VectorXd& best_unit = input.best_unit;
  const std::vector<double>&lower = input.lower, &upper = input.upper;
  if (best_unit.size() != n || static_cast<int>(lower.size()) != n || static_cast<int>(upper.size()) != n ||
      (input.fitted_runs.rows() > 0 && input.fitted_runs.cols() != n))
    throw std::invalid_argument("interval check: variables, best point and intervals have different sizes");
  IntervalCheckOutcome out;
  out.lower.resize(n);
  out.upper.resize(n);
  out.threshold = input.best_objective;
  out.all_variables = settings.all_variables;
  out.nearby_objectives = input.nearby_objectives;
  for (double o : input.nearby_objectives)
    if (std::isfinite(o)) out.threshold = std::max(out.threshold, o);
  std::vector<EndWalk> walks;
  for (int j = 0; j < n; ++j) {
    out.lower[j].end = lower[j];
    out.upper[j].end = upper[j];
    const bool extrapolated = settings.all_variables || input.fitted_runs.rows() == 0 ||
                              to_unit(variables[j], lower[j]) < input.fitted_runs.col(j).minCoeff() - 1e-12 ||
                              to_unit(variables[j], upper[j]) > input.fitted_runs.col(j).maxCoeff() + 1e-12;
    for (double direction : {-1.0, 1.0}) {
      IntervalEndCheck& record = direction < 0 ? out.lower[j] : out.upper[j];
      record.end = direction < 0 ? lower[j] : upper[j];
      const double end_unit = std::clamp(to_unit(variables[j], record.end), 0.0, 1.0);
      const double end_offset = direction * (end_unit - best_unit(j));  // < kSamePoint: at or beyond the answer
      record.checked = extrapolated || end_offset < kSamePoint;
      if (!record.checked) continue;
      EndWalk walk;
      walk.variable = j;
      walk.direction = direction;
      walk.end_distance = std::max(end_offset, 0.0);
      walk.distance = std::max(walk.end_distance, settings.first_step);
      walk.last_fit = best_unit;
      walk.record = &record;
      walks.push_back(walk);
    }
  }
  for (int batch = 0;; ++batch) {
    std::vector<EndWalk*> active;
    std::vector<Eigen::VectorXd> planned;
    for (EndWalk& w : walks) {
      while (w.active) {  // a closed end may reopen at once as the check of the posterior's own end
        const double unit = std::clamp(best_unit(w.variable) + w.direction * w.distance, 0.0, 1.0);
        Eigen::VectorXd point = w.retrying ? profile(w.variable, unit) : w.last_fit;
        point(w.variable) = unit;
        if (w.retrying && (point - w.last_point).cwiseAbs().maxCoeff() < kSamePoint) {
          close_rejected(w, unit, variables[w.variable]);  // the re-drawn profile would repeat the run
          continue;
        }
        w.last_point = point;
        active.push_back(&w);
        planned.push_back(point);
        break;
      }
    }
    if (active.empty()) break;
    const int replicates = batch == 0 ? settings.replicates : 0;
    Eigen::MatrixXd points(replicates + static_cast<int>(active.size()), n);
    std::vector<std::string> kinds(points.rows(), "interval_check");
    for (int r = 0; r < replicates; ++r) {
      points.row(r) = replicate_point(best_unit, input.first_replicate + r).transpose();
      kinds[r] = "replicate";
    }
    for (std::size_t a = 0; a < active.size(); ++a)
      points.row(replicates + static_cast<int>(a)) = planned[a].transpose();
    const Eigen::VectorXd objectives = evaluate(batch, points, kinds);
    out.runs += static_cast<int>(points.rows());
    for (int r = 0; r < replicates; ++r) {
      out.replicate_objectives.push_back(objectives(r));
      if (std::isfinite(objectives(r))) out.threshold = std::max(out.threshold, objectives(r));
    }
    for (std::size_t a = 0; a < active.size(); ++a)
      decide(*active[a], planned[a](active[a]->variable), objectives(replicates + static_cast<int>(a)), out.threshold,
             settings.max_steps, variables[active[a]->variable]);
  }
  for (int j = 0; j < n; ++j) {  // the check only widens
    out.lower[j].end = std::min(out.lower[j].end, lower[j]);
    out.upper[j].end = std::max(out.upper[j].end, upper[j]);
    out.lower[j].widened = out.lower[j].end < lower[j];
    out.upper[j].widened = out.upper[j].end > upper[j];
  }
  return out;
}

nlohmann::json interval_check_json(const IntervalCheckOutcome& outcome, const std::vector<VariableSpec>& variables) {
  const auto finite_or_null = [](double x) { return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(nullptr); };
  const auto end_json = [&](const IntervalEndCheck& e) {
    nlohmann::json checks = nlohmann::json::array();
    for (std::size_t k = 0; k < e.values.size(); ++k)
      checks.push_back({{"value", e.values[k]}, {"objective", finite_or_null(e.objectives[k])}, {"fits", e.fits[k]}});
    return nlohmann::json{{"checked", e.checked}, {"checks", checks}, {"end", e.end}, {"widened", e.widened}};
  };
  nlohmann::json replicates = nlohmann::json::array(), nearby = nlohmann::json::array();
  for (double o : outcome.replicate_objectives) replicates.push_back(finite_or_null(o));
  for (double o : outcome.nearby_objectives) nearby.push_back(finite_or_null(o));
  nlohmann::json per_variable = nlohmann::json::object();
  for (std::size_t j = 0; j < variables.size(); ++j)
    per_variable[variables[j].name] = {{"lower", end_json(outcome.lower[j])}, {"upper", end_json(outcome.upper[j])}};
  const std::string scope = outcome.all_variables
                                ? "for each variable"
                                : "for each variable with an interval end beyond the runs the posterior was fitted to";
  return {
      {"method", scope + ": a run at each end (the other variables where that end's last fitting run had them, the "
                         "best point at first; retried once on the local surrogate's profile), stepping outwards "
                         "while the run's objective is within the spread of nudged re-runs of the best point and the "
                         "runs near it"},
      {"replicate_objectives", replicates},
      {"nearby_objectives", nearby},
      {"threshold", outcome.threshold},
      {"runs", outcome.runs},
      {"variables", per_variable}};
}

}  // namespace demfit::identify
