#pragma once
// Spectral form of the RBF saddle system, used for the width/smoothing search and the final fit.
//   [A + s·λ·I  P] [α]   [Y]
//   [P^T        0] [β] = [0]
// With Q an orthonormal basis of null(P^T): α = Q (Q^T A Q + s·λ·I)^-1 Q^T Y, and the upper-left
// block of the inverse is H = Q (Q^T A Q + s·λ·I)^-1 Q^T. One symmetric eigendecomposition of
// Q^T A Q per width serves every λ, and Rippa's closed-form leave-one-out residual is α_i / H_ii.
#include "rbf_internal.hpp"

#include <Eigen/QR>

namespace demfit::rbf_surrogate::detail {

struct Prepared {
  Basis basis;
  Tail tail;
  WidthCriterion criterion;
  MatrixXd points;            // n×d
  MatrixXd d2;                // n×n squared distances
  MatrixXd tail_p;            // n×q
  MatrixXd null_basis;        // n×(n-q), orthonormal, P^T Q = 0
  MatrixXd scaled_values;     // n×m_eff: outputs / sqrt(m·var), compressed to <= n columns
  double nearest_mean = 0.0;  // mean nearest-neighbour distance
  double diameter = 0.0;      // largest pairwise distance
};

// Validates inputs (one-line std::invalid_argument) and builds the width-independent parts.
Prepared prepare(const MatrixXd& points, const MatrixXd& values, const RbfOptions& options);

struct Spectrum {
  MatrixXd w;          // n×k = Q V
  VectorXd eigen;      // k eigenvalues of Q^T A Q
  MatrixXd z;          // k×m_eff = W^T scaled_values
  double scale = 1.0;  // max |eigenvalue|, the unit of the relative smoothing
  double sign = 1.0;
  double width = 0.0;
};

Spectrum spectrum(const Prepared& prepared, double width);

// Normalised criterion: mean over outputs of (sum_i e_ij^2 / n) / var_j. +infinity when the system
// is numerically singular (smallest |eigenvalue + s·λ| below 1e-13 of the largest).
double criterion(const Prepared& prepared, const Spectrum& s, double smoothing_absolute);

// Coefficients for the real (unscaled) values at the chosen width and smoothing.
void solve(const Prepared& prepared, const Spectrum& s, const MatrixXd& values, double smoothing_absolute,
           MatrixXd& alpha, MatrixXd& beta, MatrixXd& loo_residuals);

}  // namespace demfit::rbf_surrogate::detail
