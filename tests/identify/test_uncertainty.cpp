#include <catch2/catch.hpp>

#include <cmath>
#include <random>

#include "demfit/identify/uncertainty.hpp"

using namespace demfit::identify;

TEST_CASE("Student-t quantiles match tabulated values", "[identify][uncertainty]") {
  // Tabulated two-sided 95 % values t_{0.975, dof}.
  CHECK(student_t_quantile(0.975, 5) == Approx(2.570582).epsilon(2e-3));
  CHECK(student_t_quantile(0.975, 10) == Approx(2.228139).epsilon(2e-4));
  CHECK(student_t_quantile(0.975, 30) == Approx(2.042272).epsilon(1e-5));
  CHECK(student_t_quantile(0.975, 10000000) == Approx(1.959964).epsilon(1e-6));
}

TEST_CASE("Straight-line fit intervals equal the closed-form least-squares ones", "[identify][uncertainty]") {
  // y = a + b x: J = [1, x], Var(b) = s^2/Sxx, Var(a) = s^2 (1/N + mean(x)^2/Sxx).
  const int N = 25;
  std::mt19937_64 rng(3);
  std::normal_distribution<double> noise(0.0, 0.05);
  Eigen::MatrixXd J(N, 2);
  Eigen::VectorXd r(N);
  double sx = 0, sxx = 0;
  for (int i = 0; i < N; ++i) {
    const double x = i / 10.0;
    J(i, 0) = 1.0;
    J(i, 1) = x;
    r(i) = noise(rng);
    sx += x;
  }
  // Residuals of a least-squares fit are orthogonal to J's columns: project them.
  r -= J * (J.transpose() * J).ldlt().solve(J.transpose() * r);
  const double mean = sx / N;
  for (int i = 0; i < N; ++i) sxx += std::pow(J(i, 1) - mean, 2);
  const double s2 = r.squaredNorm() / (N - 2);
  std::vector<VariableSpec> variables{{"a", -10, 10, 0}, {"b", -10, 10, 0}};
  const auto estimate = estimate_uncertainty(J, r, variables);
  CHECK(estimate.degrees_of_freedom == N - 2);
  CHECK(estimate.residual_variance == Approx(s2).epsilon(1e-12));
  CHECK(estimate.standard_error[1] == Approx(std::sqrt(s2 / sxx)).epsilon(1e-9));
  CHECK(estimate.standard_error[0] == Approx(std::sqrt(s2 * (1.0 / N + mean * mean / sxx))).epsilon(1e-9));
  CHECK(estimate.ci_half_width[1] == Approx(student_t_quantile(0.975, N - 2) * estimate.standard_error[1]));
  // corr(a, b) = -mean / sqrt(mean^2 + Sxx/N)
  CHECK(estimate.correlation(0, 1) == Approx(-mean / std::sqrt(mean * mean + sxx / N)).epsilon(1e-9));
  CHECK_FALSE(estimate.unidentifiable[0]);
  CHECK_FALSE(estimate.unidentifiable[1]);
}

TEST_CASE("A variable the residuals do not depend on is flagged unidentifiable", "[identify][uncertainty]") {
  Eigen::MatrixXd J(10, 3);
  Eigen::VectorXd r(10);
  for (int i = 0; i < 10; ++i) {
    J(i, 0) = 1.0;
    J(i, 1) = i;
    J(i, 2) = 0.0;  // no influence at all
    r(i) = 0.01 * ((i % 3) - 1);
  }
  std::vector<VariableSpec> variables{{"a", 0, 1, 0.5}, {"b", 0, 1, 0.5}, {"c", 0, 1, 0.5}};
  const auto estimate = estimate_uncertainty(J, r, variables);
  CHECK(estimate.unidentifiable[2]);
  CHECK_FALSE(estimate.unidentifiable[0]);
  CHECK_FALSE(std::isfinite(estimate.ci_half_width[2]));
  // Two perfectly correlated variables (same column): both flagged.
  J.col(2) = J.col(1);
  const auto aliased = estimate_uncertainty(J, r, variables);
  CHECK(aliased.unidentifiable[1]);
  CHECK(aliased.unidentifiable[2]);
}
