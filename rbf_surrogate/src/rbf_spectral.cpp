// Spectral solution of the RBF system and the closed-form leave-one-out criterion (Rippa 1999).
#include "rbf_spectral.hpp"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace demfit::rbf_surrogate::detail {

namespace {

constexpr double kSingular = 1e-11;

void check_inputs(const MatrixXd& points, const MatrixXd& values, const RbfOptions& options) {
  const auto n = points.rows();
  if (n < 2) throw std::invalid_argument("RBF fit: need at least 2 points, got " + std::to_string(n));
  if (points.cols() < 1) throw std::invalid_argument("RBF fit: points have no coordinates");
  if (values.rows() != n)
    throw std::invalid_argument("RBF fit: " + std::to_string(values.rows()) + " value rows for " + std::to_string(n) +
                                " points");
  if (values.cols() < 1) throw std::invalid_argument("RBF fit: values have no output columns");
  if (!points.allFinite()) throw std::invalid_argument("RBF fit: a point coordinate is NaN or infinite");
  if (!values.allFinite()) throw std::invalid_argument("RBF fit: a value is NaN or infinite");
  if (!uses_width(options.basis) && options.tail != Tail::linear)
    throw std::invalid_argument(std::string("RBF fit: basis ") + basis_name(options.basis) +
                                " is conditionally positive definite of order 2; use Tail::linear");
  const int q = tail_terms(options.tail, static_cast<int>(points.cols()));
  if (n <= q)
    throw std::invalid_argument("RBF fit: " + std::to_string(n) + " points but the tail has " + std::to_string(q) +
                                " terms; need at least " + std::to_string(q + 1) + " points");
  if (options.fixed_width && !(*options.fixed_width > 0.0 && std::isfinite(*options.fixed_width)))
    throw std::invalid_argument("RBF fit: fixed_width must be a positive number");
  if (options.fixed_smoothing && !(*options.fixed_smoothing >= 0.0 && std::isfinite(*options.fixed_smoothing)))
    throw std::invalid_argument("RBF fit: fixed_smoothing must be a non-negative number");
}

// Per-output normalisation by the variance (outputs with zero spread get the largest variance so a
// constant output neither dominates nor divides by zero), then compression: the criterion only
// depends on Y Y^T, so Y (n×m) may be replaced by R^T from Y^T = Q R (n×n) when m > n.
MatrixXd scale_values(const MatrixXd& values) {
  const auto n = values.rows(), m = values.cols();
  VectorXd var(m);
  for (Eigen::Index j = 0; j < m; ++j) {
    const double mean = values.col(j).mean();
    var[j] = (values.col(j).array() - mean).square().sum() / static_cast<double>(n);
  }
  const double fallback = var.maxCoeff() > 0.0 ? var.maxCoeff() : 1.0;
  MatrixXd scaled(n, m);
  for (Eigen::Index j = 0; j < m; ++j)
    scaled.col(j) = values.col(j) / std::sqrt((var[j] > 1e-300 ? var[j] : fallback) * static_cast<double>(m));
  if (m <= n) return scaled;
  Eigen::HouseholderQR<MatrixXd> qr(scaled.transpose());
  const MatrixXd r = qr.matrixQR().topRows(n).triangularView<Eigen::Upper>();
  return r.transpose();
}

}  // namespace

Prepared prepare(const MatrixXd& points, const MatrixXd& values, const RbfOptions& options) {
  check_inputs(points, values, options);
  Prepared p{options.basis,
             options.tail,
             options.criterion,
             points,
             squared_distances(points, points),
             tail_matrix(options.tail, points),
             MatrixXd(),
             scale_values(values)};
  const auto n = points.rows();
  double max_d2 = 0.0, nn_sum = 0.0;
  for (Eigen::Index i = 0; i < n; ++i) {
    double nn = std::numeric_limits<double>::infinity();
    for (Eigen::Index j = 0; j < n; ++j)
      if (j != i) {
        nn = std::min(nn, p.d2(i, j));
        max_d2 = std::max(max_d2, p.d2(i, j));
      }
    nn_sum += std::sqrt(nn);
  }
  p.diameter = std::sqrt(max_d2);
  p.nearest_mean = nn_sum / static_cast<double>(n);
  for (Eigen::Index i = 0; i < n; ++i)
    for (Eigen::Index j = i + 1; j < n; ++j)
      if (std::sqrt(p.d2(i, j)) <= 1e-10 * std::max(1.0, p.diameter))
        throw std::invalid_argument("RBF fit: duplicate points (rows " + std::to_string(i) + " and " +
                                    std::to_string(j) + "); remove repeated designs or average them");
  const auto q = p.tail_p.cols();
  if (q == 0) {
    p.null_basis = MatrixXd::Identity(n, n);
    return p;
  }
  Eigen::ColPivHouseholderQR<MatrixXd> qr(p.tail_p);
  qr.setThreshold(1e-10);
  if (qr.rank() < q)
    throw std::invalid_argument(
        "RBF fit: points are affinely dependent (all on a hyperplane); the linear "
        "tail needs points spanning every dimension, use Tail::constant");
  const MatrixXd full_q = qr.householderQ();
  p.null_basis = full_q.rightCols(n - q);
  return p;
}

Spectrum spectrum(const Prepared& prepared, double width) {
  const MatrixXd a = kernel_from_squared_distances(prepared.basis, prepared.d2, width, prepared.tail != Tail::none);
  const MatrixXd& q = prepared.null_basis;
  const MatrixXd b = q.transpose() * a * q;
  Eigen::SelfAdjointEigenSolver<MatrixXd> eig(b);
  Spectrum s;
  s.eigen = eig.eigenvalues();
  s.w = q * eig.eigenvectors();
  s.z = s.w.transpose() * prepared.scaled_values;
  s.scale = std::max(s.eigen.cwiseAbs().maxCoeff(), std::numeric_limits<double>::min());
  s.sign = definiteness_sign(prepared.basis);
  s.width = width;
  return s;
}

namespace {

// 1 / (eigenvalue + s·λ), or an empty vector when the system is numerically singular.
VectorXd inverse_denominators(const Spectrum& s, double smoothing) {
  const VectorXd denom = s.eigen.array() + s.sign * smoothing;
  if (denom.cwiseAbs().minCoeff() < kSingular * s.scale) return VectorXd();
  return denom.cwiseInverse();
}

}  // namespace

double criterion(const Prepared& prepared, const Spectrum& s, double smoothing) {
  const VectorXd inv = inverse_denominators(s, smoothing);
  if (inv.size() == 0) return std::numeric_limits<double>::infinity();
  const MatrixXd alpha = s.w * (inv.asDiagonal() * s.z);
  const VectorXd diag = s.w.array().square().matrix() * inv;  // H_ii
  const auto n = static_cast<double>(alpha.rows());
  if (prepared.criterion == WidthCriterion::gcv) {
    // Golub-Heath-Wahba: the diagonal replaced by its mean.
    const double mean_diag = diag.mean();
    return alpha.squaredNorm() / (mean_diag * mean_diag) / n;
  }
  double sum = 0.0;
  for (Eigen::Index i = 0; i < alpha.rows(); ++i) sum += alpha.row(i).squaredNorm() / (diag[i] * diag[i]);
  return std::isfinite(sum) ? sum / n : std::numeric_limits<double>::infinity();
}

void solve(const Prepared& prepared, const Spectrum& s, const MatrixXd& values, double smoothing, MatrixXd& alpha,
           MatrixXd& beta, MatrixXd& loo_residuals) {
  const VectorXd inv = inverse_denominators(s, smoothing);
  if (inv.size() == 0)
    throw std::invalid_argument(
        "RBF fit: the system is numerically singular at the chosen width; "
        "remove near-duplicate points or choose a smaller fixed_width");
  alpha = s.w * (inv.asDiagonal() * (s.w.transpose() * values));
  const VectorXd diag = s.w.array().square().matrix() * inv;
  loo_residuals = diag.cwiseInverse().asDiagonal() * alpha;
  const auto q = prepared.tail_p.cols();
  if (q == 0) {
    beta = MatrixXd(0, values.cols());
    return;
  }
  // P β = Y - (A + s·λ·I) α holds exactly (the residual lies in range(P)); least squares recovers β.
  MatrixXd a = kernel_from_squared_distances(prepared.basis, prepared.d2, s.width, prepared.tail != Tail::none);
  a.diagonal().array() += s.sign * smoothing;
  const MatrixXd residual = values - a * alpha;
  beta = prepared.tail_p.colPivHouseholderQr().solve(residual);
}

}  // namespace demfit::rbf_surrogate::detail
