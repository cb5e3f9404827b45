#pragma once
// A small bounded Levenberg-Marquardt fit of model parameters to the study targets, with a
// forward finite-difference Jacobian from model evaluations (run `jobs` at a time). Used for the
// base and augmented fits of the diagnosis: the residual tests need a precise local optimum (a
// residual at the noise level), which the surrogate loop does not guarantee in few runs.
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

// Data to match: each target's data points, its simulated curve name and its noise level.
// Residuals are (simulated y at the data x - data y) / sigma, so the cost is a chi-square.
struct FitTarget {
  std::string name;
  std::string curve;
  identify::Curve data;
  double sigma = 1.0;
};

struct FitOptions {
  int jobs = 1;                  // model evaluations at once
  int max_iterations = 60;
  double fd_step = 1e-5;         // forward-difference step, fraction of each variable's range
  double relative_tolerance = 1e-9;  // stop when the cost decreases by less than this fraction
  unsigned long seed = 0;        // passed to the model (EvaluationContext)
};

struct FitResult {
  identify::ParameterSet parameters;  // fixed + fitted values
  std::vector<double> values;         // fitted values, FitVariable order
  double chi_square = 0.0;            // sum of squared normalised residuals
  Eigen::VectorXd residual;           // normalised, concatenated over targets
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

// Minimises the chi-square over the variables within their bounds, others at `fixed`.
// Throws std::runtime_error if the start point cannot be evaluated.
FitResult fit_least_squares(const identify::Model& model, const identify::ParameterSet& fixed,
                            const std::vector<FitVariable>& variables, const std::vector<FitTarget>& targets,
                            const FitOptions& options);

}  // namespace demfit::diagnose
