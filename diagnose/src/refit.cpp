// Re-identification of one candidate (base variables + the effect's): local starts, and the
// surrogate search when no candidate passed; see workflow.hpp and docs/diagnose.md, step 4.
#include <algorithm>
#include <string>

#include "demfit/diagnose/surrogate_start.hpp"
#include "demfit/diagnose/workflow.hpp"
#include "fit_context.hpp"
#include "text_format.hpp"

namespace demfit::diagnose::detail {

namespace {

// Residual tests and information criteria of a re-fit over `variables` (base + the effect's);
// true when it passes the criterion.
bool assess(const FitContext& c, Diagnosis& d, const std::vector<FitVariable>& variables, CandidateFit& f) {
  const int k = static_cast<int>(variables.size());
  f.analysis = analyse(f.fit, d.targets, k, c.dof_noise, c.options.alpha_named);
  f.criterion_chi_square = d.criterion_replicas > 0 ? detail::replicated_chi_square(
                                                          c, f.fit.parameters, variables, d.targets,
                                                          d.criterion_replicas, f.fit.chi_square, d.refit_evaluations)
                                                    : f.fit.chi_square;
  f.bic = bic(f.criterion_chi_square, k, c.points);
  f.aicc = aicc(f.criterion_chi_square, k, c.points);
  f.delta_bic = d.base_bic - f.bic;
  f.delta_aicc = d.base_aicc - f.aicc;
  // 4. Name an effect only if the criterion favours it AND its residual is noise.
  f.passes = f.delta_bic > d.bic_threshold && !f.analysis.structural;
  return f.passes;
}

// The variables of a re-fit (base + the effect's) and the fixed set without the effect's
// parameters. Starts: 0 the base optimum + the score test's estimate, 1 study initial values + the
// estimate, 2 and later study initial values + mid-range effect.
std::vector<FitVariable> refit_variables(const Diagnosis& d, const EffectCandidate& effect, const ScreeningScore& score,
                                         int start, identify::ParameterSet& fixed) {
  std::vector<FitVariable> vars = d.base_variables;
  if (start == 0)
    for (auto& v : vars) v.start = d.base.parameters.at(v.name);
  for (std::size_t j = 0; j < effect.parameters.size(); ++j) {
    const auto& p = effect.parameters[j];
    const double towards = (p.upper - p.off_value) >= (p.off_value - p.lower) ? p.upper : p.lower;
    const double mid = 0.5 * (p.off_value + towards);
    vars.push_back({p.name, p.lower, p.upper, start < 2 ? score.start[j] : mid});
    fixed.erase(p.name);
  }
  return vars;
}

// Fits from `vars`' starts, assesses the fit and keeps it in `f` by replaces_kept_start. True when
// it passes; a start that cannot be evaluated is noted and skipped.
bool try_refit_start(const FitContext& c, Diagnosis& d, const identify::ParameterSet& fixed,
                     const std::vector<FitVariable>& vars, const Eigen::MatrixXd* jacobian, CandidateFit& f,
                     bool& fitted) {
  const FitOptions fit = stage_fit_options(c.options, c.started, "re-fit base + " + f.effect);
  try {
    CandidateFit trial;
    trial.effect = f.effect;
    trial.fit = fit_least_squares(c.model, fixed, vars, d.targets, fit, jacobian);
    d.refit_evaluations += trial.fit.evaluations;
    const bool passes = assess(c, d, vars, trial);
    if (!fitted || replaces_kept_start(f, trial)) f = std::move(trial);
    fitted = true;
    return passes;
  } catch (const std::exception& e) {
    d.notes.push_back("effect '" + f.effect + "': a re-identification start failed (" + e.what() + ")");
    return false;
  }
}

// The search's point itself as a re-fit (its one run's residual, `known_residual` when the search
// ran it, else run here; no Jacobian is needed by the assessment), so the smoothed optimum is
// judged before a local descent follows one run's noise.
bool assess_surrogate_point(const FitContext& c, Diagnosis& d, const identify::ParameterSet& fixed,
                            const std::vector<FitVariable>& vars, const Eigen::VectorXd& known_residual,
                            CandidateFit& f, bool& fitted) {
  CandidateFit trial;
  trial.effect = f.effect;
  trial.fit.parameters = fixed;
  for (const auto& v : vars) {
    trial.fit.parameters[v.name] = v.start;
    trial.fit.values.push_back(v.start);
  }
  Eigen::VectorXd residual = known_residual;
  if (residual.size() == 0) {
    residual = residuals_at(c.model, {trial.fit.parameters}, d.targets, c.options.fit).front();
    d.refit_evaluations += 1;
  }
  if (residual.size() == 0) return false;
  trial.fit.residual = residual;
  trial.fit.chi_square = residual.squaredNorm();
  trial.fit.evaluations = 1;
  const bool passes = assess(c, d, vars, trial);
  if (!fitted || replaces_kept_start(f, trial)) f = std::move(trial);
  fitted = true;
  return passes;
}

// When no local start passed: a surrogate search over base + effect variables
// (surrogate_start.hpp), told the base optimum and the base search's point (effect off) and the
// kept fit's point; its point of lowest predicted chi-square is assessed as it is and, if it does
// not pass, starts a local fit.
bool refit_from_surrogate_search(const FitContext& c, Diagnosis& d, const EffectCandidate& effect,
                                 const ScreeningScore& score, CandidateFit& f, bool& fitted) {
  identify::ParameterSet fixed = c.fixed;
  std::vector<FitVariable> vars = refit_variables(d, effect, score, 0, fixed);
  Eigen::VectorXd search_residual;
  std::vector<double> base_point = d.base.values;
  for (const auto& p : effect.parameters) base_point.push_back(p.off_value);
  std::vector<std::vector<double>> known{base_point};
  std::vector<double> known_chi_squares{d.base.chi_square};
  if (!d.base_search_values.empty()) {
    // The base search's point with the effect off, at the mean of its fresh runs: the nested
    // search starts from the best base point known, not only from the local fit's.
    std::vector<double> searched = d.base_search_values;
    for (const auto& p : effect.parameters) searched.push_back(p.off_value);
    known.push_back(std::move(searched));
    known_chi_squares.push_back(d.base_search_criterion_chi_square);
  }
  if (fitted) {
    known.push_back(f.fit.values);
    known_chi_squares.push_back(f.fit.chi_square);
  }
  const int runs = c.options.refit_search_evaluations;
  progress(c.options, c.started, "surrogate search over base + " + effect.name + " (" + std::to_string(runs) + " runs)");
  try {
    const SurrogateStart s =
        surrogate_search_start(c.model, fixed, vars, d.targets, c.options.fit, runs, c.options.fit.seed, known,
                               known_chi_squares);
    d.refit_evaluations += s.evaluations;
    search_residual = s.run_residual;
    std::string at;
    for (std::size_t j = 0; j < vars.size(); ++j) {
      vars[j].start = s.values[j];
      at += (j ? ", " : "") + vars[j].name + " " + format("%.6g", s.values[j]);
    }
    d.notes.push_back("effect '" + effect.name + "': no local re-fit start passed; a surrogate search (" +
                      std::to_string(s.evaluations) + " runs) predicts chi-square " +
                      format("%.4g", s.predicted_chi_square) + " at " + at + " (its run: " +
                      format("%.4g", s.run_chi_square) + ")");
  } catch (const std::exception& e) {
    d.notes.push_back("effect '" + effect.name + "': the surrogate search failed (" + e.what() + ")");
    return false;
  }
  if (assess_surrogate_point(c, d, fixed, vars, search_residual, f, fitted)) return true;
  return try_refit_start(c, d, fixed, vars, nullptr, f, fitted);
}

}  // namespace

// Re-identifies base variables + one effect's parameters. Start 0: the base optimum with the
// score test's linearised estimate, its Jacobian assembled from the base fit's and the screening
// sensitivities (no finite differences). The augmented problem can have local minima (e.g. a toe
// shift traded against a lower rate), so if that start does not pass the criterion, further
// starts follow (refit_variables).
// Kept: the first start that passes, else the one of lowest criterion chi-square
// (replaces_kept_start). Returns false if every start failed.
bool refit_candidate(const FitContext& c, Diagnosis& d, const EffectCandidate& effect, const ScreeningScore& score,
                     CandidateFit& f) {
  f.effect = effect.name;
  const auto k = static_cast<Eigen::Index>(d.base_variables.size() + effect.parameters.size());
  const Eigen::Index rows = d.base.residual.size();
  // Seed Jacobian in normalised coordinates (d r / d u = d r / d value * range).
  Eigen::MatrixXd seed;
  if (score.sensitivity.rows() == rows) {
    seed.resize(rows, k);
    seed.leftCols(d.base.jacobian.cols()) = d.base.jacobian;
    for (std::size_t j = 0; j < effect.parameters.size(); ++j)
      seed.col(d.base.jacobian.cols() + static_cast<Eigen::Index>(j)) =
          score.sensitivity.col(static_cast<Eigen::Index>(j)) *
          (effect.parameters[j].upper - effect.parameters[j].lower);
  }
  bool fitted = false;
  for (int start = 0; start < std::max(1, c.options.refit_starts); ++start) {
    identify::ParameterSet fixed = c.fixed;
    const std::vector<FitVariable> vars = refit_variables(d, effect, score, start, fixed);
    if (try_refit_start(c, d, fixed, vars, start == 0 && seed.size() > 0 ? &seed : nullptr, f, fitted)) return true;
  }
  return fitted;
}

// 3c. When no re-fitted candidate passed: the surrogate search for each of them, in screening
// order, the search's fit replacing the kept one by replaces_kept_start (a candidate whose every
// local start failed gets its first fit here).
void search_failed_refits(const FitContext& c, Diagnosis& d, const std::vector<EffectCandidate>& candidates,
                          const std::vector<int>& order) {
  for (const int index : order) {
    const EffectCandidate& effect = candidates[static_cast<std::size_t>(index)];
    auto kept = std::find_if(d.refits.begin(), d.refits.end(), [&](const auto& r) { return r.effect == effect.name; });
    CandidateFit f;
    bool fitted = kept != d.refits.end();
    if (fitted) f = *kept;
    f.effect = effect.name;
    refit_from_surrogate_search(c, d, effect, d.screening[static_cast<std::size_t>(index)], f, fitted);
    if (!fitted) continue;
    if (kept != d.refits.end())
      *kept = std::move(f);
    else
      d.refits.push_back(std::move(f));
  }
}

}  // namespace demfit::diagnose::detail
