// Residual statistics against analytic values and known distributions (Monte Carlo, seeded).
#include <catch2/catch.hpp>

#include <cmath>
#include <random>

#include "demfit/diagnose/residual_tests.hpp"

using namespace demfit::diagnose;

namespace {
std::vector<double> white_noise(int n, double sigma, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal(0.0, sigma);
  std::vector<double> out(n);
  for (auto& v : out) v = normal(rng);
  return out;
}
// Exact chi-square upper tail for even k: exp(-x/2) sum_{i<k/2} (x/2)^i / i!.
double chi_square_upper_even(double x, int k) {
  double term = 1.0, sum = 1.0;
  for (int i = 1; i < k / 2; ++i) {
    term *= (x / 2.0) / i;
    sum += term;
  }
  return std::exp(-x / 2.0) * sum;
}
}  // namespace

TEST_CASE("The noise estimator recovers the sigma of white noise on a smooth curve within 15 percent") {
  for (unsigned seed : {1u, 2u, 3u}) {
    const int n = 201;
    const double sigma = 0.02;
    const auto noise = white_noise(n, sigma, seed);
    std::vector<double> x(n), y(n);
    for (int i = 0; i < n; ++i) {
      x[i] = 2.0 * i / (n - 1) + 0.3 * std::sin(0.1 * i) / n;  // slightly uneven spacing
      y[i] = std::sin(3.0 * x[i]) + 0.5 * x[i] + noise[i];
    }
    CHECK(estimate_noise_sigma(x, y) == Approx(sigma).epsilon(0.15));
  }
}

TEST_CASE("The noise estimator gives zero on a noise-free straight line with uneven spacing") {
  const std::vector<double> x{0.0, 0.1, 0.35, 0.4, 0.9, 1.3};
  std::vector<double> y;
  for (double v : x) y.push_back(2.0 - 3.0 * v);
  CHECK(estimate_noise_sigma(x, y) == Approx(0.0).margin(1e-12));
}

TEST_CASE("The runs test counts runs and matches the Wald-Wolfowitz mean and variance") {
  // 10 positive and 10 negative in 4 blocks: 4 runs; mean 11, variance 2*100*180/(400*19).
  std::vector<double> r;
  for (int b = 0; b < 4; ++b)
    for (int i = 0; i < 5; ++i) r.push_back(b % 2 == 0 ? 1.0 : -1.0);
  const RunsTest t = runs_test(r);
  CHECK(t.runs == 4);
  CHECK(t.positive == 10);
  CHECK(t.negative == 10);
  CHECK(t.z == Approx((4.0 - 11.0 + 0.5) / std::sqrt(36000.0 / 7600.0)).epsilon(1e-12));
  CHECK(t.p_value < 0.002);
  // Alternating signs: as many runs as points, no evidence of structure.
  std::vector<double> alternating;
  for (int i = 0; i < 20; ++i) alternating.push_back(i % 2 ? 1.0 : -1.0);
  CHECK(runs_test(alternating).p_value > 0.99);
}

TEST_CASE("The runs test and the autocorrelation test hold their level on white noise") {
  // Under H0 p-values are ~uniform: the share below 0.05 must be near 0.05 (binomial sd 0.007
  // for 1000 trials; tolerance 0.025 covers the normal approximations).
  int runs_rejections = 0, lag_rejections = 0;
  const int trials = 1000;
  for (int k = 0; k < trials; ++k) {
    const auto r = white_noise(100, 1.0, 100 + k);
    runs_rejections += runs_test(r).p_value < 0.05;
    lag_rejections += autocorrelation_test(r).p_value < 0.05;
  }
  CHECK(runs_rejections / double(trials) == Approx(0.05).margin(0.025));
  CHECK(lag_rejections / double(trials) == Approx(0.05).margin(0.025));
}

TEST_CASE("The autocorrelation test estimates the lag-1 correlation of an AR(1) series and rejects it") {
  const int n = 2000;
  const auto e = white_noise(n, 1.0, 7);
  std::vector<double> r(n);
  r[0] = e[0];
  for (int i = 1; i < n; ++i) r[i] = 0.6 * r[i - 1] + e[i];
  const AutocorrelationTest t = autocorrelation_test(r);
  CHECK(t.lag1 == Approx(0.6).margin(0.05));  // sd of the estimate ~ 0.018
  CHECK(t.durbin_watson == Approx(2.0 * (1.0 - t.lag1)).margin(0.01));
  CHECK(t.p_value < 1e-6);
}

TEST_CASE("The chi-square upper tail approximation agrees with the exact even-dof formula") {
  for (int k : {10, 20, 40})
    for (double q : {0.5, 1.0, 1.5, 2.0}) {
      const double x = q * k;
      const double exact = chi_square_upper_even(x, k);
      if (exact < 1e-4) continue;
      INFO("k = " << k << ", x = " << x);
      CHECK(chi_square_upper_p(x, k) == Approx(exact).epsilon(0.1).margin(0.003));
    }
}

TEST_CASE("The variance test passes residuals at the noise level and rejects residuals twice as large") {
  const auto r = white_noise(200, 1.0, 11);
  CHECK(variance_test(r, 1.0, 3, 0.0).p_value > 0.01);
  CHECK(variance_test(r, 0.5, 3, 0.0).p_value < 1e-6);
  // With sigma estimated from 100 effective dof the test is less sure, but a factor 4 in variance is clear.
  CHECK(variance_test(r, 0.5, 3, 100.0).p_value < 1e-4);
}

TEST_CASE("Localisation puts the largest excess in the region where a bump was added") {
  const int n = 90;
  ResidualSegment s{"curve", {}, white_noise(n, 0.01, 5), 0.01};
  for (int i = 0; i < n; ++i) {
    s.x.push_back(double(i) / (n - 1));
    if (i >= 70) s.residual[i] += 0.05;
  }
  const ResidualAnalysis a = analyse_residuals({s}, 0, 0.0, 0.01);
  REQUIRE(a.regions.size() == 3);
  REQUIRE(a.worst_region == 2);
  CHECK(a.regions[2].label.find("last third") != std::string::npos);
  CHECK(a.structural);
  // A loop (x up then down) is split into two branches of three regions each.
  ResidualSegment loop{"loop", {}, white_noise(60, 0.01, 6), 0.01};
  for (int i = 0; i < 60; ++i) loop.x.push_back(i < 30 ? i / 29.0 : (59 - i) / 29.0);
  const ResidualAnalysis b = analyse_residuals({loop}, 0, 0.0, 0.01);
  CHECK(b.regions.size() == 6);
  CHECK(b.regions[3].label.find("x-decreasing branch") != std::string::npos);
  CHECK_FALSE(b.structural);
}

TEST_CASE("Failing only the lag-1 test is told apart from failing any other residual test", "[diagnose][residual]") {
  ResidualAnalysis a;
  a.alpha = 0.05;  // each test at 0.0125
  a.runs.p_value = 0.5;
  a.variance.p_value = 0.3;
  a.smooth.p_value = 0.2;
  a.autocorrelation.p_value = 0.011;
  CHECK(fails_only_autocorrelation(a));
  a.autocorrelation.p_value = 0.0125;  // not below the per-test level: nothing fails
  CHECK_FALSE(fails_only_autocorrelation(a));
  a.autocorrelation.p_value = 0.011;
  a.runs.p_value = 0.01;  // two tests fail
  CHECK_FALSE(fails_only_autocorrelation(a));
}
