// The diagnosis workflow; see workflow.hpp and docs/diagnose.md.
#include "demfit/diagnose/workflow.hpp"
#include "fit_context.hpp"
#include "text_format.hpp"
#include "verdict_summary.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <numeric>
#include <stdexcept>

namespace demfit::diagnose {

const char* verdict_text(Verdict verdict) {
  switch (verdict) {
    case Verdict::no_missing_effect:
      return "no missing effect";
    case Verdict::effect_identified:
      return "missing effect identified";
    case Verdict::unexplained_structural:
      return "unexplained structural residual";
    case Verdict::ambiguous:
      return "ambiguous: several effects explain the residual";
  }
  return "?";
}

DiagnoseOptions expensive_model_options() {
  DiagnoseOptions o;
  o.base_starts = 1;
  o.refit_starts = 1;
  o.screen_step = 0.2;
  o.fit.fd_step = 0.02;
  o.fit.central_differences = true;
  o.fit.broyden = true;
  o.fit.absolute_tolerance = 0.1;
  o.fit.relative_tolerance = 1e-5;
  o.fit.max_evaluations = 60;
  // Re-fit every candidate scoring at least a quarter of the best: an s = 4 drum was measured
  // whose three screening scores were within 25 % of each other and whose true effect ranked third.
  o.refit_score_ratio = 0.25;
  o.scatter_replicas = 4;
  return o;
}

double bic(double chi_square, int parameters, int points) { return chi_square + parameters * std::log(points); }

double aicc(double chi_square, int parameters, int points) {
  const double k = parameters;
  const double denominator = points - k - 1.0;
  return chi_square + 2.0 * k + (denominator > 0.0 ? 2.0 * k * (k + 1.0) / denominator : 1e300);
}

namespace detail {

void progress(const DiagnoseOptions& options, std::chrono::steady_clock::time_point started, const std::string& what) {
  if (!options.progress) return;
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  std::fprintf(stderr, "demfit diagnose: %s (%.0f s so far)\n", what.c_str(), seconds);
}

FitOptions stage_fit_options(const DiagnoseOptions& options, std::chrono::steady_clock::time_point started,
                             const std::string& what) {
  FitOptions fit = options.fit;
  if (options.progress)
    fit.on_step = [&options, started, what](int iteration, int evaluations, double chi_square) {
      progress(
          options, started,
          format("%s: step %d, %d evaluations, chi-square %.4g", what.c_str(), iteration, evaluations, chi_square));
    };
  return fit;
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

}  // namespace detail

namespace {

using detail::FitContext;
using detail::format;
using detail::progress;
using detail::analyse;
using detail::refit_candidate;
using detail::search_failed_refits;
using detail::stage_fit_options;

std::vector<FitTarget> make_targets(const identify::StudySpec& study, double given_sigma,
                                    std::vector<std::string>& notes) {
  std::vector<FitTarget> targets;
  for (const auto& t : study.targets) {
    if (t.metric != identify::CurveMetric::mse)
      throw std::runtime_error("diagnose: target '" + t.name +
                               "': metric curve_mapping is not supported by diagnose yet; use \"mse\" for this target");
    FitTarget f{t.name, t.curve, t.data, 1.0, {}};
    if (given_sigma > 0.0) {
      f.sigma = given_sigma;
    } else {
      f.sigma = estimate_noise_sigma(t.data.x, t.data.y);
      double scale = 0.0;
      for (double y : t.data.y) scale = std::max(scale, std::abs(y));
      const double floor = 1e-9 * std::max(scale, 1e-300);
      if (f.sigma < floor) {
        f.sigma = floor;
        notes.push_back("target '" + t.name +
                        "': the data look noise-free; noise level floored at 1e-9 of max|y| (give --noise)");
      }
    }
    targets.push_back(f);
  }
  if (targets.empty()) throw std::runtime_error("diagnose: the study has no targets; add one under \"targets\"");
  return targets;
}

void check_model_accepts(const identify::Model& model, const std::vector<EffectCandidate>& candidates) {
  const auto descriptors = model.parameters();
  for (const auto& c : candidates)
    for (const auto& p : c.parameters) {
      const identify::ParameterDescriptor* d = identify::find_descriptor(descriptors, p.name);
      if (!d)
        throw std::runtime_error("diagnose: effect '" + c.name + "': the model has no parameter '" + p.name +
                                 "'; remove the effect with --effects or use a model that implements it");
      if (!d->valid.contains_interval(p.lower, p.upper))
        throw std::runtime_error("diagnose: effect '" + c.name + "': parameter '" + p.name + "' range [" +
                                 format("%g, %g", p.lower, p.upper) + "] lies outside the model's valid range " +
                                 d->valid.to_string() + "; narrow it");
    }
}

// Base fit from the study's initial values. A fit that ends with a variable on a bound may sit in
// a corner minimum of the box (a long first step can land there), and a base fit caught in a local
// minimum would look like a structural residual: then further starts follow,
// v_lo + (v_hi - v_lo) i / base_starts, and the best is kept.
FitResult fit_base(const FitContext& c, const std::vector<FitVariable>& variables,
                   const std::vector<FitTarget>& targets, int& evaluations) {
  const FitOptions fit = stage_fit_options(c.options, c.started, "base fit");
  FitResult best = fit_least_squares(c.model, c.fixed, variables, targets, fit);
  evaluations += best.evaluations;
  bool on_bound = false;
  for (std::size_t j = 0; j < variables.size(); ++j) on_bound = on_bound || at_bound(variables[j], best.values[j]);
  for (int start = 1; start < c.options.base_starts && on_bound; ++start) {
    std::vector<FitVariable> vars = variables;
    for (auto& v : vars) v.start = v.lower + (v.upper - v.lower) * start / c.options.base_starts;
    try {
      FitResult trial = fit_least_squares(c.model, c.fixed, vars, targets, fit);
      evaluations += trial.evaluations;
      if (trial.chi_square < best.chi_square) best = std::move(trial);
    } catch (const std::exception&) {
      // The study's start point worked; an unevaluable extra start is simply skipped.
    }
  }
  return best;
}

}  // namespace

bool replaces_kept_start(const CandidateFit& kept, const CandidateFit& trial) {
  return trial.passes || trial.criterion_chi_square < kept.criterion_chi_square;
}

// 4-5. The verdict from the re-fits: the passing candidate with the largest delta BIC, unless
// another plausible candidate fits about as well — its delta BIC also exceeds the threshold and is
// within the threshold of the chosen one's (|delta BIC_a - delta BIC_b| <= threshold), whether or
// not its residual passed the noise tests (a 148.0 vs 147.4 tie is no evidence for either).
void decide_verdict(Diagnosis& d, double bic_threshold) {
  for (std::size_t i = 0; i < d.refits.size(); ++i)
    if (d.refits[i].passes && (d.chosen < 0 || d.refits[i].delta_bic > d.refits[d.chosen].delta_bic))
      d.chosen = static_cast<int>(i);
  d.verdict = d.chosen >= 0 ? Verdict::effect_identified : Verdict::unexplained_structural;
  if (d.chosen < 0) return;
  for (std::size_t i = 0; i < d.refits.size(); ++i) {
    const bool plausible = d.refits[i].delta_bic > bic_threshold;
    if (plausible && std::abs(d.refits[d.chosen].delta_bic - d.refits[i].delta_bic) <= bic_threshold)
      d.tied.push_back(static_cast<int>(i));
  }
  if (d.tied.size() > 1) {
    d.verdict = Verdict::ambiguous;
    d.chosen = -1;
  } else {
    d.tied.clear();
  }
}

// Indices of the candidates to re-fit, best score first: every one scoring at least
// options.refit_score_ratio x the best, and at least the options.refit_best highest.
std::vector<int> refit_order(const std::vector<ScreeningScore>& screening, const DiagnoseOptions& options) {
  std::vector<int> order(screening.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return screening[a].score > screening[b].score; });
  if (order.empty()) return order;
  const double best = screening[order.front()].score;
  std::size_t keep = 0;
  while (keep < order.size() && (static_cast<int>(keep) < options.refit_best ||
                                 screening[order[keep]].score >= options.refit_score_ratio * best))
    ++keep;
  order.resize(keep);
  return order;
}

Diagnosis run_diagnosis(const identify::StudySpec& study, const identify::Model& model,
                        const std::vector<EffectCandidate>& candidates, const DiagnoseOptions& options) {
  const auto started = std::chrono::steady_clock::now();
  validate_candidates(candidates);
  check_model_accepts(model, candidates);
  Diagnosis d;
  d.candidates = candidates;
  d.bic_threshold = options.bic_threshold;
  d.noise_given = options.noise_sigma > 0.0;
  d.data_scatter_ratio = options.data_scatter_ratio;
  d.refit_search_evaluations = options.refit_search_evaluations;
  d.targets = make_targets(study, options.noise_sigma, d.notes);
  // Fixed: model defaults, the study's fixed values, every effect at its off value.
  identify::ParameterSet fixed = model.default_parameters();
  for (const auto& [name, value] : study.fixed_parameters) fixed[name] = value;
  for (const auto& c : candidates)
    for (const auto& p : c.parameters) fixed[p.name] = p.off_value;
  for (const auto& v : study.variables) {
    d.base_variables.push_back({v.name, v.lower, v.upper, v.initial});
    fixed.erase(v.name);
  }
  FitContext context{model, fixed, options, started};
  for (const auto& t : d.targets) {
    context.points += static_cast<int>(t.data.x.size());
    if (options.noise_sigma <= 0.0) context.dof_noise += noise_estimate_dof(static_cast<int>(t.data.x.size()));
  }
  const int k_base = static_cast<int>(d.base_variables.size());

  // 1-2. Base fit and its residual tests.
  d.base = fit_base(context, d.base_variables, d.targets, d.base_evaluations);
  d.base_analysis = analyse(d.base, d.targets, k_base, context.dof_noise, options.alpha);
  d.base_analysis_data_noise = d.base_analysis;
  // The model's own scatter is measured only when the data noise alone does not explain the base
  // residual (a smooth model, or a good fit, costs nothing extra).
  if (d.base_analysis.structural && options.scatter_replicas > 0) {
    detail::account_for_scatter(context, d);
    if (d.scatter_in_noise_model)
      d.base_analysis = analyse(d.base, d.targets, k_base, context.dof_noise, options.alpha);
  }
  if (d.criterion_replicas == 0) d.base_criterion_chi_square = d.base.chi_square;
  if (d.criterion_replicas > 0 && options.refit_search_evaluations > 0 && d.base_analysis_data_noise.structural)
    detail::search_base_optimum(context, d);
  d.base_bic = bic(d.base_criterion_chi_square, k_base, context.points);
  d.base_aicc = aicc(d.base_criterion_chi_square, k_base, context.points);
  progress(options, started,
           format("base fit done: %d evaluations, residual %s", d.base_evaluations,
                  d.base_analysis.structural ? "structural" : "noise"));

  // 3. Screening (always: it is cheap and the report shows it).
  d.screening = screen_candidates(model, d.base, d.base_variables, d.targets, candidates, options.screen_step,
                                  options.fit, &d.screening_evaluations);
  progress(options, started,
           format("screening of %zu candidates done: %d evaluations", candidates.size(), d.screening_evaluations));
  auto finish = [&] {
    d.summary = detail::summarise(d);
    d.evaluations = d.base_evaluations + d.screening_evaluations + d.refit_evaluations;
    d.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  };
  if (!d.base_analysis_data_noise.structural) {
    d.verdict = Verdict::no_missing_effect;
    finish();
    return d;
  }
  // 3b. Re-identify every candidate that screened about as well as the best, with its extra parameters.
  const std::vector<int> order = refit_order(d.screening, options);
  for (std::size_t rank = 0; rank < order.size(); ++rank) {
    progress(options, started,
             format("re-fit %zu/%zu: base + %s", rank + 1, order.size(), candidates[order[rank]].name.c_str()));
    CandidateFit f;
    if (refit_candidate(context, d, candidates[order[rank]], d.screening[order[rank]], f))
      d.refits.push_back(std::move(f));
  }
  // A search is made only when the local fits name nothing: it can turn "unexplained" into a name
  // where one run's scatter hid an effect's optimum; rivals of a passing candidate are compared by
  // their local fits (docs/diagnose.md, step 4).
  const bool any_passes = std::any_of(d.refits.begin(), d.refits.end(), [](const auto& r) { return r.passes; });
  if (!any_passes && options.refit_search_evaluations > 0) search_failed_refits(context, d, candidates, order);
  decide_verdict(d, d.bic_threshold);
  if (d.verdict == Verdict::unexplained_structural && d.scatter_in_noise_model && !d.base_analysis.structural) {
    // Structure against the data noise alone, but within the model's own scatter, and no candidate
    // wins under that noise: nothing detectable is missing at this model's resolution.
    d.verdict = Verdict::no_missing_effect;
  }
  finish();
  return d;
}

}  // namespace demfit::diagnose
