#pragma once
// Shared by the hidden-effect DEM diagnoses (test_dem_hidden_effects.cpp, test_hertz_hidden_cohesion.cpp):
// a scenario (case, overrides, base variables, truth, measured curves, noise seed), the synthetic
// measurements made from it (the DEM model with the hidden effect on, then seeded Gaussian noise by
// cases::add_relative_noise, the code path of `demfit simulate --noise`), the diagnosis run on them,
// and the figures each test prints (named effect, criterion values, RMS gap, cost).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "demfit/cases/effect_catalogue.hpp"
#include "demfit/cases/model_factory.hpp"
#include "demfit/cases/synthetic_noise.hpp"
#include "demfit/diagnose/workflow.hpp"

namespace demfit::diagnose::hidden_effect_test {

// Relative noise of the synthetic measurements unless a scenario gives its own: sigma = kNoise *
// max|y| (as `simulate --noise`).
constexpr double kNoise = 0.02;

// Fills are cached in the build tree, shared by every hidden-effect test.
inline void use_test_cache() { setenv("DEMFIT_CACHE_DIR", DEMFIT_BINARY_DIR "/tests/diagnose/dem_fill_cache", 1); }

// The catalogue's effects for a case as diagnose candidates (the conversion of
// apps/demfit/cmd_diagnose.cpp, without its CLI notes).
inline std::vector<EffectCandidate> candidates_for(const std::string& case_name,
                                                   const std::vector<std::string>& without = {},
                                                   const nlohmann::json& overrides = {}) {
  std::vector<EffectCandidate> out;
  for (const auto& e : cases::effects_for_case(case_name, overrides)) {
    if (std::find(without.begin(), without.end(), e.name) != without.end()) continue;
    EffectCandidate c{e.name, e.description, {}, e.curves};
    for (const auto& p : e.parameters) c.parameters.push_back(p);
    out.push_back(std::move(c));
  }
  return out;
}

struct Scenario {
  std::string label;
  std::string case_name;
  nlohmann::json overrides;
  std::vector<identify::VariableSpec> variables;  // base variables (bounds, initial values)
  identify::ParameterSet truth;                   // base variable values and the hidden effect
  std::vector<std::string> curves;                // measured curves (targets)
  std::uint64_t seed =
      1;  // noise seed; target k uses seed + k (`simulate --noise` numbers all written curves in name order)
  double noise = kNoise;     // relative noise level
  bool noise_given = false;  // diagnose with the true noise level (as `--noise`) instead of estimating it
};

struct Outcome {
  Diagnosis diagnosis;
  std::vector<double> sigma;  // true noise level of each target [y units]
  // RMS of the simulated-minus-data residual divided by the true data noise, r_i / sigma_true,i, over
  // all targets (1 = the noise level). A whitened target's residual is mapped back to y units by its
  // noise factor L (residual = L^-1 (simulated - data)).
  double rms_over_true_sigma(const FitResult& fit) const {
    double sum = 0.0;
    Eigen::Index k = 0;
    for (std::size_t t = 0; t < diagnosis.targets.size(); ++t) {
      const FitTarget& target = diagnosis.targets[t];
      const auto n = static_cast<Eigen::Index>(target.data.x.size());
      const Eigen::VectorXd normalised = fit.residual.segment(k, n);
      const Eigen::VectorXd raw = target.noise_factor.size() > 0
                                      ? Eigen::VectorXd(target.noise_factor.triangularView<Eigen::Lower>() * normalised)
                                      : Eigen::VectorXd(normalised * target.sigma);
      sum += raw.squaredNorm() / (sigma[t] * sigma[t]);
      k += n;
    }
    return std::sqrt(sum / static_cast<double>(k));
  }
};

inline std::string detail_scatter(const TargetScatter& s, bool whitened) {
  char text[160];
  std::snprintf(text, sizeof text, " (model scatter %.4g, lag-1 %.3f, %d runs%s)", s.sigma, s.lag1, s.replicas,
                whitened ? ": whitened" : ": below the threshold");
  return text;
}

// `study` with the scenario's variables, each measured curve of the model run at the truth (its
// defaults, then the scenario's truth) plus seeded noise as a target; the noise levels into `sigma`.
inline void add_synthetic_targets(identify::StudySpec& study, const identify::Model& model,
                                  const identify::ParameterSet& truth_values, const std::vector<std::string>& names,
                                  double noise, std::uint64_t seed, std::vector<double>& sigma) {
  use_test_cache();  // the truth run's fill too
  identify::ParameterSet truth = model.default_parameters();
  for (const auto& [name, value] : truth_values) truth[name] = value;
  const identify::CurveSet curves = model.evaluate(truth, {});
  for (std::size_t k = 0; k < names.size(); ++k) {
    identify::TargetSpec target;
    target.name = target.curve = names[k];
    target.data = curves.at(names[k]);
    double scale = 0.0;
    for (double y : target.data.y) scale = std::max(scale, std::abs(y));
    target.data.y = cases::add_relative_noise(target.data.y, noise, seed + k);
    sigma.push_back(noise * scale);
    study.targets.push_back(target);
  }
}

// The diagnosis of `study` (its targets made by add_synthetic_targets, true noise levels `sigma`)
// and the figures of the closing note; `noise_given`: diagnose with the true noise level (single-
// target studies only) instead of estimating it.
inline Outcome diagnose_and_report(const std::string& label, const identify::StudySpec& study,
                                   const identify::Model& model, const std::vector<EffectCandidate>& candidates,
                                   std::vector<double> sigma, bool noise_given) {
  use_test_cache();
  Outcome out;
  out.sigma = std::move(sigma);
  DiagnoseOptions options = expensive_model_options();
  options.fit.jobs = 2;
  if (const char* jobs = std::getenv("DEMFIT_DIAGNOSE_JOBS")) options.fit.jobs = std::atoi(jobs);
  if (noise_given) options.noise_sigma = out.sigma.front();
  // The targets are one run of this very model (plus noise): its scatter is in the data once more
  // (`demfit diagnose --data-scatter 1`).
  options.data_scatter_ratio = 1.0;
  if (const char* starts = std::getenv("DEMFIT_DIAGNOSE_REFIT_STARTS")) options.refit_starts = std::atoi(starts);
  if (const char* search = std::getenv("DEMFIT_DIAGNOSE_REFIT_SEARCH")) options.refit_search_evaluations = std::atoi(search);
  out.diagnosis = run_diagnosis(study, model, candidates, options);
  // The figures of the closing note.
  const Diagnosis& d = out.diagnosis;
  std::printf("\n[%s] verdict: %s%s\n", label.c_str(), verdict_text(d.verdict),
              d.chosen >= 0 ? (" -> " + d.refits[d.chosen].effect).c_str() : "");
  for (std::size_t t = 0; t < d.targets.size(); ++t)
    std::printf("  target %s: noise sigma true %.4g, used %.4g%s\n", d.targets[t].name.c_str(), out.sigma[t],
                d.targets[t].sigma,
                t < d.scatter.size() ? detail_scatter(d.scatter[t], d.targets[t].noise_factor.size() > 0).c_str() : "");
  std::printf(
      "  BIC threshold used %.4g (chi-square spread of the scatter replicas %.4g; criterion over %d replicas, "
      "base %.4g against its fit's %.4g)\n",
      d.bic_threshold, d.scatter_chi_square_sd, d.criterion_replicas, d.base_criterion_chi_square, d.base.chi_square);
  std::printf(
      "  base RMS/sigma_true %.2f; worst region %s\n", out.rms_over_true_sigma(d.base),
      d.base_analysis.worst_region >= 0 ? d.base_analysis.regions[d.base_analysis.worst_region].label.c_str() : "-");
  std::printf("  base tests: runs p %.3g, lag-1 %.3f (p %.3g), variance ratio %.3g (p %.3g), smooth p %.3g -> %s\n",
              d.base_analysis.runs.p_value, d.base_analysis.autocorrelation.lag1,
              d.base_analysis.autocorrelation.p_value, d.base_analysis.variance.ratio, d.base_analysis.variance.p_value,
              d.base_analysis.smooth.p_value, d.base_analysis.structural ? "structure" : "noise");
  for (const auto& sc : d.screening)
    std::printf("  screening %-20s score %10.4g  share %.3f  absorbed by base %.3f  gain at full range %.4g%s\n",
                sc.effect.c_str(), sc.score, sc.fraction_explained, sc.absorbed_by_base, sc.full_range_gain,
                sc.evaluated ? "" : "  (perturbed run failed)");
  auto values = [](const FitResult& f, const std::vector<FitVariable>& base, const std::string& extra) {
    std::string text;
    for (const auto& v : base) text += v.name + " " + std::to_string(f.parameters.at(v.name)) + ", ";
    return text + extra;
  };
  std::printf("  base fit: %s(%d evaluations)\n", values(d.base, d.base_variables, "").c_str(), d.base.evaluations);
  for (const auto& r : d.refits) {
    std::string extra;
    for (const auto& c : d.candidates)
      if (c.name == r.effect)
        for (const auto& p : c.parameters) extra += p.name + " " + std::to_string(r.fit.parameters.at(p.name)) + " ";
    std::printf(
        "  refit     %-20s delta BIC %9.4g (chi-square %.4g, criterion %.4g)  RMS/sigma_true %.2f  residual %s  %s\n",
        r.effect.c_str(), r.delta_bic, r.fit.chi_square, r.criterion_chi_square, out.rms_over_true_sigma(r.fit),
        r.analysis.structural ? "structure" : "noise", r.passes ? "PASSES" : "fails");
    std::printf(
        "            tests: runs p %.3g, lag-1 %.3f (p %.3g), variance ratio %.3g (p %.3g), smooth p %.3g; %s(%d "
        "evaluations)\n",
        r.analysis.runs.p_value, r.analysis.autocorrelation.lag1, r.analysis.autocorrelation.p_value,
        r.analysis.variance.ratio, r.analysis.variance.p_value, r.analysis.smooth.p_value,
        values(r.fit, d.base_variables, extra).c_str(), r.fit.evaluations);
  }
  for (const auto& note : d.notes) std::printf("  note: %s\n", note.c_str());
  std::printf("  evaluations %d (base %d, screening %d, re-fits %d), wall time %.1f s\n", d.evaluations,
              d.base_evaluations, d.screening_evaluations, d.refit_evaluations, d.wall_seconds);
  return out;
}

// The scenario as a study of its one case: synthetic targets, then the diagnosis and its figures.
inline Outcome run(const Scenario& s, const std::vector<EffectCandidate>& candidates) {
  const auto model = cases::make_model(s.case_name, s.overrides, DEMFIT_SOURCE_DIR);
  identify::StudySpec study;
  study.name = s.label;
  study.model_reference = s.case_name;
  study.base_dir = DEMFIT_SOURCE_DIR;  // a case file named by path resolves against the source tree
  study.model_overrides = s.overrides;
  study.variables = s.variables;
  std::vector<double> sigma;
  add_synthetic_targets(study, *model, s.truth, s.curves, s.noise, s.seed, sigma);
  return diagnose_and_report(s.label, study, *model, candidates, sigma, s.noise_given);
}

}  // namespace demfit::diagnose::hidden_effect_test
