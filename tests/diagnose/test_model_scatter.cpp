// The model's own (trajectory) scatter measured from replicas and added to the noise
// model as an AR(1) process along the curve; residuals whitened by its Cholesky factor.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>

#include "demfit/diagnose/model_scatter.hpp"

using namespace demfit::diagnose;

namespace {

FitTarget target(const std::string& name, int points, double sigma) {
  FitTarget t;
  t.name = name;
  t.curve = name;
  for (int i = 0; i < points; ++i) {
    t.data.x.push_back(i);
    t.data.y.push_back(0.0);
  }
  t.sigma = sigma;
  return t;
}

// One stationary AR(1) series of n points with standard deviation sigma and lag-1 correlation rho.
Eigen::VectorXd ar1(int n, double sigma, double rho, std::mt19937_64& rng) {
  std::normal_distribution<double> normal(0.0, 1.0);
  Eigen::VectorXd x(n);
  x(0) = sigma * normal(rng);
  for (int i = 1; i < n; ++i) x(i) = rho * x(i - 1) + sigma * std::sqrt(1.0 - rho * rho) * normal(rng);
  return x;
}

}  // namespace

TEST_CASE("The scatter of replicas is recovered as its standard deviation and lag-1 correlation",
          "[diagnose][scatter]") {
  // 40 replicas x 2 targets of 300 points; the true scatter: 0.8 and 0.3 (y units), rho 0.9 and 0.
  // Tolerances: sigma within 5 %, rho within 0.03 (sampling error ~1 % and ~0.01 at 12,000 points).
  std::mt19937_64 rng(7);
  const std::vector<FitTarget> targets{target("surface", 300, 0.5), target("torque", 300, 2.0)};
  const Eigen::VectorXd common = ar1(600, 3.0, 0.5, rng);  // a shared offset the estimate must ignore
  std::vector<Eigen::VectorXd> replicas;
  for (int k = 0; k < 40; ++k) {
    Eigen::VectorXd r(600);
    r.head(300) = (common.head(300) + ar1(300, 0.8, 0.9, rng)) / 0.5;  // normalised by each sigma
    r.tail(300) = (common.tail(300) + ar1(300, 0.3, 0.0, rng)) / 2.0;
    replicas.push_back(r);
  }
  const auto s = estimate_scatter(replicas, targets);
  REQUIRE(s.size() == 2);
  CHECK(s[0].sigma == Approx(0.8).epsilon(0.05));
  CHECK(s[0].lag1 == Approx(0.9).margin(0.03));
  CHECK(s[1].sigma == Approx(0.3).epsilon(0.05));
  CHECK(s[1].lag1 == Approx(0.0).margin(0.03));
  CHECK(s[0].replicas == 40);
}

TEST_CASE("The noise factor reproduces white data noise plus AR(1) scatter as its covariance", "[diagnose][scatter]") {
  const TargetScatter scatter{"surface", 0.7, 0.8, 5};
  const Eigen::MatrixXd l = scatter_noise_factor(25, 0.4, scatter);
  const Eigen::MatrixXd covariance = l * l.transpose();
  for (int i = 0; i < 25; ++i)
    for (int j = 0; j < 25; ++j) {
      const double expected = 0.49 * std::pow(0.8, std::abs(i - j)) + (i == j ? 0.16 : 0.0);
      CHECK(covariance(i, j) == Approx(expected).margin(1e-12));
    }
  CHECK(l.triangularView<Eigen::StrictlyUpper>().toDenseMatrix().norm() == 0.0);
}

TEST_CASE("Residuals drawn from the scatter noise model come out white after whitening", "[diagnose][scatter]") {
  // 2,000 draws of 50 points from sigma_data 0.4 + AR(1) scatter 0.7 at rho 0.85: before whitening
  // the lag-1 correlation is 0.85 x 0.49 / 0.65 = 0.64; after it, unit variance within 3 % and lag-1
  // correlation within 0.02 of 0.
  const TargetScatter scatter{"surface", 0.7, 0.85, 5};
  const Eigen::MatrixXd l = scatter_noise_factor(50, 0.4, scatter);
  std::mt19937_64 rng(11);
  std::normal_distribution<double> normal(0.0, 1.0);
  double squares = 0.0, lagged = 0.0, raw_squares = 0.0, raw_lagged = 0.0;
  for (int draw = 0; draw < 2000; ++draw) {
    Eigen::VectorXd r = ar1(50, 0.7, 0.85, rng);
    for (int i = 0; i < 50; ++i) r(i) += 0.4 * normal(rng);
    const Eigen::VectorXd w = l.triangularView<Eigen::Lower>().solve(r);
    squares += w.squaredNorm();
    lagged += w.head(49).dot(w.tail(49));
    raw_squares += r.squaredNorm();
    raw_lagged += r.head(49).dot(r.tail(49));
  }
  CHECK(raw_lagged / raw_squares == Approx(0.85 * 0.49 / 0.65).margin(0.03));
  CHECK(squares / (2000.0 * 50.0) == Approx(1.0).epsilon(0.03));
  CHECK(lagged / squares == Approx(0.0).margin(0.02));
}

TEST_CASE("Renormalising an old residual gives the residual the whitened targets compute directly",
          "[diagnose][scatter]") {
  std::vector<FitTarget> old{target("surface", 12, 0.5), target("torque", 8, 2.0)};
  std::vector<FitTarget> whitened = old;
  whitened[0].noise_factor = scatter_noise_factor(12, 0.5, TargetScatter{"surface", 0.6, 0.7, 5});
  whitened[0].sigma = std::hypot(0.5, 0.6);
  whitened[1].sigma = 3.0;  // a white target whose level changed
  demfit::identify::CurveSet curves;
  for (auto* t : {&old[0], &old[1]}) {
    demfit::identify::Curve c{"x", "y", t->data.x, {}};
    for (double x : c.x) c.y.push_back(std::sin(x) + 0.1 * x);
    curves[t->curve] = c;
  }
  const Eigen::VectorXd before = normalised_residual(curves, old);
  const Eigen::VectorXd direct = normalised_residual(curves, whitened);
  const Eigen::VectorXd mapped = renormalisation(old, whitened) * before;
  REQUIRE(direct.size() == 20);
  CHECK((mapped - direct).norm() <= 1e-12 * direct.norm());
  CHECK(direct(15) == Approx((std::sin(3.0) + 0.3) / 3.0));  // torque point x = 3, white, sigma 3
}

TEST_CASE("When the data are themselves a model run the residual holds two realisations of the scatter and is "
          "whitened only when both are counted",
          "[diagnose][scatter]") {
  // Residual = (model run's scatter) - (data's own run's scatter) + white data noise: 2,000 draws of 50
  // points, scatter 0.7 at rho 0.85 in each run, data noise 0.4. Exact covariance of the residual:
  // 0.16 I + 2 x 0.49 R. Counting both realisations (data scatter ratio 1): unit variance within 3 % and
  // lag-1 within 0.02 of 0. Counting one (ratio 0): the whitened residual keeps the variance and lag-1
  // correlation of L1^-1 C L1^-T (C the true covariance, L1 the one-realisation factor), computed here
  // exactly: 1.446 and 0.113; the draws within 3 % and 0.02 of them.
  std::vector<FitTarget> targets{target("surface", 50, 0.4)};
  const std::vector<TargetScatter> scatter{{"surface", 0.7, 0.85, 5}};
  std::vector<bool> whitened;
  const auto one = with_scatter(targets, scatter, 0.25, 0.0, whitened);
  const auto two = with_scatter(targets, scatter, 0.25, 1.0, whitened);
  REQUIRE(whitened.front());
  CHECK(two.front().sigma == Approx(std::sqrt(0.16 + 2.0 * 0.49)).epsilon(1e-12));
  std::mt19937_64 rng(13);
  std::normal_distribution<double> normal(0.0, 1.0);
  double squares[2] = {0.0, 0.0}, lagged[2] = {0.0, 0.0};
  for (int draw = 0; draw < 2000; ++draw) {
    Eigen::VectorXd r = ar1(50, 0.7, 0.85, rng) - ar1(50, 0.7, 0.85, rng);
    for (int i = 0; i < 50; ++i) r(i) += 0.4 * normal(rng);
    for (int k = 0; k < 2; ++k) {
      const Eigen::MatrixXd& l = (k == 0 ? one : two).front().noise_factor;
      const Eigen::VectorXd w = l.triangularView<Eigen::Lower>().solve(r);
      squares[k] += w.squaredNorm();
      lagged[k] += w.head(49).dot(w.tail(49));
    }
  }
  CHECK(squares[1] / (2000.0 * 50.0) == Approx(1.0).epsilon(0.03));
  CHECK(lagged[1] / squares[1] == Approx(0.0).margin(0.02));
  Eigen::MatrixXd true_covariance = 0.16 * Eigen::MatrixXd::Identity(50, 50);
  for (int i = 0; i < 50; ++i)
    for (int j = 0; j < 50; ++j) true_covariance(i, j) += 2.0 * 0.49 * std::pow(0.85, std::abs(i - j));
  const Eigen::MatrixXd& l1 = one.front().noise_factor;
  const Eigen::MatrixXd half = l1.triangularView<Eigen::Lower>().solve(true_covariance);
  const Eigen::MatrixXd seen = l1.triangularView<Eigen::Lower>().solve(half.transpose());  // L1^-1 C L1^-T
  const double expected_variance = seen.trace() / 50.0;
  const double expected_lag1 = seen.diagonal(1).sum() / seen.trace();
  REQUIRE(expected_variance > 1.4);  // the one-realisation model is wrong here by construction
  CHECK(squares[0] / (2000.0 * 50.0) == Approx(expected_variance).epsilon(0.03));
  CHECK(lagged[0] / squares[0] == Approx(expected_lag1).margin(0.02));
}

TEST_CASE("A scatter below the threshold leaves the target white whatever the data's own scatter, and a negative "
          "ratio is refused",
          "[diagnose][scatter]") {
  std::vector<bool> whitened;
  const auto out = with_scatter({target("torque", 10, 2.0)}, {{"torque", 0.4, 0.5, 5}}, 0.25, 1.0, whitened);
  CHECK_FALSE(whitened.front());
  CHECK(out.front().sigma == 2.0);
  CHECK(out.front().noise_factor.size() == 0);
  CHECK_THROWS_AS(with_scatter({target("torque", 10, 2.0)}, {{"torque", 0.4, 0.5, 5}}, 0.25, -1.0, whitened),
                  std::invalid_argument);
}
