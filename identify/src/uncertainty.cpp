#include "demfit/identify/uncertainty.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace demfit::identify {
namespace {

// Inverse of the standard normal CDF (Acklam's rational approximation, |rel. error| < 1.2e-9).
double normal_quantile(double p) {
  static const double a[] = {-3.969683028665376e+01, 2.209460984245205e+02, -2.759285104469687e+02,
                             1.383577518672690e+02, -3.066479806614716e+01, 2.506628277459239e+00};
  static const double b[] = {-5.447609879822406e+01, 1.615858368580409e+02, -1.556989798598866e+02,
                             6.680131188771972e+01, -1.328068155288572e+01};
  static const double c[] = {-7.784894002430293e-03, -3.223964580411365e-01, -2.400758277161838e+00,
                             -2.549732539343734e+00, 4.374664141464968e+00, 2.938163982698783e+00};
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

}  // namespace

double student_t_quantile(double p, int dof) {
  const double z = normal_quantile(p);
  if (dof <= 0) return std::numeric_limits<double>::infinity();
  const double n = dof, z3 = z * z * z, z5 = z3 * z * z, z7 = z5 * z * z;
  // Cornish-Fisher expansion of the t distribution (Abramowitz & Stegun 26.7.5).
  return z + (z3 + z) / (4 * n) + (5 * z5 + 16 * z3 + 3 * z) / (96 * n * n) +
         (3 * z7 + 19 * z5 + 17 * z3 - 15 * z) / (384 * n * n * n);
}

UncertaintyEstimate estimate_uncertainty(const Eigen::MatrixXd& jacobian, const Eigen::VectorXd& residuals,
                                         const std::vector<VariableSpec>& variables, double confidence) {
  const int n = static_cast<int>(variables.size());
  const int N = static_cast<int>(residuals.size());
  UncertaintyEstimate out;
  out.degrees_of_freedom = std::max(N - n, 1);
  out.residual_variance = residuals.squaredNorm() / out.degrees_of_freedom;
  // Work in range-scaled variables z = x / range so the conditioning test is unit-free.
  Eigen::VectorXd range(n);
  for (int j = 0; j < n; ++j) range(j) = variables[j].upper - variables[j].lower;
  const Eigen::MatrixXd scaled = jacobian * range.asDiagonal();
  const Eigen::MatrixXd normal = scaled.transpose() * scaled;
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(normal);
  const Eigen::VectorXd lambda = eigen.eigenvalues();   // ascending
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
  const Eigen::MatrixXd covariance = out.residual_variance * range.asDiagonal() * inverse * range.asDiagonal();
  const double t = student_t_quantile(0.5 * (1.0 + confidence), out.degrees_of_freedom);
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

}  // namespace demfit::identify
