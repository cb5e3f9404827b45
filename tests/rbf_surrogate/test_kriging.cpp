// Kriging model: interpolation, agreement with an independent dense GP computation, gradient,
// maximum-likelihood anisotropy and noise estimation.
#include "demfit/rbf_surrogate/design.hpp"
#include "demfit/rbf_surrogate/kriging.hpp"
#include "test_functions.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <random>

using namespace demfit::rbf_surrogate;

namespace {

MatrixXd design(int n, int d, std::uint64_t seed) { return latin_hypercube_maximin(n, d, seed, Box::unit(d)); }

// Matérn-5/2 written out independently of the library (Rasmussen & Williams 2006, eq. 4.17).
double matern_reference(double r) {
  return (1.0 + std::sqrt(5.0) * r + 5.0 * r * r / 3.0) * std::exp(-std::sqrt(5.0) * r);
}

double scaled_distance(const VectorXd& a, const VectorXd& b, const VectorXd& length) {
  return (a - b).cwiseQuotient(length).norm();
}

}  // namespace

TEST_CASE("Kriging interpolates its data with zero predictive deviation at the data points",
          "[rbf_surrogate][kriging]") {
  const MatrixXd x = design(30, 2, 3);
  const VectorXd y = testfn::franke_values(x);
  const KrigingModel m = KrigingModel::fit(x, y);
  const double range = y.maxCoeff() - y.minCoeff();
  for (Eigen::Index i = 0; i < x.rows(); ++i) {
    double mean = 0.0, sd = 0.0;
    m.predict(x.row(i).transpose(), mean, sd);
    CHECK(std::abs(mean - y[i]) < 1e-5 * range);
    CHECK(sd < 1e-3 * std::sqrt(m.process_variance()));
  }
  // Away from the data the deviation is positive and the mean stays close to Franke (30 points).
  VectorXd p(2);
  p << 0.5123, 0.4871;
  CHECK(m.standard_deviation(p) > 0.0);
  CHECK(m.mean(p) == Approx(testfn::franke(p[0], p[1])).margin(0.05 * range));
}

TEST_CASE("Kriging prediction equals the GP posterior from an independent dense solve", "[rbf_surrogate][kriging]") {
  const MatrixXd x = design(12, 3, 5);
  VectorXd y(12);
  for (int i = 0; i < 12; ++i) y[i] = std::sin(3 * x(i, 0)) + x(i, 1) * x(i, 2);
  KrigingOptions o;
  o.length_hint = VectorXd::Constant(3, 0.4);
  o.length_hint[1] = 0.7;
  o.fixed_hyperparameters = true;
  o.min_nugget = 1e-10;
  const KrigingModel m = KrigingModel::fit(x, y, o);
  // Reference: R + gI, generalised least squares mean, kriging mean and universal-kriging variance
  // (kriging.hpp formulas) with a full-pivot LU instead of the library's Cholesky.
  const VectorXd& len = o.length_hint;
  MatrixXd r(12, 12);
  for (int i = 0; i < 12; ++i)
    for (int j = 0; j < 12; ++j)
      r(i, j) = matern_reference(scaled_distance(x.row(i), x.row(j), len)) + (i == j ? 1e-10 : 0.0);
  const Eigen::FullPivLU<MatrixXd> lu(r);
  const VectorXd ones = VectorXd::Ones(12);
  const VectorXd ri1 = lu.solve(ones);
  const double mu = ri1.dot(y) / ones.dot(ri1);
  const VectorXd w = lu.solve(y - mu * ones);
  const double sigma2 = (y - mu * ones).dot(w) / 12.0;
  for (const double t : {0.1, 0.37, 0.8}) {
    const VectorXd p = VectorXd::Constant(3, t);
    VectorXd k(12);
    for (int i = 0; i < 12; ++i) k[i] = matern_reference(scaled_distance(p, x.row(i), len));
    const double mean = mu + k.dot(w);
    const double u = 1.0 - ri1.dot(k);
    const double var = sigma2 * (1.0 - k.dot(lu.solve(k)) + u * u / ones.dot(ri1));
    double got_mean = 0.0, got_sd = 0.0;
    m.predict(p, got_mean, got_sd);
    CHECK(got_mean == Approx(mean).epsilon(1e-8));
    CHECK(got_sd == Approx(std::sqrt(var)).epsilon(1e-6));
  }
  CHECK(m.process_variance() == Approx(sigma2).epsilon(1e-8));
}

TEST_CASE("Kriging mean gradient matches central finite differences for both kernels", "[rbf_surrogate][kriging]") {
  const MatrixXd x = design(25, 2, 7);
  const VectorXd y = testfn::franke_values(x);
  for (const KrigingKernel kernel : {KrigingKernel::matern52, KrigingKernel::gaussian}) {
    KrigingOptions o;
    o.kernel = kernel;
    const KrigingModel m = KrigingModel::fit(x, y, o);
    VectorXd p(2), g;
    p << 0.31, 0.64;
    m.mean(p, &g);
    for (int j = 0; j < 2; ++j) {
      const double h = 1e-6;
      VectorXd a = p, b = p;
      a[j] += h;
      b[j] -= h;
      CHECK(g[j] == Approx((m.mean(a) - m.mean(b)) / (2 * h)).epsilon(1e-5).margin(1e-6));
    }
  }
}

TEST_CASE("Maximum likelihood gives a long length scale to a coordinate the function ignores",
          "[rbf_surrogate][kriging]") {
  const MatrixXd x = design(30, 2, 11);
  VectorXd y(30);
  for (int i = 0; i < 30; ++i) y[i] = std::sin(6.0 * x(i, 0));  // independent of x1
  const KrigingModel m = KrigingModel::fit(x, y);
  INFO("length scales " << m.length_scales().transpose());
  CHECK(m.length_scales()[1] > 5.0 * m.length_scales()[0]);
}

TEST_CASE("Kriging with noise estimation recovers the noise variance of noisy data", "[rbf_surrogate][kriging]") {
  const int n = 120;
  const MatrixXd x = design(n, 1, 13);
  std::mt19937_64 rng(17);
  VectorXd y(n);
  const double noise_sd = 0.1;
  for (int i = 0; i < n; ++i) {
    const double u1 = 1.0 - uniform01(rng), u2 = uniform01(rng);
    y[i] = std::sin(4.0 * x(i, 0)) + noise_sd * std::sqrt(-2 * std::log(u1)) * std::cos(6.283185307179586 * u2);
  }
  KrigingOptions o;
  o.estimate_noise = true;
  const KrigingModel m = KrigingModel::fit(x, y, o);
  const double noise_variance = m.nugget() * m.process_variance();
  INFO("estimated noise sd " << std::sqrt(noise_variance));
  // 120 residuals: the sample variance of the noise is within ±30 % of the true one with high probability.
  CHECK(noise_variance > 0.7 * noise_sd * noise_sd);
  CHECK(noise_variance < 1.3 * noise_sd * noise_sd);
  // The smoothed mean follows sin(4x), not the noise.
  VectorXd p(1);
  p << 0.5;
  CHECK(m.mean(p) == Approx(std::sin(2.0)).margin(0.06));
}

TEST_CASE("Kriging kernels and their derivative match the formulas", "[rbf_surrogate][kriging]") {
  for (const double r : {0.0, 0.3, 1.0, 2.5}) {
    CHECK(matern52(r) == Approx(matern_reference(r)).epsilon(1e-14));
    CHECK(correlation(KrigingKernel::gaussian, r) == Approx(std::exp(-0.5 * r * r)).epsilon(1e-14));
    const double h = 1e-6;
    for (const KrigingKernel k : {KrigingKernel::matern52, KrigingKernel::gaussian}) {
      if (r == 0.0) continue;
      const double fd = (correlation(k, r + h) - correlation(k, r - h)) / (2 * h);
      CHECK(correlation_derivative_over_r(k, r) * r == Approx(fd).epsilon(1e-6));
    }
  }
}

TEST_CASE("Kriging fit rejects non-finite values and mismatched sizes with one-line errors",
          "[rbf_surrogate][kriging]") {
  MatrixXd x = design(5, 2, 1);
  VectorXd y = VectorXd::Ones(5);
  y[2] = std::nan("");
  CHECK_THROWS_AS(KrigingModel::fit(x, y), std::invalid_argument);
  CHECK_THROWS_AS(KrigingModel::fit(x, VectorXd::Ones(4)), std::invalid_argument);
  KrigingOptions o;
  o.fixed_hyperparameters = true;  // without a length hint
  CHECK_THROWS_AS(KrigingModel::fit(x, VectorXd::LinSpaced(5, 0, 1), o), std::invalid_argument);
}
