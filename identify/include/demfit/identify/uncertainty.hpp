#pragma once
// Approximate confidence intervals of identified variables (linearised least squares):
//   Cov = s^2 (J^T J)^-1,  s^2 = |r|^2 / (N - n)
// J = d r / d x (residuals w.r.t. the physical variables; from the surrogate in the loop),
// r = residual vector at the optimum, N residuals, n variables. Half-width of the two-sided
// confidence interval = t_{(1+c)/2, N-n} * sqrt(Cov_jj).
// A variable is flagged unidentifiable when its half-width exceeds half its bound range, or
// when J^T J is near-singular (eigenvalue < 1e-10 of the largest, in range-scaled variables)
// and the variable takes part in the near-null direction (|component| > 0.1).
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "demfit/identify/study_spec.hpp"

namespace demfit::identify {

struct UncertaintyEstimate {
  std::vector<double> standard_error;   // per variable, physical units
  std::vector<double> ci_half_width;    // per variable, physical units
  Eigen::MatrixXd correlation;          // n x n
  std::vector<bool> unidentifiable;
  double residual_variance = 0.0;       // s^2
  int degrees_of_freedom = 0;           // N - n
  double condition_number = 0.0;        // of J^T J in range-scaled variables
};

// jacobian: N x n (physical units), residuals: N.
UncertaintyEstimate estimate_uncertainty(const Eigen::MatrixXd& jacobian, const Eigen::VectorXd& residuals,
                                         const std::vector<VariableSpec>& variables, double confidence = 0.95);

// Two-sided Student-t quantile t_{p, dof} (Cornish-Fisher expansion around the normal quantile;
// relative error < 1e-3 for dof >= 3).
double student_t_quantile(double p, int dof);

}  // namespace demfit::identify
