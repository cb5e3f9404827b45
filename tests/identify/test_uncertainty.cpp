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

namespace {

// Runs scattered around an optimum in unit coordinates, m x n.
Eigen::MatrixXd scattered_runs(int m, const Eigen::VectorXd& center, double half_width, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> uniform(-half_width, half_width);
  Eigen::MatrixXd points(m, center.size());
  for (int i = 0; i < m; ++i)
    for (int j = 0; j < center.size(); ++j) points(i, j) = center(j) + uniform(rng);
  return points;
}

}  // namespace

TEST_CASE("The regression estimate on exactly linear runs equals the estimate with the true Jacobian",
          "[identify][uncertainty]") {
  // r(u) = r0 + A (u - u*) exactly: the regression recovers A, its scatter is zero, so s^2 and
  // the intervals are those of the closed form with J = A diag(du/dx).
  const int N = 30, n = 2, m = 9;
  std::mt19937_64 rng(5);
  std::normal_distribution<double> normal(0.0, 1.0);
  Eigen::MatrixXd A(N, n);
  Eigen::VectorXd r0(N);
  for (int k = 0; k < N; ++k) {
    A(k, 0) = 1.0 + 0.1 * k;
    A(k, 1) = std::sin(0.3 * k);
    r0(k) = 0.01 * normal(rng);
  }
  RunSample sample;
  sample.best_unit = Eigen::Vector2d(0.4, 0.6);
  sample.unit_points = scattered_runs(m, sample.best_unit, 0.05, 9);
  sample.residuals.resize(m, N);
  for (int i = 0; i < m; ++i)
    sample.residuals.row(i) = (r0 + A * (sample.unit_points.row(i).transpose() - sample.best_unit)).transpose();
  sample.best_residuals = r0;
  sample.unit_per_physical = Eigen::Vector2d(0.5, 2.0);  // variables of range 2 and 0.5
  const std::vector<VariableSpec> variables{{"a", 0, 2, 1}, {"b", 0, 0.5, 0.25}};
  const auto from_runs = estimate_uncertainty_from_runs(sample, variables);
  const auto exact = estimate_uncertainty(A * sample.unit_per_physical.asDiagonal(), r0, variables);
  CHECK(from_runs.jacobian_source == "regression");
  CHECK(from_runs.runs_used == m);
  CHECK(from_runs.simulation_noise_variance < 1e-20);
  for (int j = 0; j < n; ++j) {
    CHECK(from_runs.ci_half_width[j] == Approx(exact.ci_half_width[j]).epsilon(1e-8));
    CHECK_FALSE(from_runs.unidentifiable[j]);
  }
  CHECK(from_runs.correlation(0, 1) == Approx(exact.correlation(0, 1)).epsilon(1e-8));
  // The least-squares centre is the Gauss-Newton step of the exact linear model:
  // du = -(A^T A)^-1 A^T r0 (unit coordinates), physical = lower + u * range.
  const Eigen::VectorXd du = -(A.transpose() * A).ldlt().solve(A.transpose() * r0);
  REQUIRE(du.cwiseAbs().maxCoeff() < 0.05);  // inside the sampled spread: no trust-region cut
  REQUIRE(from_runs.least_squares_estimate.size() == 2);
  CHECK(from_runs.least_squares_estimate[0] == Approx(2.0 * (0.4 + du(0))).epsilon(1e-9));
  CHECK(from_runs.least_squares_estimate[1] == Approx(0.5 * (0.6 + du(1))).epsilon(1e-9));
}

TEST_CASE("A variable whose effect is below the simulation noise is flagged and its interval widens",
          "[identify][uncertainty]") {
  // Residuals: a strong linear effect of u0, none of u1, plus run-to-run noise sigma (as DEM
  // trajectory noise). A derivative of an interpolant through these runs would see steep random
  // slopes in u1; the regression sees a slope indistinguishable from zero.
  const int N = 40, m = 12;
  const double sigma = 0.02;
  std::mt19937_64 rng(17);
  std::normal_distribution<double> normal(0.0, 1.0);
  RunSample sample;
  sample.best_unit = Eigen::Vector2d(0.5, 0.5);
  sample.unit_points = scattered_runs(m, sample.best_unit, 0.1, 3);
  sample.residuals.resize(m, N);
  for (int i = 0; i < m; ++i)
    for (int k = 0; k < N; ++k)
      sample.residuals(i, k) = (1.0 + 0.05 * k) * (sample.unit_points(i, 0) - 0.5) + sigma * normal(rng);
  sample.best_residuals = Eigen::VectorXd::Zero(N);
  for (int k = 0; k < N; ++k) sample.best_residuals(k) = sigma * normal(rng);
  sample.unit_per_physical = Eigen::Vector2d(1.0, 1.0);
  const std::vector<VariableSpec> variables{{"strong", 0, 1, 0.5}, {"weak", 0, 1, 0.5}};
  const auto estimate = estimate_uncertainty_from_runs(sample, variables);
  INFO("significance strong " << estimate.effect_significance[0] << ", weak " << estimate.effect_significance[1]
                              << "; half-widths " << estimate.ci_half_width[0] << ", " << estimate.ci_half_width[1]);
  CHECK_FALSE(estimate.unidentifiable[0]);
  CHECK(estimate.unidentifiable[1]);
  CHECK(estimate.effect_significance[0] > 10.0);
  CHECK(estimate.effect_significance[1] < 2.0);
  // The scatter about the plane estimates sigma^2 (m - 3 = 9 dof per component, 40 components).
  CHECK(estimate.simulation_noise_variance == Approx(sigma * sigma).epsilon(0.25));
  // The strong variable's interval is narrower than the sampled spread (+-0.1).
  CHECK(estimate.ci_half_width[0] < 0.1);
}

TEST_CASE("Too few runs for a regression leave every variable unidentifiable", "[identify][uncertainty]") {
  RunSample sample;
  sample.best_unit = Eigen::Vector2d(0.5, 0.5);
  sample.unit_points = scattered_runs(3, sample.best_unit, 0.1, 1);
  sample.residuals = Eigen::MatrixXd::Ones(3, 5);
  sample.best_residuals = Eigen::VectorXd::Ones(5);
  sample.unit_per_physical = Eigen::Vector2d(1.0, 1.0);
  const auto estimate = estimate_uncertainty_from_runs(sample, {{"a", 0, 1, 0.5}, {"b", 0, 1, 0.5}});
  CHECK(estimate.unidentifiable == std::vector<bool>{true, true});
  CHECK_FALSE(std::isfinite(estimate.ci_half_width[0]));
}
