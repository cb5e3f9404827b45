#include "demfit/identify/study_warnings.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>

#include "demfit/identify/objective.hpp"
#include "demfit/identify/reported_interval.hpp"
#include "demfit/identify/stop_reason.hpp"
#include "demfit/identify/study_answer.hpp"

namespace demfit::identify {
namespace {

std::string number(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.4g", value);
  return text;
}

// Noise sigma from second differences: for white noise of variance s^2 on a smooth curve,
// E[(y[i+1] - 2 y[i] + y[i-1])^2] = 6 s^2.
double second_difference_noise(const std::vector<double>& y) {
  if (y.size() < 3) return 0.0;
  double sum = 0.0;
  for (std::size_t i = 1; i + 1 < y.size(); ++i) {
    const double d = y[i + 1] - 2.0 * y[i] + y[i - 1];
    sum += d * d;
  }
  return std::sqrt(sum / (6.0 * static_cast<double>(y.size() - 2)));
}

void bound_warnings(const StudySpec& spec, const EvaluationRecord& best, std::vector<std::string>& warnings) {
  for (const auto& v : spec.variables) {
    const auto found = best.parameters.find(v.name);
    if (found == best.parameters.end()) continue;
    const double tolerance = 0.005 * (v.upper - v.lower);
    if (found->second - v.lower <= tolerance || v.upper - found->second <= tolerance)
      warnings.push_back("variable '" + v.name + "' = " + number(found->second) + " lies on its " +
                         (found->second - v.lower <= tolerance ? "lower" : "upper") + " bound [" + number(v.lower) +
                         ", " + number(v.upper) +
                         "]: the optimum may lie outside; widen the bounds or check units and fill");
  }
}

double largest_y(const EvaluationRecord& run, const std::string& curve) {
  const auto found = run.curves.find(curve);
  if (found == run.curves.end() || found->second.y.empty()) return 0.0;
  return *std::max_element(found->second.y.begin(), found->second.y.end());
}

void quasi_static_warnings(const std::vector<EvaluationRecord>& runs, const EvaluationRecord& best,
                           std::vector<std::string>& warnings) {
  int checked = 0, dynamic = 0;
  for (const auto& r : runs) {
    if (!r.ok || !r.curves.count(kQuasiStaticCurve)) continue;
    ++checked;
    dynamic += largest_y(r, kQuasiStaticCurve) > 1.0;
  }
  const double best_ratio = largest_y(best, kQuasiStaticCurve);
  if (best_ratio > 1.0)
    warnings.push_back("the best run is far from quasi-static: its kinetic energy reached " + number(best_ratio) +
                       " x the case's limit on kinetic/elastic energy, so inertia shapes the curve; lower the loading "
                       "speed (e.g. pellet.piston_speed) or raise the damping");
  else if (dynamic > 0)
    warnings.push_back(std::to_string(dynamic) + " of " + std::to_string(checked) +
                       " runs were far from quasi-static (kinetic/elastic energy above the case's limit); the best "
                       "run was not, but the surrogate was fitted to them too");
}

// RMS misfit of `run` against target `t` at the target's x, in the target's y units; none when
// the run lacks the curve or it cannot be resampled there.
std::optional<double> target_rms(const TargetSpec& t, const EvaluationRecord& run) {
  const auto curve = run.curves.find(t.curve);
  if (!run.ok || curve == run.curves.end() || curve->second.x.size() < 2) return std::nullopt;
  std::vector<double> simulated;
  try {
    simulated = resample_monotone(curve->second, t.data.x);
  } catch (const std::exception&) { return std::nullopt; }
  double sum = 0.0;
  for (std::size_t i = 0; i < simulated.size(); ++i)
    sum += (simulated[i] - t.data.y[i]) * (simulated[i] - t.data.y[i]);
  return std::sqrt(sum / static_cast<double>(simulated.size()));
}

// The answer misses target `t` far above its noise. The likely cause, in order: another stored
// run fits this target clearly better (within the noise, or by less than 70 % of the answer's
// miss) -> the search has not converged; no run fits better -> model, units or fill.
std::string misfit_warning(const TargetSpec& t, const TargetMisfit& m, const std::vector<EvaluationRecord>& runs,
                           const EvaluationRecord& answer) {
  const EvaluationRecord* better = nullptr;
  double better_rms = m.rms;
  for (const auto& r : runs) {
    if (&r == &answer || (r.iteration == answer.iteration && r.point == answer.point)) continue;
    const auto rms = target_rms(t, r);
    if (rms && *rms < better_rms) {
      better = &r;
      better_rms = *rms;
    }
  }
  const std::string miss = "target '" + t.name + "': the answer misses the data by RMS " + number(m.rms) + " " +
                           m.y_label + ", " + number(m.rms / m.noise) + " x the noise of the data (" +
                           number(m.noise) + ")";
  if (better && (better_rms <= 3.0 * m.noise || better_rms < 0.7 * m.rms))
    return miss + ": the search has not converged: run " + std::to_string(better->iteration) + "/" +
           std::to_string(better->point) + " fits it with RMS " + number(better_rms) +
           "; resume with a larger stopping.max_iterations or a wider initial region";
  return miss + ", and no stored run fits it clearly better: the model, the units or the fill do not match the "
                "measurement";
}

// The warning for a study that ended without converging, by what ended it (stop_reason.hpp).
void stop_warning(const StudySpec& spec, const nlohmann::json& result, std::vector<std::string>& warnings) {
  const std::string stopped = result.value("stop_reason", std::string());
  // A result without a recognisable stop (written by hand or by a test) that did not converge
  // stopped at the iteration limit: the loop's only other ending.
  const StopKind kind =
      stop_kind_of(result).value_or(result.value("converged", false) ? StopKind::converged : StopKind::iteration_limit);
  switch (kind) {
    case StopKind::converged:
      return;
    case StopKind::failed_runs:
    case StopKind::collapsed_design:
      warnings.push_back("the study " + stopped);
      return;
    case StopKind::run_budget:
    case StopKind::wall_time_budget:
      warnings.push_back("stopped by the " + stopped +
                         "; resume with a larger stopping.max_runs or stopping.max_wall_seconds");
      return;
    case StopKind::iteration_limit:
      warnings.push_back("stopped at the iteration limit (" + std::to_string(spec.max_iterations) +
                         ") without converging; resume with a larger stopping.max_iterations");
      return;
  }
}

// Variables the data cannot pin down (reported_interval.hpp: a 95 % interval wider than half the
// bounds, or an effect on the curves below the noise): other values fit as well, so the answer is
// one point of a set. Such an answer can fit and still not transfer to another condition (a drum
// calibrated at one speed and run at another), which is why the warning says what pins it.
void identifiability_warning(const StudySpec& spec, const nlohmann::json& result, const EvaluationRecord& best,
                             std::vector<std::string>& warnings) {
  const nlohmann::json uncertainty = result.value("uncertainty", nlohmann::json());
  if (!uncertainty.is_object()) return;
  std::string names;
  int count = 0;
  for (const auto& v : spec.variables) {
    const auto found = best.parameters.find(v.name);
    if (found == best.parameters.end() || reported_interval(uncertainty, v.name, found->second).identifiable) continue;
    names += (count++ ? ", '" : "'") + v.name + "'";
  }
  if (count == 0) return;
  warnings.push_back(std::string(count == 1 ? "variable " : "variables ") + names + (count == 1 ? " is" : " are") +
                     " not identifiable from these data (95 % interval wider than half the bounds, or an effect "
                     "below the noise): other values fit as well, so the answer may not hold at another condition; "
                     "fix " + (count == 1 ? "it" : "them") + " or add an experiment that moves " +
                     (count == 1 ? "it" : "them") + " (another speed, fill or load path)");
}

}  // namespace

StudyDiagnostics study_diagnostics(const StudySpec& spec, const std::vector<EvaluationRecord>& runs,
                                   const std::vector<IterationRecord>& iterations, const EvaluationRecord* best,
                                   const std::optional<nlohmann::json>& result) {
  StudyDiagnostics d;
  if (!best) return d;
  bound_warnings(spec, *best, d.warnings);
  quasi_static_warnings(runs, *best, d.warnings);
  if (result) stop_warning(spec, *result, d.warnings);
  if (result) identifiability_warning(spec, *result, *best, d.warnings);
  const EvaluationRecord* verification = nullptr;
  for (const auto& r : runs)
    if (r.kind == "verification" && r.ok) verification = &r;
  if (verification && !iterations.empty()) {
    const double predicted = iterations.back().predicted_objective;
    const double scale = std::max(std::abs(predicted), std::abs(verification->objective));
    // Differences far below the objectives the study has seen (an exact fit: 1e-18 vs 3e-19) are no news.
    double largest = 0.0;
    for (const auto& r : runs)
      if (r.ok && std::isfinite(r.objective)) largest = std::max(largest, std::abs(r.objective));
    const double difference = std::abs(verification->objective - predicted);
    if (std::isfinite(predicted) && difference > 0.5 * scale && difference > 1e-6 * largest)
      d.warnings.push_back("the verification run's objective " + number(verification->objective) +
                           " is far from the surrogate's prediction " + number(predicted) +
                           ": the surrogate is not reliable near the optimum");
  }
  for (const auto& t : spec.targets) {
    if (t.metric != CurveMetric::mse) continue;
    const auto rms = target_rms(t, *best);
    if (!rms) continue;
    TargetMisfit m{t.name, t.data.y_label, *rms, second_difference_noise(t.data.y)};
    if (m.noise > 0.0 && m.rms > 3.0 * m.noise) d.warnings.push_back(misfit_warning(t, m, runs, *best));
    d.misfits.push_back(m);
  }
  return d;
}

StudyDiagnostics study_diagnostics(const StudyStore& store) {
  const StudySpec spec = parse_study(store.study_json(), store.path().parent_path());
  const auto runs = store.evaluations();
  const auto result = store.result();
  const EvaluationRecord* best = study_answer(runs, result, store.path().string()).run;
  return study_diagnostics(spec, runs, store.iterations(), best, result);
}

}  // namespace demfit::identify
