#pragma once
// What the stages of one diagnosis share (workflow.cpp, scatter_criterion.cpp): the model, the
// fixed parameters, the options, progress lines, and the scatter-aware criterion. Internal to the
// diagnose library.
#include <chrono>
#include <string>
#include <vector>

#include "demfit/diagnose/workflow.hpp"

namespace demfit::diagnose::detail {

// What every fit of one diagnosis shares.
struct FitContext {
  const identify::Model& model;
  const identify::ParameterSet& fixed;  // defaults, study fixed values, effects off
  const DiagnoseOptions& options;
  std::chrono::steady_clock::time_point started;  // of the diagnosis (progress lines)
  int points = 0;
  double dof_noise = 0.0;
};

// One progress line on stderr with the seconds since `started`, if options.progress.
void progress(const DiagnoseOptions& options, std::chrono::steady_clock::time_point started, const std::string& what);

// The fit options of one stage (`what`: "base fit", "re-fit base + plasticity"), printing each
// accepted step when progress is on: a base fit of DEM runs can take 20 minutes.
FitOptions stage_fit_options(const DiagnoseOptions& options, std::chrono::steady_clock::time_point started,
                             const std::string& what);

// The mean chi-square of `replicas` fresh runs at `optimum` (its `variables` moved by round-off,
// model_scatter.hpp) under `targets`; `fallback` if every replica failed. Adds the runs to
// `evaluations`. A fit keeps the luckiest of its dozens of trajectories; these runs are an
// unbiased look at its optimum.
double replicated_chi_square(const FitContext& c, const identify::ParameterSet& optimum,
                             const std::vector<FitVariable>& variables, const std::vector<FitTarget>& targets,
                             int replicas, double fallback, int& evaluations);

// The model's own scatter (model_scatter.hpp): replicas of the base optimum; targets whose scatter
// matters are whitened, the BIC threshold is raised by the replicas' chi-square spread, the base
// fit is refined under the new noise model (its Jacobian carried over linearly), and the base's
// criterion chi-square is set (Diagnosis::base_criterion_chi_square).
void account_for_scatter(const FitContext& c, Diagnosis& d);

// With the model's scatter in the criterion and DiagnoseOptions::refit_search_evaluations > 0: a
// surrogate search over the base variables (base_search.cpp); when the mean of fresh replicas at
// its point is lower than the base's criterion chi-square, it becomes the base's, and the BIC
// threshold is raised by the chi-square spread at that point instead of the base fit's. The base
// fit itself (its residual, Jacobian and the re-fits' starts) is unchanged.
void search_base_optimum(const FitContext& c, Diagnosis& d);

// Residual tests of `fit` under `targets` (`fitted` parameters; workflow.cpp).
ResidualAnalysis analyse(const FitResult& fit, const std::vector<FitTarget>& targets, int fitted, double dof_noise,
                         double alpha);

// Re-identifies base variables + one effect's parameters from its local starts (refit.cpp); the
// kept fit in `f`; false if every start failed.
bool refit_candidate(const FitContext& c, Diagnosis& d, const EffectCandidate& effect, const ScreeningScore& score,
                     CandidateFit& f);

// When no re-fitted candidate passed: the surrogate search for each candidate of `order`
// (refit.cpp), replacing or adding its entry of d.refits.
void search_failed_refits(const FitContext& c, Diagnosis& d, const std::vector<EffectCandidate>& candidates,
                          const std::vector<int>& order);

}  // namespace demfit::diagnose::detail
