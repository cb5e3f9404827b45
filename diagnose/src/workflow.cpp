// The diagnosis workflow; see workflow.hpp and docs/diagnose.md.
#include "demfit/diagnose/workflow.hpp"
#include "demfit/diagnose/surrogate_start.hpp"
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

}  // namespace detail

namespace {

using detail::FitContext;
using detail::format;
using detail::progress;
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

// The search's point itself as a re-fit (its one run's residual; no Jacobian is needed by the
// assessment), so the smoothed optimum is judged before a local descent follows one run's noise.
bool assess_surrogate_point(const FitContext& c, Diagnosis& d, const identify::ParameterSet& fixed,
                            const std::vector<FitVariable>& vars, CandidateFit& f, bool& fitted) {
  CandidateFit trial;
  trial.effect = f.effect;
  trial.fit.parameters = fixed;
  for (const auto& v : vars) {
    trial.fit.parameters[v.name] = v.start;
    trial.fit.values.push_back(v.start);
  }
  const auto residual = residuals_at(c.model, {trial.fit.parameters}, d.targets, c.options.fit).front();
  d.refit_evaluations += 1;
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
// (surrogate_start.hpp), told the base optimum (effect off) and the kept fit's point; its point of
// lowest predicted chi-square is assessed as it is and, if it does not pass, starts a local fit.
bool refit_from_surrogate_search(const FitContext& c, Diagnosis& d, const EffectCandidate& effect,
                                 const ScreeningScore& score, CandidateFit& f, bool& fitted) {
  identify::ParameterSet fixed = c.fixed;
  std::vector<FitVariable> vars = refit_variables(d, effect, score, 0, fixed);
  std::vector<double> base_point = d.base.values;
  for (const auto& p : effect.parameters) base_point.push_back(p.off_value);
  std::vector<std::vector<double>> known{base_point};
  std::vector<double> known_chi_squares{d.base.chi_square};
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
  if (assess_surrogate_point(c, d, fixed, vars, f, fitted)) return true;
  return try_refit_start(c, d, fixed, vars, nullptr, f, fitted);
}

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
