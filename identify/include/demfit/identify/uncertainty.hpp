#pragma once
// Approximate confidence intervals of identified variables (linearised least squares):
//   Cov = s^2 (J^T J)^-1,  two-sided half-width = t_{(1+c)/2, dof} * sqrt(Cov_jj)
// J = d r / d x (residuals w.r.t. the physical variables), r = residual vector at the optimum,
// N residuals, n variables.
//
// Two ways to get J and s^2:
//  - estimate_uncertainty(J, r, ...): J given (e.g. analytic), s^2 = |r|^2 / (N - n).
//  - estimate_uncertainty_from_runs(...): what the study loop uses. J is the slope of
//    a linear least-squares regression of the EVALUATED residual vectors on the variables over the
//    runs near the optimum, not the derivative of an interpolating surrogate: a DEM response has
//    trajectory noise (a tiny parameter change gives a slightly different packing history), and an
//    interpolating RBF turns that noise into steep, fictitious slopes -> far too narrow intervals.
//    The regression's own residual scatter sigma_fit^2 (simulation noise + curvature over the
//    sample) is added to the residual variance at the optimum: s^2 = |r|^2/(N - n) + sigma_fit^2.
//
// A variable is flagged unidentifiable when
//  (a) its half-width exceeds half its bound range, or
//  (b) J^T J is near-singular (eigenvalue < 1e-10 of the largest, in range-scaled variables) and
//      the variable takes part in the near-null direction (|component| > 0.1), or
//  (c) (regression only) the curve change it produces over the sampled runs is not significantly
//      larger than the simulation noise: effect_significance_j = |B_j| / sqrt(N sigma_fit^2 c_jj)
//      < 2, where B_j is the regression slope row of variable j (all N residuals) and c_jj the
//      (X^T X)^-1 diagonal entry: under "no effect", |B_j|^2 / (sigma_fit^2 c_jj) ~ chi^2_N, so the
//      ratio is ~1; an identifiable variable moves the curve by many noise standard deviations.
//      Such a variable gets an unbounded interval ("anywhere in its bounds"); the others' J^T J is
//      taken without it (intervals conditional on it) and debiased for the slopes' own noise:
//      J^T J = B^T B - N sigma_fit^2 (X^T X)^-1 (slope block), the expected excess of B^T B.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "demfit/identify/study_spec.hpp"

namespace demfit::identify {

struct UncertaintyEstimate {
  std::vector<double> standard_error;  // per variable, physical units
  std::vector<double> ci_half_width;   // per variable, physical units
  Eigen::MatrixXd correlation;         // n x n
  std::vector<bool> unidentifiable;
  double residual_variance = 0.0;  // s^2 (per residual component)
  int degrees_of_freedom = 0;      // N - n
  double condition_number = 0.0;   // of J^T J in range-scaled variables
  // Regression estimate only (estimate_uncertainty_from_runs); otherwise 0 / empty.
  std::string jacobian_source = "given";    // "given" or "regression"
  int runs_used = 0;                        // runs in the regression
  double simulation_noise_variance = 0.0;   // sigma_fit^2 per residual component
  std::vector<double> effect_significance;  // per variable (criterion (c)); empty when not computed
  // Regression only: the least-squares centre of the local linear model, physical units, per
  // variable (unidentifiable ones stay at the best run). x_best + dx, dx = -(J^T J)^-1 J^T r0 with
  // r0 the regression's residual vector at the best run: the runs' average, not one noisy run,
  // decides where the curve fits best. The step is kept inside the sampled spread (no
  // extrapolation). The intervals are centred here.
  std::vector<double> least_squares_estimate;
};

// jacobian: N x n (physical units), residuals: N.
UncertaintyEstimate estimate_uncertainty(const Eigen::MatrixXd& jacobian, const Eigen::VectorXd& residuals,
                                         const std::vector<VariableSpec>& variables, double confidence = 0.95);

// Runs near the optimum, for the regression estimate.
struct RunSample {
  Eigen::MatrixXd unit_points;        // m x n, unit (optimiser) coordinates of the runs
  Eigen::MatrixXd residuals;          // m x N, evaluated residual vectors of the same runs
  Eigen::VectorXd best_unit;          // n, the optimum (the best run)
  Eigen::VectorXd best_residuals;     // N, its evaluated residuals
  Eigen::VectorXd unit_per_physical;  // n, d(unit)/d(physical) at the optimum
};

// Regression Jacobian and noise as described above. Needs m >= n + 2 distinct runs; with fewer,
// every variable is reported unidentifiable with an infinite interval.
UncertaintyEstimate estimate_uncertainty_from_runs(const RunSample& sample, const std::vector<VariableSpec>& variables,
                                                   double confidence = 0.95);

// Inverse of the standard normal CDF (Acklam's rational approximation, |rel. error| < 1.2e-9).
double normal_quantile(double p);

// ---- Posterior sampling on the local surrogate ----
// Intervals that stay right when another parameter is poorly pinned. The residual vector is
// regressed on the unit coordinates over the runs near the optimum, r(u) ≈ b0 + J (u − u_best)
// (the local linear surrogate of the residuals; its regression residuals E measure the simulation
// noise). Likelihood of the measured curve: r(u) ~ N(0, Σ), Σ = Σ_sim + σ_w² I with
//   Σ_sim = (1 − λ) EᵀE/(m − n − 1) + λ tr(·)/N I   (λ = 0.2: shrinkage of a rank-deficient
//                                                      covariance, Ledoit & Wolf 2004)
//   σ_w² = max(0, SSR_min/(N − n) − tr Σ_sim/N)        (what the best fit leaves beyond the
//                                                      simulation noise: data noise)
// i.e. correlated (smooth, DEM trajectory-like) noise is weighted as such instead of as N
// independent points. Prior uniform on the variable bounds (unit box). The posterior is a normal
// truncated to the box; it is sampled by Gibbs sampling (exact univariate truncated-normal
// conditionals), so a weak parameter spreads over its bounds and a parameter correlated with it
// gets the marginal (not conditional) interval. Reported: posterior median, equal-tailed
// `confidence` interval of every marginal, the correlation of the draws.
struct PosteriorOptions {
  int draws = 20000;
  int burn_in = 1000;
  std::uint64_t seed = 1;
  double confidence = 0.95;
  double shrinkage = 0.2;
};

struct PosteriorEstimate {
  std::vector<double> median, lower, upper;  // physical units, per variable
  Eigen::MatrixXd correlation;               // of the draws
  Eigen::MatrixXd draws;                     // up to 2000 kept draws (physical units), for the pair plot
  std::vector<bool> unidentifiable;          // interval wider than half the bounds
  double simulation_noise_variance = 0.0;    // tr Σ_sim / N
  double data_noise_variance = 0.0;          // σ_w²
  int runs_used = 0;
};

// Needs m >= n + 3 runs; throws std::invalid_argument otherwise.
PosteriorEstimate sample_posterior_from_runs(const RunSample& sample, const std::vector<VariableSpec>& variables,
                                             const PosteriorOptions& options = {});

// Pair plot of the draws (marginal histograms on the diagonal, scatter below) as a PNG through
// gnuplot. Returns an empty string on success, else why no plot was written.
std::string write_posterior_pair_plot(const PosteriorEstimate& estimate, const std::vector<VariableSpec>& variables,
                                      const std::filesystem::path& png);

// Two-sided Student-t quantile t_{p, dof} (Cornish-Fisher expansion around the normal quantile;
// relative error < 1e-3 for dof >= 3).
double student_t_quantile(double p, int dof);

}  // namespace demfit::identify
