// The diagnosis workflow; see workflow.hpp and docs/diagnose.md.
#include "demfit/diagnose/workflow.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>
#include <set>
#include <stdexcept>

namespace demfit::diagnose {

const char* verdict_text(Verdict verdict) {
  switch (verdict) {
    case Verdict::no_missing_effect: return "no missing effect";
    case Verdict::effect_identified: return "missing effect identified";
    case Verdict::unexplained_structural: return "unexplained structural residual";
  }
  return "?";
}

double bic(double chi_square, int parameters, int points) { return chi_square + parameters * std::log(points); }

double aicc(double chi_square, int parameters, int points) {
  const double k = parameters;
  const double denominator = points - k - 1.0;
  return chi_square + 2.0 * k + (denominator > 0.0 ? 2.0 * k * (k + 1.0) / denominator : 1e300);
}

namespace {

template <typename... Args>
std::string format(const char* fmt, Args... args) {
  char buffer[400];
  std::snprintf(buffer, sizeof buffer, fmt, args...);
  return buffer;
}

std::string tests_text(const ResidualAnalysis& a) {
  return format("runs p = %.3g, lag-1 autocorrelation %.3f (p = %.3g), variance ratio %.3g (p = %.3g), "
                "smooth structure p = %.3g",
                a.runs.p_value, a.autocorrelation.lag1, a.autocorrelation.p_value, a.variance.ratio,
                a.variance.p_value, a.smooth.p_value);
}

std::vector<FitTarget> make_targets(const identify::StudySpec& study, double given_sigma, std::vector<std::string>& notes) {
  std::vector<FitTarget> targets;
  for (const auto& t : study.targets) {
    if (t.metric != identify::CurveMetric::mse)
      throw std::runtime_error("diagnose: target '" + t.name +
                               "': metric curve_mapping is not supported by diagnose yet; use \"mse\" for this target");
    FitTarget f{t.name, t.curve, t.data, 1.0};
    if (given_sigma > 0.0) {
      f.sigma = given_sigma;
    } else {
      f.sigma = estimate_noise_sigma(t.data.x, t.data.y);
      double scale = 0.0;
      for (double y : t.data.y) scale = std::max(scale, std::abs(y));
      const double floor = 1e-9 * std::max(scale, 1e-300);
      if (f.sigma < floor) {
        f.sigma = floor;
        notes.push_back("target '" + t.name + "': the data look noise-free; noise level floored at 1e-9 of max|y| (give --noise)");
      }
    }
    targets.push_back(f);
  }
  if (targets.empty()) throw std::runtime_error("diagnose: the study has no targets; add one under \"targets\"");
  return targets;
}

ResidualAnalysis analyse(const FitResult& fit, const std::vector<FitTarget>& targets, int fitted, double dof_noise,
                         double alpha) {
  std::vector<ResidualSegment> segments;
  Eigen::Index k = 0;
  for (const auto& t : targets) {
    ResidualSegment s{t.name, t.data.x, {}, t.sigma};
    for (std::size_t i = 0; i < t.data.x.size(); ++i) s.residual.push_back(fit.residual(k++) * t.sigma);
    segments.push_back(std::move(s));
  }
  return analyse_residuals(segments, fitted, dof_noise, alpha);
}

void check_model_accepts(const identify::Model& model, const std::vector<EffectCandidate>& candidates) {
  const auto names = model.parameter_names();
  const std::set<std::string> known(names.begin(), names.end());
  for (const auto& c : candidates)
    for (const auto& p : c.parameters)
      if (!known.count(p.name))
        throw std::runtime_error("diagnose: effect '" + c.name + "': the model has no parameter '" + p.name +
                                 "'; remove the effect with --effects or use a model that implements it");
}

std::string summarise(const Diagnosis& d) {
  const ResidualAnalysis& a = d.base_analysis;
  std::string where;
  if (a.worst_region >= 0)
    where = "; largest misfit in " + a.regions[a.worst_region].label +
            format(" (RMS/sigma %.3g)", a.regions[a.worst_region].rms_over_sigma);
  const std::string base_numbers = format("base fit RMS %.4g, max %.4g, noise sigma %.4g", a.rms, a.max_abs, a.sigma);
  switch (d.verdict) {
    case Verdict::no_missing_effect:
      return "No missing effect: the base residual is consistent with noise (" + tests_text(a) + "); " +
             base_numbers + ".";
    case Verdict::effect_identified: {
      const CandidateFit& c = d.refits[d.chosen];
      return "Missing effect: '" + c.effect + "'" + format(" (delta BIC %.4g > %.3g, delta AICc %.4g). ", c.delta_bic, d.bic_threshold, c.delta_aicc) +
             "Residual before: " + tests_text(a) + where + ". After: " + tests_text(c.analysis) +
             format(". RMS gap %.4g -> %.4g, max %.4g -> %.4g", a.rms, c.analysis.rms, a.max_abs, c.analysis.max_abs) +
             format(" (noise sigma %.4g).", a.sigma);
    }
    case Verdict::unexplained_structural: {
      std::string best;
      if (!d.refits.empty()) {
        const auto it = std::max_element(d.refits.begin(), d.refits.end(),
                                         [](const auto& x, const auto& y) { return x.delta_bic < y.delta_bic; });
        best = " Best candidate '" + it->effect + "'" + format(": delta BIC %.4g, RMS after %.4g", it->delta_bic, it->analysis.rms) +
               (it->analysis.structural ? ", residual still structural (" + tests_text(it->analysis) + ")"
                                        : std::string(", below the criterion")) +
               ".";
      } else {
        best = " No candidate effects were given.";
      }
      return "Unexplained structural residual: the base residual is not noise (" + tests_text(a) + where + "); " + base_numbers + "." + best +
             " No candidate explains it; no effect is named.";
    }
  }
  return "";
}

}  // namespace

Diagnosis run_diagnosis(const identify::StudySpec& study, const identify::Model& model,
                        const std::vector<EffectCandidate>& candidates, const DiagnoseOptions& options) {
  validate_candidates(candidates);
  check_model_accepts(model, candidates);
  Diagnosis d;
  d.candidates = candidates;
  d.bic_threshold = options.bic_threshold;
  d.noise_given = options.noise_sigma > 0.0;
  d.targets = make_targets(study, options.noise_sigma, d.notes);
  int points = 0;
  double dof_noise = 0.0;
  for (const auto& t : d.targets) {
    points += static_cast<int>(t.data.x.size());
    if (options.noise_sigma <= 0.0) dof_noise += noise_estimate_dof(static_cast<int>(t.data.x.size()));
  }
  // Fixed: model defaults, the study's fixed values, every effect at its off value.
  identify::ParameterSet fixed = model.default_parameters();
  for (const auto& [name, value] : study.fixed_parameters) fixed[name] = value;
  for (const auto& c : candidates)
    for (const auto& p : c.parameters) fixed[p.name] = p.off_value;
  for (const auto& v : study.variables) {
    d.base_variables.push_back({v.name, v.lower, v.upper, v.initial});
    fixed.erase(v.name);
  }
  const int k_base = static_cast<int>(d.base_variables.size());

  // 1-2. Base fit and its residual tests.
  // Two starts by default (study initial values, then the middle of the bounds): a base fit
  // caught in a local minimum would look like a structural residual.
  d.base = fit_least_squares(model, fixed, d.base_variables, d.targets, options.fit);
  for (int start = 1; start < options.base_starts; ++start) {
    std::vector<FitVariable> vars = d.base_variables;
    for (auto& v : vars) v.start = v.lower + (v.upper - v.lower) * start / options.base_starts;
    try {
      FitResult trial = fit_least_squares(model, fixed, vars, d.targets, options.fit);
      if (trial.chi_square < d.base.chi_square) d.base = std::move(trial);
    } catch (const std::exception&) {
      // The study's start point worked; an unevaluable extra start is simply skipped.
    }
  }
  d.base_analysis = analyse(d.base, d.targets, k_base, dof_noise, options.alpha);
  d.base_bic = bic(d.base.chi_square, k_base, points);
  d.base_aicc = aicc(d.base.chi_square, k_base, points);

  // 3. Screening (always: it is cheap and the report shows it).
  d.screening = screen_candidates(model, d.base, d.base_variables, d.targets, candidates, options.screen_step, options.fit);
  if (!d.base_analysis.structural) {
    d.verdict = Verdict::no_missing_effect;
    d.summary = summarise(d);
    return d;
  }
  std::vector<int> order(candidates.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
                   [&](int a, int b) { return d.screening[a].score > d.screening[b].score; });
  // 3b. Re-identify the best few with their extra parameters.
  for (int rank = 0; rank < std::min<int>(options.refit_best, static_cast<int>(order.size())); ++rank) {
    const EffectCandidate& c = candidates[order[rank]];
    CandidateFit f;
    f.effect = c.name;
    bool fitted = false;
    // Several starts (the augmented problem can have local minima, e.g. a toe shift traded
    // against a lower rate): base optimum + linearised effect estimate, study initial values +
    // that estimate, study initial values + mid-range effect. The lowest chi-square wins.
    for (int start = 0; start < std::max(1, options.refit_starts); ++start) {
      std::vector<FitVariable> vars = d.base_variables;
      if (start == 0)
        for (auto& v : vars) v.start = d.base.parameters.at(v.name);
      identify::ParameterSet fixed_c = fixed;
      for (std::size_t j = 0; j < c.parameters.size(); ++j) {
        const auto& p = c.parameters[j];
        const double mid = p.off_value + 0.5 * ((p.upper - p.off_value) >= (p.off_value - p.lower) ? p.upper - p.off_value
                                                                                                     : p.lower - p.off_value);
        vars.push_back({p.name, p.lower, p.upper, start < 2 ? d.screening[order[rank]].start[j] : mid});
        fixed_c.erase(p.name);
      }
      try {
        FitResult trial = fit_least_squares(model, fixed_c, vars, d.targets, options.fit);
        if (!fitted || trial.chi_square < f.fit.chi_square) f.fit = std::move(trial);
        fitted = true;
      } catch (const std::exception& e) {
        d.notes.push_back("effect '" + c.name + "': a re-identification start failed (" + e.what() + ")");
      }
    }
    if (!fitted) continue;
    const int k_base_effect = k_base + static_cast<int>(c.parameters.size());
    const int k = k_base_effect;
    f.analysis = analyse(f.fit, d.targets, k, dof_noise, options.alpha);
    f.bic = bic(f.fit.chi_square, k, points);
    f.aicc = aicc(f.fit.chi_square, k, points);
    f.delta_bic = d.base_bic - f.bic;
    f.delta_aicc = d.base_aicc - f.aicc;
    // 4. Name an effect only if the criterion favours it AND its residual is noise.
    f.passes = f.delta_bic > options.bic_threshold && !f.analysis.structural;
    d.refits.push_back(std::move(f));
  }
  for (std::size_t i = 0; i < d.refits.size(); ++i)
    if (d.refits[i].passes && (d.chosen < 0 || d.refits[i].delta_bic > d.refits[d.chosen].delta_bic))
      d.chosen = static_cast<int>(i);
  d.verdict = d.chosen >= 0 ? Verdict::effect_identified : Verdict::unexplained_structural;
  d.summary = summarise(d);
  return d;
}

}  // namespace demfit::diagnose
