#pragma once
// The model's own scatter: a DEM curve is a chaotic trajectory's average, so two runs
// whose parameters differ only in round-off differ by a smooth, correlated error of about the size
// of the data noise (s = 4 drum free surface: 0.5-0.8 mm against sigma 0.46 mm). A residual at the
// true parameters then looks "structural" to tests that assume white data noise alone, and no
// candidate — the true one included — can ever pass them. Here that scatter is measured from
// replicas at one parameter point and modelled per target as a stationary AR(1) process along the
// curve, added to the white data noise:
//   Sigma_t = sigma_data^2 I + sigma_scatter^2 R(rho),   R_ij = rho^|i - j|,
// and residuals are whitened by the Cholesky factor of Sigma_t (least_squares.hpp, FitTarget).
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "demfit/diagnose/least_squares.hpp"

namespace demfit::diagnose {

struct TargetScatter {
  std::string target;
  double sigma = 0.0;  // [y units] standard deviation of one run about the replicas' mean
  double lag1 = 0.0;   // correlation of neighbouring points' deviations (clamped to [0, 0.95])
  int replicas = 0;    // curves used (the base curve included)
};

// Per target: sigma and lag-1 correlation of the deviations of `replica_residuals` (each a
// normalised residual vector over all targets, as FitResult::residual, from runs differing only in
// round-off) about their pointwise mean. Needs at least 2 replicas.
std::vector<TargetScatter> estimate_scatter(const std::vector<Eigen::VectorXd>& replica_residuals,
                                            const std::vector<FitTarget>& targets);

// Lower Cholesky factor of sigma_data^2 I + scatter.sigma^2 R(scatter.lag1) for n points.
Eigen::MatrixXd scatter_noise_factor(int points, double sigma_data, const TargetScatter& scatter);

// Parameter sets of the replicas: `base` with every variable moved by k x 1e-7 of its range
// (k = 1..replicas; downwards where upwards would leave the range): round-off-sized changes, so
// only the trajectory changes.
std::vector<identify::ParameterSet> replica_parameter_sets(const identify::ParameterSet& base,
                                                           const std::vector<FitVariable>& variables, int replicas);

// The targets with the scatter in their noise model where one run's scatter exceeds `threshold` x
// the data noise (noise_factor set, sigma the total); the others unchanged. `whitened[t]` tells
// which. The scatter's variance counts 1 + `data_scatter_ratio` times: the model run's own
// trajectory, plus the data's own scatter as a multiple of it (1: the data are one such run).
std::vector<FitTarget> with_scatter(const std::vector<FitTarget>& targets, const std::vector<TargetScatter>& scatter,
                                    double threshold, double data_scatter_ratio, std::vector<bool>& whitened);

// Standard deviation of the replicas' chi-squares after `renormalisation` (r -> A r): how noisy one
// evaluation's chi-square is at fixed parameters.
double chi_square_spread(const std::vector<Eigen::VectorXd>& replica_residuals, const Eigen::MatrixXd& renormalisation);

// Linear map from the residual normalised by the old targets to the one of `whitened` (per target:
// L^-1 sigma_old), block diagonal: r_new = A r_old and J_new = A J_old without a model evaluation.
Eigen::MatrixXd renormalisation(const std::vector<FitTarget>& old_targets, const std::vector<FitTarget>& whitened);

}  // namespace demfit::diagnose
