#pragma once
// A small bounded Levenberg-Marquardt fit of model parameters to the study targets, with a
// finite-difference Jacobian from model evaluations (run `jobs` at a time) kept up to date by
// Broyden rank-one updates between finite-difference refreshes (evaluations are what a DEM
// diagnosis pays for). Used for the base and augmented fits of the diagnosis: the residual tests
// need a precise local optimum (a residual at the noise level), which the surrogate loop does not
// guarantee in few runs.
#include <functional>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "demfit/identify/model.hpp"
#include "demfit/identify/study_spec.hpp"

namespace demfit::diagnose {

struct FitVariable {
  std::string name;
  double lower = 0.0, upper = 1.0;
  double start = 0.5;
};

// Which bound `value` lies within `fraction` of the variable's range of: -1 the lower, +1 the upper,
// 0 neither. One rule for both uses below and the diagnosis summary's note (1 % of the range).
int near_bound(const FitVariable& variable, double value, double fraction);
// True when `value` lies within 1e-6 of the range of one of the variable's bounds (a fitted value
// held there by the bound).
bool at_bound(const FitVariable& variable, double value);

// Data to match: each target's data points, its simulated curve name and its noise level.
// Residuals are (simulated y at the data x - data y) / sigma, so the cost is a chi-square.
// A target whose x reverses (a loading-unloading cycle) is matched branch by branch: data branch
// k is compared with simulated branch k (each branch monotone in x).
struct FitTarget {
  std::string name;
  std::string curve;
  identify::Curve data;
  double sigma = 1.0;  // [y units] the noise level per point (with noise_factor: its marginal level)
  // Empty: white noise, residual = (simulated - data) / sigma. Otherwise the lower Cholesky factor
  // L of the target's noise covariance [y^2] (model_scatter.hpp), residual = L^-1 (simulated - data):
  // correlated noise whitened, so the chi-square, BIC and residual tests stay valid.
  Eigen::MatrixXd noise_factor;
};

struct FitOptions {
  int jobs = 1;  // model evaluations at once
  int max_iterations = 60;
  // Finite-difference step, fraction of each variable's range. 1e-5 suits smooth models; a DEM
  // curve changes chaotically under tiny parameter changes (contact order, trajectory
  // divergence), so DEM fits use ~0.02: the difference must be dominated by the parameter's
  // systematic effect, not by that trajectory noise (docs/diagnose.md).
  double fd_step = 1e-5;
  bool central_differences = false;  // (r(u+h) - r(u-h)) / 2h: second-order, 2 evaluations per column
  // Broyden (1965) rank-one secant update of the Jacobian after every trial step, the
  // finite-difference Jacobian being recomputed only when a step fails or at convergence.
  bool broyden = true;
  double relative_tolerance = 1e-9;  // stop when the cost decreases by less than this fraction
  // Stop when the chi-square decreases by less than this (chi-square units): a change far below 1
  // cannot move a BIC comparison whose threshold is 10.
  double absolute_tolerance = 0.01;
  int max_evaluations = 0;  // stop after about this many model evaluations (0 = no limit)
  unsigned long seed = 0;   // passed to the model (EvaluationContext)
  // Called after every accepted step (step number from 1, model evaluations so far, the
  // chi-square reached), so that a fit of DEM runs lasting many minutes is not silent.
  std::function<void(int iteration, int evaluations, double chi_square)> on_step;
};

struct FitResult {
  identify::ParameterSet parameters;  // fixed + fitted values
  std::vector<double> values;         // fitted values, FitVariable order
  double chi_square = 0.0;            // sum of squared normalised residuals
  Eigen::VectorXd residual;           // normalised, concatenated over targets
  // d residual / d u at the returned point, u = (value - lower) / (upper - lower) per variable
  // (finite differences, possibly Broyden-updated since); reused by the screening and re-fits.
  Eigen::MatrixXd jacobian;
  int evaluations = 0;
  int iterations = 0;
};

// Simulated minus data, in y units, per target (the data x are the abscissae; the simulated
// curve is resampled linearly, so it must be monotone in x). Throws if a curve is missing.
std::vector<std::vector<double>> raw_residuals(const identify::CurveSet& curves, const std::vector<FitTarget>& targets);

// Normalised residual vector of one parameter set (concatenated, divided by each target sigma).
Eigen::VectorXd normalised_residual(const identify::CurveSet& curves, const std::vector<FitTarget>& targets);

// Evaluates the model at several parameter sets, `jobs` at a time; a failed evaluation
// (exception) gives an empty CurveSet. Order of results = order of inputs.
std::vector<identify::CurveSet> evaluate_many(const identify::Model& model,
                                              const std::vector<identify::ParameterSet>& sets, int jobs,
                                              unsigned long seed);

// Normalised residual vector at each parameter set (evaluated `options.jobs` at a time); an empty
// vector where the evaluation or the residual failed.
std::vector<Eigen::VectorXd> residuals_at(const identify::Model& model, const std::vector<identify::ParameterSet>& sets,
                                          const std::vector<FitTarget>& targets, const FitOptions& options);

// Splits x into maximal monotone runs (a new branch where x reverses); returns the first index of
// each branch and, last, x.size(). A repeated x value stays in the current branch.
std::vector<std::size_t> monotone_branches(const std::vector<double>& x);

// Minimises the chi-square over the variables within their bounds, others at `fixed`.
// `initial_jacobian` (optional, d residual / d u at the start, as FitResult::jacobian) replaces
// the first finite-difference Jacobian when its shape fits.
// Throws std::runtime_error if the start point cannot be evaluated.
FitResult fit_least_squares(const identify::Model& model, const identify::ParameterSet& fixed,
                            const std::vector<FitVariable>& variables, const std::vector<FitTarget>& targets,
                            const FitOptions& options, const Eigen::MatrixXd* initial_jacobian = nullptr);

}  // namespace demfit::diagnose
