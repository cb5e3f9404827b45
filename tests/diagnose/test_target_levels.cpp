// The level part of a fit's misfit per target (target_levels.hpp) against hand-computed means,
// for white targets and for one whitened by a known noise factor.
#include <catch2/catch.hpp>

#include <cmath>

#include "demfit/diagnose/target_levels.hpp"

using namespace demfit::diagnose;

namespace {

FitTarget flat_target(const std::string& name, int points, double sigma) {
  FitTarget t;
  t.name = name;
  t.sigma = sigma;
  for (int i = 0; i < points; ++i) {
    t.data.x.push_back(i);
    t.data.y.push_back(0.0);
  }
  return t;
}

}  // namespace

TEST_CASE("Target levels are the means of the residuals in each target's units and their share of its squares") {
  // Target a: raw residual 1 + (-0.5, 0.5, -0.5, 0.5) -> mean 1, mean square 1.25, share 0.8.
  // Target b, whitened by L: raw residual -2 everywhere -> mean -2, share 1.
  std::vector<FitTarget> targets{flat_target("a", 4, 0.5), flat_target("b", 3, 0.25)};
  Eigen::MatrixXd factor(3, 3);
  factor << 0.25, 0, 0, 0.1, 0.2, 0, 0.05, 0.1, 0.3;
  targets[1].noise_factor = factor;
  const Eigen::Vector4d raw_a(0.5, 1.5, 0.5, 1.5);
  const Eigen::VectorXd raw_b = Eigen::VectorXd::Constant(3, -2.0);
  Eigen::VectorXd residual(7);
  residual << raw_a / 0.5, factor.triangularView<Eigen::Lower>().solve(raw_b);
  const std::vector<TargetLevel> levels = target_levels(targets, residual);
  REQUIRE(levels.size() == 2);
  CHECK(levels[0].target == "a");
  CHECK(levels[0].mean == Approx(1.0).epsilon(1e-12));
  CHECK(levels[0].mean_over_sigma == Approx(2.0).epsilon(1e-12));
  CHECK(levels[0].level_share == Approx(0.8).epsilon(1e-12));
  CHECK(levels[1].mean == Approx(-2.0).epsilon(1e-12));
  CHECK(levels[1].mean_over_sigma == Approx(-8.0).epsilon(1e-12));
  CHECK(levels[1].level_share == Approx(1.0).epsilon(1e-12));
  const std::string text = opposite_levels_text(levels);
  CHECK(text.find("above its data in 'a'") != std::string::npos);
  CHECK(text.find("below it in 'b'") != std::string::npos);
  CHECK_THROWS_AS(target_levels(targets, Eigen::VectorXd::Zero(6)), std::invalid_argument);
  CHECK_THROWS_AS(target_levels(targets, Eigen::VectorXd::Zero(8)), std::invalid_argument);
}

TEST_CASE("Opposite levels are reported only when the level is at least half of each target's squared residual") {
  TargetLevel up{"up", 1.0, 2.0, 0.9}, down{"down", -1.0, -2.0, 0.9}, shape{"shape", -1.0, -2.0, 0.3};
  CHECK_FALSE(opposite_levels_text({up, down}).empty());
  CHECK(opposite_levels_text({up, shape}).empty());  // the negative one is mostly shape
  CHECK(opposite_levels_text({up, up}).empty());     // same sign: one shared shift could remove both
  CHECK(opposite_levels_text({up}).empty());
}
