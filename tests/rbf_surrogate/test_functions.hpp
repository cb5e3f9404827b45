#pragma once
// Standard analytic test functions with known minima (shared by tests and bench/rbf_surrogate).
// Sources: Franke (1979) NPS report; Dixon & Szegö (1978) for Branin and Hartmann-6.
#include <Eigen/Dense>

#include <cmath>
#include <vector>

#include "demfit/rbf_surrogate/bounds.hpp"

namespace demfit::rbf_surrogate::testfn {

// Franke's bivariate test function on [0,1]^2.
inline double franke(double x, double y) {
  return 0.75 * std::exp(-(9 * x - 2) * (9 * x - 2) / 4.0 - (9 * y - 2) * (9 * y - 2) / 4.0) +
         0.75 * std::exp(-(9 * x + 1) * (9 * x + 1) / 49.0 - (9 * y + 1) / 10.0) +
         0.5 * std::exp(-(9 * x - 7) * (9 * x - 7) / 4.0 - (9 * y - 3) * (9 * y - 3) / 4.0) -
         0.2 * std::exp(-(9 * x - 4) * (9 * x - 4) - (9 * y - 7) * (9 * y - 7));
}

// Franke's function at each row (x, y) of `points`.
inline Eigen::VectorXd franke_values(const Eigen::MatrixXd& points) {
  Eigen::VectorXd values(points.rows());
  for (Eigen::Index i = 0; i < points.rows(); ++i) values[i] = franke(points(i, 0), points(i, 1));
  return values;
}

// Branin on x1 in [-5, 10], x2 in [0, 15]; global minimum 0.397887 (three minimisers).
constexpr double kBraninMinimum = 0.397887357729739;
inline const std::vector<Variable> kBraninVariables{{"x1", -5.0, 10.0}, {"x2", 0.0, 15.0}};
inline double branin(const Eigen::VectorXd& x) {
  const double pi = 3.141592653589793;
  const double b = 5.1 / (4 * pi * pi), c = 5 / pi, t = 1 / (8 * pi);
  const double u = x[1] - b * x[0] * x[0] + c * x[0] - 6;
  return u * u + 10 * (1 - t) * std::cos(x[0]) + 10;
}

// Hartmann-6 on [0,1]^6; global minimum -3.32237.
constexpr double kHartmann6Minimum = -3.32236801141551;
inline double hartmann6(const Eigen::VectorXd& x) {
  static const double alpha[4] = {1.0, 1.2, 3.0, 3.2};
  static const double a[4][6] = {
      {10, 3, 17, 3.5, 1.7, 8}, {0.05, 10, 17, 0.1, 8, 14}, {3, 3.5, 1.7, 10, 17, 8}, {17, 8, 0.05, 10, 0.1, 14}};
  static const double p[4][6] = {{1312, 1696, 5569, 124, 8283, 5886},
                                 {2329, 4135, 8307, 3736, 1004, 9991},
                                 {2348, 1451, 3522, 2883, 3047, 6650},
                                 {4047, 8828, 8732, 5743, 1091, 381}};
  double f = 0;
  for (int i = 0; i < 4; ++i) {
    double s = 0;
    for (int j = 0; j < 6; ++j) s += a[i][j] * (x[j] - 1e-4 * p[i][j]) * (x[j] - 1e-4 * p[i][j]);
    f -= alpha[i] * std::exp(-s);
  }
  return f;
}

// Rosenbrock in n dimensions; minimum 0 at (1, ..., 1).
inline double rosenbrock(const Eigen::VectorXd& x) {
  double f = 0;
  for (Eigen::Index i = 0; i + 1 < x.size(); ++i)
    f += 100 * (x[i + 1] - x[i] * x[i]) * (x[i + 1] - x[i] * x[i]) + (1 - x[i]) * (1 - x[i]);
  return f;
}

}  // namespace demfit::rbf_surrogate::testfn
