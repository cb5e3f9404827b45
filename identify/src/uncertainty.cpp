#include "demfit/identify/uncertainty.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace demfit::identify {
// Inverse of the standard normal CDF (Acklam's rational approximation, |rel. error| < 1.2e-9).
double normal_quantile(double p) {
  static const double a[] = {-3.969683028665376e+01, 2.209460984245205e+02,  -2.759285104469687e+02,
                             1.383577518672690e+02,  -3.066479806614716e+01, 2.506628277459239e+00};
  static const double b[] = {-5.447609879822406e+01, 1.615858368580409e+02, -1.556989798598866e+02,
                             6.680131188771972e+01, -1.328068155288572e+01};
  static const double c[] = {-7.784894002430293e-03, -3.223964580411365e-01, -2.400758277161838e+00,
                             -2.549732539343734e+00, 4.374664141464968e+00,  2.938163982698783e+00};
  static const double d[] = {7.784695709041462e-03, 3.224671290700398e-01, 2.445134137142996e+00,
                             3.754408661907416e+00};
  const double low = 0.02425;
  if (p < low) {
    const double q = std::sqrt(-2 * std::log(p));
    return (((((c[0] * q + c[1]) * q + c[2]) * q + c[3]) * q + c[4]) * q + c[5]) /
           ((((d[0] * q + d[1]) * q + d[2]) * q + d[3]) * q + 1);
  }
  if (p > 1 - low) return -normal_quantile(1 - p);
  const double q = p - 0.5, r = q * q;
  return (((((a[0] * r + a[1]) * r + a[2]) * r + a[3]) * r + a[4]) * r + a[5]) * q /
         (((((b[0] * r + b[1]) * r + b[2]) * r + b[3]) * r + b[4]) * r + 1);
}

double student_t_quantile(double p, int dof) {
  const double z = normal_quantile(p);
  if (dof <= 0) return std::numeric_limits<double>::infinity();
  const double n = dof, z3 = z * z * z, z5 = z3 * z * z, z7 = z5 * z * z;
  // Cornish-Fisher expansion of the t distribution (Abramowitz & Stegun 26.7.5).
  return z + (z3 + z) / (4 * n) + (5 * z5 + 16 * z3 + 3 * z) / (96 * n * n) +
         (3 * z7 + 19 * z5 + 17 * z3 - 15 * z) / (384 * n * n * n);
}

namespace {

// The linearised interval for a given normal matrix J^T J (physical units), residual variance
// and degrees of freedom; `meat` (optional, J^T Sigma J) adds the sandwich term
// (J^T J)^-1 J^T Sigma J (J^T J)^-1 of a correlated noise with covariance Sigma.
UncertaintyEstimate linearised_estimate(const Eigen::MatrixXd& jtj, double residual_variance, int dof,
                                        const std::vector<VariableSpec>& variables, double confidence,
                                        const Eigen::MatrixXd* meat = nullptr) {
  const int n = static_cast<int>(variables.size());
  UncertaintyEstimate out;
  out.degrees_of_freedom = dof;
  out.residual_variance = residual_variance;
  // Work in range-scaled variables z = x / range so the conditioning test is unit-free.
  Eigen::VectorXd range(n);
  for (int j = 0; j < n; ++j) range(j) = variables[j].upper - variables[j].lower;
  const Eigen::MatrixXd normal = range.asDiagonal() * jtj * range.asDiagonal();
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(normal);
  const Eigen::VectorXd lambda = eigen.eigenvalues();  // ascending
  const double largest = std::max(lambda(n - 1), 0.0);
  out.condition_number = lambda(0) > 0.0 ? largest / lambda(0) : std::numeric_limits<double>::infinity();
  // Pseudo-inverse: near-null directions are dropped (their variance is not estimable).
  Eigen::MatrixXd inverse = Eigen::MatrixXd::Zero(n, n);
  std::vector<bool> weak(n, false);
  for (int k = 0; k < n; ++k) {
    if (largest > 0.0 && lambda(k) > 1e-10 * largest) {
      inverse += eigen.eigenvectors().col(k) * eigen.eigenvectors().col(k).transpose() / lambda(k);
    } else {
      for (int j = 0; j < n; ++j)
        if (std::abs(eigen.eigenvectors()(j, k)) > 0.1) weak[j] = true;
    }
  }
  const Eigen::MatrixXd physical_inverse = range.asDiagonal() * inverse * range.asDiagonal();
  Eigen::MatrixXd covariance = residual_variance * physical_inverse;
  if (meat) covariance += physical_inverse * *meat * physical_inverse;
  const double t = student_t_quantile(0.5 * (1.0 + confidence), dof);
  out.correlation = Eigen::MatrixXd::Zero(n, n);
  for (int j = 0; j < n; ++j) {
    const double se = std::sqrt(std::max(covariance(j, j), 0.0));
    out.standard_error.push_back(weak[j] ? std::numeric_limits<double>::infinity() : se);
    out.ci_half_width.push_back(weak[j] ? std::numeric_limits<double>::infinity() : t * se);
    out.unidentifiable.push_back(weak[j] || t * se > 0.5 * range(j));
    for (int i = 0; i < n; ++i) {
      const double denominator = std::sqrt(std::max(covariance(i, i), 0.0) * std::max(covariance(j, j), 0.0));
      out.correlation(i, j) = denominator > 0.0 ? covariance(i, j) / denominator : (i == j ? 1.0 : 0.0);
    }
  }
  return out;
}

UncertaintyEstimate nothing_identifiable(int n, int runs) {
  const double inf = std::numeric_limits<double>::infinity();
  UncertaintyEstimate out;
  out.standard_error.assign(n, inf);
  out.ci_half_width.assign(n, inf);
  out.unidentifiable.assign(n, true);
  out.correlation = Eigen::MatrixXd::Identity(n, n);
  out.condition_number = inf;
  out.jacobian_source = "regression";
  out.runs_used = runs;
  out.effect_significance.assign(n, 0.0);
  return out;
}

double physical_of_unit(const VariableSpec& v, double unit) {
  return v.log_scale ? v.lower * std::pow(v.upper / v.lower, unit) : v.lower + unit * (v.upper - v.lower);
}

// Gauss-Newton step of the local linear model in scaled coordinates z = (u - u_best) / spread:
// minimise |r0 + S^T dz|^2 with S^T S debiased (bias = N sigma_fit^2 (X^T X)^-1, full matrix).
std::vector<double> least_squares_centre(const RunSample& sample, const std::vector<VariableSpec>& variables,
                                         const std::vector<int>& kept, const Eigen::MatrixXd& slopes,
                                         const Eigen::VectorXd& intercept, const Eigen::MatrixXd& bias,
                                         const Eigen::VectorXd& spread) {
  const int n = static_cast<int>(variables.size()), k = static_cast<int>(kept.size());
  Eigen::MatrixXd normal(k, k);
  Eigen::VectorXd gradient(k);
  for (int a = 0; a < k; ++a) {
    gradient(a) = slopes.row(kept[a]).dot(intercept);
    for (int b = 0; b < k; ++b)
      normal(a, b) = slopes.row(kept[a]).dot(slopes.row(kept[b])) - bias(kept[a] + 1, kept[b] + 1);
  }
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(normal);
  const double largest = std::max(eigen.eigenvalues()(k - 1), 0.0);
  Eigen::VectorXd step = Eigen::VectorXd::Zero(k);
  for (int c = 0; c < k; ++c) {
    const double lambda = eigen.eigenvalues()(c);
    if (largest > 0.0 && lambda > 1e-10 * largest)
      step -= eigen.eigenvectors().col(c) * eigen.eigenvectors().col(c).dot(gradient) / lambda;
  }
  // Trust region = the sampled spread: |dz| <= 1 in every coordinate (direction kept).
  const double longest = step.size() ? step.cwiseAbs().maxCoeff() : 0.0;
  if (longest > 1.0) step /= longest;
  std::vector<double> out(n);
  Eigen::VectorXd unit = sample.best_unit;
  for (int a = 0; a < k; ++a) unit(kept[a]) = std::clamp(unit(kept[a]) + step(a) * spread(kept[a]), 0.0, 1.0);
  for (int j = 0; j < n; ++j) out[j] = physical_of_unit(variables[j], unit(j));
  return out;
}

}  // namespace

UncertaintyEstimate estimate_uncertainty(const Eigen::MatrixXd& jacobian, const Eigen::VectorXd& residuals,
                                         const std::vector<VariableSpec>& variables, double confidence) {
  const int n = static_cast<int>(variables.size());
  const int dof = std::max(static_cast<int>(residuals.size()) - n, 1);
  return linearised_estimate(jacobian.transpose() * jacobian, residuals.squaredNorm() / dof, dof, variables,
                             confidence);
}

UncertaintyEstimate estimate_uncertainty_from_runs(const RunSample& sample, const std::vector<VariableSpec>& variables,
                                                   double confidence) {
  const int n = static_cast<int>(variables.size());
  const int m = static_cast<int>(sample.unit_points.rows());
  const int N = static_cast<int>(sample.best_residuals.size());
  if (m < n + 2 || N == 0) return nothing_identifiable(n, m);
  // Design matrix [1, (u - u_best) / spread]: the scaling only conditions the solve. A variable
  // that does not vary over the sample gets a zero column (no information: flagged below).
  Eigen::MatrixXd X(m, n + 1);
  X.col(0).setOnes();
  Eigen::VectorXd spread(n);
  for (int j = 0; j < n; ++j) {
    const Eigen::ArrayXd d = sample.unit_points.col(j).array() - sample.best_unit(j);
    spread(j) = d.abs().maxCoeff();
    X.col(j + 1) = spread(j) > 0.0 ? Eigen::VectorXd(d / spread(j)) : Eigen::VectorXd::Zero(m);
  }
  const Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> qr(X);
  const Eigen::MatrixXd B = qr.solve(sample.residuals);  // (n+1) x N regression coefficients
  const int dof_fit = m - static_cast<int>(qr.rank());
  if (dof_fit < 1) return nothing_identifiable(n, m);
  // sigma_fit^2: scatter of the runs about the plane, per residual component.
  const double fit_variance = (sample.residuals - X * B).squaredNorm() / (static_cast<double>(N) * dof_fit);
  const Eigen::MatrixXd pseudo_inverse = qr.pseudoInverse();
  const Eigen::MatrixXd xtx_inverse = pseudo_inverse * pseudo_inverse.transpose();
  // Criterion (c) first: each slope row against its own noise level (see the header).
  const Eigen::MatrixXd slopes = B.bottomRows(n);  // n x N, per scaled coordinate
  std::vector<double> significance(n, 0.0);
  std::vector<int> kept;  // variables with a significant effect
  for (int j = 0; j < n; ++j) {
    const double slope = slopes.row(j).norm();
    const double noise = std::sqrt(N * fit_variance * xtx_inverse(j + 1, j + 1));
    significance[j] = spread(j) == 0.0 ? 0.0
                      : noise > 0.0    ? slope / noise
                      : slope > 0.0    ? std::numeric_limits<double>::infinity()
                                       : 0.0;
    if (significance[j] >= 2.0) kept.push_back(j);
  }
  UncertaintyEstimate out = nothing_identifiable(n, m);
  out.simulation_noise_variance = fit_variance;
  out.effect_significance = significance;
  const int dof = std::max(N - n, 1);
  out.degrees_of_freedom = dof;
  // Misfit variance at the optimum: the best run's residuals, or the regression's smoothed
  // prediction there if larger (the best of many noisy runs is a lucky one).
  out.residual_variance = std::max(sample.best_residuals.squaredNorm(), B.row(0).squaredNorm()) / dof;
  if (kept.empty()) return out;
  // J^T J of the kept variables. Built from estimated slopes it is biased upwards by the slopes'
  // own noise, E[B^T B] = B_true^T B_true + N sigma_fit^2 (X^T X)^-1 (slope block): subtract
  // that term. Variables without a significant effect are left out, so the intervals of the
  // others are conditional on them (their slopes are noise: keeping them would only mix noise
  // into every direction).
  const int k = static_cast<int>(kept.size());
  const Eigen::MatrixXd scatter = sample.residuals - X * B;  // m x N, simulation noise of each run
  Eigen::MatrixXd jacobian(N, k);                            // physical units
  Eigen::MatrixXd bias(k, k);
  std::vector<VariableSpec> kept_variables;
  for (int a = 0; a < k; ++a) {
    const int i = kept[a];
    kept_variables.push_back(variables[i]);
    // Scaled coordinate -> physical: d(scaled)/d(physical) = (du/dx) / spread.
    const double to_physical = sample.unit_per_physical(i) / spread(i);
    jacobian.col(a) = slopes.row(i).transpose() * to_physical;
    for (int b = 0; b < k; ++b)
      bias(a, b) = N * fit_variance * xtx_inverse(i + 1, kept[b] + 1) * to_physical *
                   sample.unit_per_physical(kept[b]) / spread(kept[b]);
  }
  const Eigen::MatrixXd jtj = jacobian.transpose() * jacobian - bias;
  // The simulation noise is correlated along the curve (a different packing history shifts the
  // whole curve): its effect on the parameters is the sandwich term with Sigma estimated from
  // the runs' scatter about the plane, Sigma = E^T E / dof_fit.
  const Eigen::MatrixXd projected = scatter * jacobian;  // m x k
  const Eigen::MatrixXd meat = projected.transpose() * projected / dof_fit;
  const UncertaintyEstimate sub =
      linearised_estimate(jtj, out.residual_variance, dof, kept_variables, confidence, &meat);
  out.condition_number = sub.condition_number;
  out.least_squares_estimate = least_squares_centre(sample, variables, kept, slopes, B.row(0).transpose(),
                                                    N * fit_variance * xtx_inverse, spread);
  for (int a = 0; a < k; ++a) {
    const int i = kept[a];
    out.standard_error[i] = sub.standard_error[a];
    out.ci_half_width[i] = sub.ci_half_width[a];
    out.unidentifiable[i] = sub.unidentifiable[a];
    for (int b = 0; b < k; ++b) out.correlation(i, kept[b]) = sub.correlation(a, b);
  }
  return out;
}

}  // namespace demfit::identify
