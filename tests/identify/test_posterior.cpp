// Posterior intervals on the local surrogate: coverage on an analytic model
// with a well-determined, a weak and a correlated parameter under DEM-like noise.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>

#include "demfit/identify/interval_check.hpp"
#include "demfit/identify/uncertainty.hpp"
#include "test_helpers.hpp"

using namespace demfit::identify;

namespace {

// y(x) = p1 sin(πx) + p3 (x + x²/2) + 0.03 p2 x on 50 stations of [0, 1]:
//  p1 "well"  — its own shape, well determined;
//  p2 "weak"  — moves the curve by at most 1 % of max|y|, along x: the same shape as the smooth
//               run-to-run noise, so the data cannot pin it;
//  p3 "corr"  — correlated with p2 (both contain x), identifiable only jointly with what p2 does.
const std::vector<VariableSpec> kVariables{{"well", 0.5, 2.0, 1.0}, {"weak", 0.0, 1.0, 0.5}, {"corr", 0.5, 2.0, 1.0}};
constexpr int kStations = 50;

Eigen::VectorXd curve(const Eigen::Vector3d& p) {
  Eigen::VectorXd y(kStations);
  for (int i = 0; i < kStations; ++i) {
    const double x = i / (kStations - 1.0);
    y(i) = p(0) * std::sin(3.141592653589793 * x) + p(2) * (x + 0.5 * x * x) + 0.03 * p(1) * x;
  }
  return y;
}

// DEM-like noise: every run (and the experiment) is one smooth random realisation, like another
// packing history: σ = 0.5 % of max|y| (≈ 2.9) on each of three smooth shapes.
Eigen::VectorXd trajectory_noise(std::mt19937_64& rng) {
  std::normal_distribution<double> normal(0.0, 0.005 * 2.9);
  const double g1 = normal(rng), g2 = normal(rng), g3 = normal(rng);
  Eigen::VectorXd e(kStations);
  for (int i = 0; i < kStations; ++i) {
    const double x = i / (kStations - 1.0);
    e(i) = g1 * x + g2 * std::sin(6.283185307179586 * x) + g3 * (2 * x * x - 1);
  }
  return e;
}

Eigen::Vector3d to_physical(const Eigen::Vector3d& u) {
  Eigen::Vector3d p;
  for (int j = 0; j < 3; ++j) p(j) = kVariables[j].lower + u(j) * (kVariables[j].upper - kVariables[j].lower);
  return p;
}

// One synthetic identification: a measured curve (truth + trajectory noise + 0.5 % white noise)
// and 15 runs on a Latin-hypercube-like sample of a box of half-width 0.15 (unit) around a centre
// that misses the truth by up to 0.05 per coordinate (as a loop's last iterations would).
RunSample synthetic_sample(std::uint64_t seed, Eigen::Vector3d& truth_unit, Eigen::VectorXd* measured_out = nullptr) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  truth_unit << 0.2 + 0.6 * uniform(rng), 0.2 + 0.6 * uniform(rng), 0.2 + 0.6 * uniform(rng);
  std::normal_distribution<double> white(0.0, 0.005 * 2.9);
  Eigen::VectorXd measured = curve(to_physical(truth_unit)) + trajectory_noise(rng);
  for (int i = 0; i < kStations; ++i) measured(i) += white(rng);
  if (measured_out) *measured_out = measured;
  const int m = 15;
  RunSample s;
  s.unit_points.resize(m, 3);
  s.residuals.resize(m, kStations);
  Eigen::Vector3d centre;
  for (int j = 0; j < 3; ++j) centre(j) = truth_unit(j) + 0.1 * (uniform(rng) - 0.5);
  int best = 0;
  for (int i = 0; i < m; ++i) {
    for (int j = 0; j < 3; ++j)  // stratified per coordinate, strata shuffled by the draw
      s.unit_points(i, j) = std::clamp(centre(j) - 0.15 + 0.3 * (((i * (2 * j + 7)) % m) + uniform(rng)) / m, 0.0, 1.0);
    s.residuals.row(i) =
        (curve(to_physical(s.unit_points.row(i).transpose())) + trajectory_noise(rng) - measured).transpose();
    if (s.residuals.row(i).squaredNorm() < s.residuals.row(best).squaredNorm()) best = i;
  }
  s.best_unit = s.unit_points.row(best).transpose();
  s.best_residuals = s.residuals.row(best).transpose();
  s.unit_per_physical = Eigen::Vector3d(1.0 / 1.5, 1.0, 1.0 / 1.5);
  return s;
}

}  // namespace

// Measured (60 seeds): coverage well 0.933, correlated 0.917, weak 0.933; the former linearised
// interval (estimate_uncertainty_from_runs) of the correlated one: 0.917. Before the data-noise
// estimate accounted for the noise the fit absorbs (σ_w² from tr(MΣ_sim)): well 0.77, correlated 0.85.
TEST_CASE("95 % posterior intervals of the identifiable parameters contain the truth in 90-98 % of 60 noise seeds",
          "[identify][uncertainty][posterior]") {
  const int seeds = 60;
  int inside_well = 0, inside_corr = 0, inside_weak = 0, weak_flagged = 0, conditional_inside_corr = 0;
  for (int seed = 1; seed <= seeds; ++seed) {
    Eigen::Vector3d truth_unit;
    const RunSample sample = synthetic_sample(static_cast<std::uint64_t>(seed), truth_unit);
    const Eigen::Vector3d truth = to_physical(truth_unit);
    PosteriorOptions options;
    options.seed = static_cast<std::uint64_t>(seed);
    const PosteriorEstimate e = sample_posterior_from_runs(sample, kVariables, options);
    const auto inside = [&](int j) { return e.lower[j] <= truth(j) && truth(j) <= e.upper[j]; };
    inside_well += inside(0);
    inside_weak += inside(1);
    inside_corr += inside(2);
    weak_flagged += e.unidentifiable[1];
    // The former linearised estimate, for comparison (conditional on the weak parameter).
    const UncertaintyEstimate c = estimate_uncertainty_from_runs(sample, kVariables);
    if (!c.least_squares_estimate.empty() && std::isfinite(c.ci_half_width[2]))
      conditional_inside_corr += std::abs(c.least_squares_estimate[2] - truth(2)) <= c.ci_half_width[2];
  }
  const double well = double(inside_well) / seeds, corr = double(inside_corr) / seeds;
  INFO("coverage: well " << well << ", correlated " << corr << ", weak " << double(inside_weak) / seeds
                         << " (flagged unidentifiable in " << weak_flagged << " of " << seeds
                         << "); linearised conditional interval of the correlated one: "
                         << double(conditional_inside_corr) / seeds);
  CHECK(well >= 0.90);
  CHECK(well <= 0.98);
  CHECK(corr >= 0.90);
  CHECK(corr <= 0.98);
  // The weak one's interval is honest too, and mostly spans more than half its bounds (measured:
  // coverage 0.93, flagged in 47 of 60 seeds; its effect, 1 % of max|y|, is sometimes resolved).
  const double weak = double(inside_weak) / seeds;
  CHECK(weak >= 0.90);
  CHECK(weak <= 0.98);
  CHECK(weak_flagged >= seeds * 2 / 3);
  WARN("coverage: well " << well << ", correlated " << corr << ", weak " << double(inside_weak) / seeds
                         << ", weak flagged " << weak_flagged << "/" << seeds
                         << ", former conditional interval of the correlated one "
                         << double(conditional_inside_corr) / seeds);
}

// The interval-end checks (interval_check.hpp) on the same 60 seeds: every check run is a fresh
// noisy run (trajectory noise redrawn), the retry's profile is the exact least-squares optimum of
// the other two parameters (the curve is linear in them), the spread from two replicates.
TEST_CASE(
    "Interval-end checks keep the identifiable parameters' coverage at least 90 % in 60 noise seeds, 5x wider at most",
    "[identify][uncertainty][posterior][interval_check]") {
  const int seeds = 60;
  int inside[3] = {0, 0, 0}, widened[3] = {0, 0, 0};
  double width_ratio[3] = {0, 0, 0};
  int runs = 0;
  for (int seed = 1; seed <= seeds; ++seed) {
    Eigen::Vector3d truth_unit;
    Eigen::VectorXd measured;
    const RunSample sample = synthetic_sample(static_cast<std::uint64_t>(seed), truth_unit, &measured);
    PosteriorOptions options;
    options.seed = static_cast<std::uint64_t>(seed);
    const PosteriorEstimate e = sample_posterior_from_runs(sample, kVariables, options);
    std::mt19937_64 rng(1000 + seed);
    const auto objective = [&](const Eigen::Vector3d& u) {
      return (curve(to_physical(u)) + trajectory_noise(rng) - measured).squaredNorm() / kStations;
    };
    const ProfilePoint profile = [&](int variable, double unit) {
      Eigen::Vector3d u = sample.best_unit;
      u(variable) = unit;
      // y is linear in the unit coordinates: least squares over the other two, clamped to the box.
      const Eigen::VectorXd base = curve(to_physical(u));
      Eigen::MatrixXd columns(kStations, 2);
      std::vector<int> others;
      for (int j = 0; j < 3; ++j)
        if (j != variable) others.push_back(j);
      for (int k = 0; k < 2; ++k) {
        Eigen::Vector3d shifted = u;
        shifted(others[k]) += 1.0;
        columns.col(k) = curve(to_physical(shifted)) - base;
      }
      const Eigen::Vector2d step = columns.colPivHouseholderQr().solve(measured - base);
      for (int k = 0; k < 2; ++k) u(others[k]) = std::clamp(u(others[k]) + step(k), 0.0, 1.0);
      return Eigen::VectorXd(u);
    };
    const EvaluateBatch evaluate = [&](int, const Eigen::MatrixXd& points, const std::vector<std::string>&) {
      Eigen::VectorXd out(points.rows());
      for (int i = 0; i < points.rows(); ++i) out(i) = objective(points.row(i).transpose());
      runs += static_cast<int>(points.rows());
      return out;
    };
    IntervalCheckSpec settings;
    settings.max_steps = 6;
    IntervalCheckInput input;
    input.best_unit = sample.best_unit;
    input.best_objective = sample.best_residuals.squaredNorm() / kStations;
    input.lower = e.lower;
    input.upper = e.upper;
    input.fitted_runs = sample.unit_points;
    const auto checked = check_interval_ends(kVariables, input, settings, profile, evaluate);
    const Eigen::Vector3d truth = to_physical(truth_unit);
    for (int j = 0; j < 3; ++j) {
      inside[j] += checked.lower[j].end <= truth(j) && truth(j) <= checked.upper[j].end;
      widened[j] += checked.lower[j].widened || checked.upper[j].widened;
      width_ratio[j] += (checked.upper[j].end - checked.lower[j].end) / (e.upper[j] - e.lower[j]) / seeds;
    }
  }
  const double well = double(inside[0]) / seeds, weak = double(inside[1]) / seeds, corr = double(inside[2]) / seeds;
  // Measured: coverage 0.983, 1, 1; widened in 60, 60, 59 seeds; mean width ratio 4.6, 1.6, 4.5.
  // No 98 % cap on coverage here: a checked interval contains its answer with room on both sides
  // (interval_check.hpp), and the best run lies outside the posterior's interval in 53 (well) and
  // 47 (correlated) of the 60 seeds; the checked ends merely stretched to the answer, as reported
  // before that rule, already covered 59 and 60 of 60 (checked ends alone 58, 58; width 4.2x, 4.1x).
  // The cost of the room is width, bounded instead.
  WARN("after interval checks: coverage well "
       << well << ", weak " << weak << ", correlated " << corr << "; widened in " << widened[0] << ", " << widened[1]
       << ", " << widened[2] << " of " << seeds << " seeds; mean width ratio " << width_ratio[0] << ", "
       << width_ratio[1] << ", " << width_ratio[2] << "; " << runs << " runs");
  CHECK(well >= 0.90);
  CHECK(corr >= 0.90);
  CHECK(width_ratio[0] <= 5.0);
  CHECK(width_ratio[2] <= 5.0);
}

TEST_CASE("Posterior draws of two parameters that move the curve alike are strongly correlated",
          "[identify][uncertainty][posterior]") {
  Eigen::Vector3d truth_unit;
  const RunSample sample = synthetic_sample(3, truth_unit);
  const PosteriorEstimate e = sample_posterior_from_runs(sample, kVariables);
  // weak (x) and corr (x + x²/2): raising one is compensated by lowering the other.
  CHECK(e.correlation(1, 2) < -0.5);
  CHECK(std::abs(e.correlation(0, 0) - 1.0) < 1e-12);
  for (int j = 0; j < 3; ++j) {
    CHECK(e.lower[j] <= e.median[j]);
    CHECK(e.median[j] <= e.upper[j]);
  }
}

TEST_CASE("The posterior pair plot is a PNG when gnuplot is available", "[identify][uncertainty][posterior]") {
  Eigen::Vector3d truth_unit;
  const PosteriorEstimate e = sample_posterior_from_runs(synthetic_sample(5, truth_unit), kVariables);
  const auto png = test::fresh_dir("posterior_plot") / "posterior_pairs.png";
  const std::string warning = write_posterior_pair_plot(e, kVariables, png);
  if (!warning.empty()) {
    WARN(warning);
    CHECK_FALSE(std::filesystem::exists(png));
  } else {
    CHECK(std::filesystem::file_size(png) > 1000);
  }
}

TEST_CASE("Too few runs for the posterior are refused with a message", "[identify][uncertainty][posterior]") {
  Eigen::Vector3d truth_unit;
  RunSample s = synthetic_sample(1, truth_unit);
  s.unit_points.conservativeResize(5, 3);
  s.residuals.conservativeResize(5, Eigen::NoChange);
  CHECK_THROWS_WITH(sample_posterior_from_runs(s, kVariables), Catch::Contains("n + 3 runs"));
}
