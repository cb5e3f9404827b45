// Expected improvement: closed form against numerical integration, the log form in the far tail,
// and the maximiser against a dense grid.
#include "demfit/rbf_surrogate/design.hpp"
#include "demfit/rbf_surrogate/expected_improvement.hpp"

#include <catch2/catch.hpp>

#include <cmath>

using namespace demfit::rbf_surrogate;

namespace {

// EI/s = ∫_{-∞}^{z} (z − t) φ(t) dt by composite Simpson on [z − span, z] in long double; the
// integrand's scale is 1 near t ≈ 0 and 1/|z| in the far tail.
long double ei_over_sd_by_quadrature(double z) {
  const long double span = z > -1.0 ? 12.0L + z : 40.0L / std::fabs(z);
  const long double a = z - span, b = z;
  const int n = 200000;
  const long double h = (b - a) / n;
  auto f = [z](long double t) { return (z - t) * std::exp(-0.5L * t * t) / std::sqrt(2.0L * 3.14159265358979323846L); };
  long double sum = f(a) + f(b);
  for (int i = 1; i < n; ++i) sum += (i % 2 ? 4.0L : 2.0L) * f(a + i * h);
  return sum * h / 3.0L;
}

}  // namespace

TEST_CASE("Expected improvement equals the integral of the improvement over the normal density",
          "[rbf_surrogate][ei]") {
  for (const double z : {-3.0, -1.0, 0.0, 0.5, 2.0}) {
    const double sd = 0.7, best = 1.3, mean = best - z * sd;
    const double expected = sd * static_cast<double>(ei_over_sd_by_quadrature(z));
    CHECK(expected_improvement(mean, sd, best) == Approx(expected).epsilon(1e-9));
    CHECK(log_expected_improvement(mean, sd, best) == Approx(std::log(expected)).epsilon(1e-9));
  }
  // Without uncertainty EI is the plain improvement.
  CHECK(expected_improvement(1.0, 0.0, 1.5) == Approx(0.5));
  CHECK(expected_improvement(2.0, 0.0, 1.5) == 0.0);
}

TEST_CASE("Log expected improvement stays accurate in the far tail where EI underflows its formula",
          "[rbf_surrogate][ei]") {
  for (const double z : {-6.5, -15.0, -19.9, -20.1, -30.0}) {
    const long double reference = ei_over_sd_by_quadrature(z);
    INFO("z = " << z);
    CHECK(log_expected_improvement(-z, 1.0, 0.0) == Approx(std::log(static_cast<double>(reference))).epsilon(1e-9));
  }
  // Deeper still: finite and decreasing (candidates keep a ranking instead of all tying at 0).
  CHECK(std::isfinite(log_expected_improvement(40.0, 1.0, 0.0)));
  CHECK(log_expected_improvement(40.0, 1.0, 0.0) < log_expected_improvement(30.0, 1.0, 0.0));
}

TEST_CASE("EI maximiser finds the peak of the EI surface found by a dense grid", "[rbf_surrogate][ei]") {
  const MatrixXd x = latin_hypercube_maximin(6, 1, 2, Box::unit(1));
  VectorXd y(6);
  for (int i = 0; i < 6; ++i) y[i] = std::sin(10.0 * x(i, 0)) + x(i, 0);
  const KrigingModel m = KrigingModel::fit(x, y);
  Eigen::Index best_i = 0;
  const double best = y.minCoeff(&best_i);
  double grid_max = -1e300;
  for (int k = 0; k <= 20000; ++k) {
    VectorXd p(1);
    p << k / 20000.0;
    double mean = 0.0, sd = 0.0;
    m.predict(p, mean, sd);
    grid_max = std::max(grid_max, log_expected_improvement(mean, sd, best));
  }
  const AcquisitionResult r = maximise_expected_improvement(m, best, x.row(best_i).transpose(), Box::unit(1), 3);
  CHECK(r.log_ei >= grid_max - 1e-6);
  CHECK(Box::unit(1).contains(r.x));
}

TEST_CASE("EI maximiser never proposes a point inside an excluded ball", "[rbf_surrogate][ei]") {
  const MatrixXd x = latin_hypercube_maximin(10, 2, 4, Box::unit(2));
  VectorXd y(10);
  for (int i = 0; i < 10; ++i) y[i] = (x.row(i).array() - 0.3).square().sum();
  const KrigingModel m = KrigingModel::fit(x, y);
  Eigen::Index best_i = 0;
  const double best = y.minCoeff(&best_i);
  AcquisitionOptions o;
  VectorXd centre(2);
  centre << 0.3, 0.3;
  o.excluded_centres = {centre};
  o.excluded_radius = 0.25;
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    const AcquisitionResult r =
        maximise_expected_improvement(m, best, x.row(best_i).transpose(), Box::unit(2), seed, o);
    CHECK((r.x - centre).norm() >= 0.25);
  }
}
