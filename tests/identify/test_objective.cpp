#include <catch2/catch.hpp>

#include <cmath>

#include "demfit/identify/objective.hpp"

using namespace demfit::identify;

namespace {
TargetSpec target(const Curve& data, CurveMetric metric = CurveMetric::mse, double weight = 1.0) {
  return TargetSpec{
      .name = std::string("t"), .curve = std::string("c"), .data = data, .csv = {}, .metric = metric, .weight = weight};
}
}  // namespace

TEST_CASE("Resampling a piecewise-linear curve is exact and holds end values flat outside", "[identify][metric]") {
  const Curve line{"x", "y", {3.0, 2.0, 0.0}, {7.0, 5.0, 1.0}};  // y = 2x + 1, decreasing x order
  const auto y = resample_monotone(line, {0.5, 1.25, 2.75, -1.0, 4.0});
  CHECK(y[0] == Approx(2.0).epsilon(1e-14));
  CHECK(y[1] == Approx(3.5).epsilon(1e-14));
  CHECK(y[2] == Approx(6.5).epsilon(1e-14));
  CHECK(y[3] == 1.0);
  CHECK(y[4] == 7.0);
  CHECK_THROWS_WITH(resample_monotone(Curve{"x", "y", {0, 2, 1}, {0, 1, 2}}, {0.5}), Catch::Contains("not monotone"));
}

TEST_CASE("The MSE composite equals (1/P) sum ((f-G)/max|G|)^2 times the weight", "[identify][metric]") {
  const Curve measured{"x", "y", {0, 1, 2, 3}, {1.0, -4.0, 2.0, 3.0}};
  const CompositeObjective objective({target(measured, CurveMetric::mse, 2.5)});
  const Curve simulated{"x", "y", {0, 3}, {0.0, 3.0}};  // y = x
  const Eigen::VectorXd responses = objective.responses({{"c", simulated}});
  double expected = 0.0;
  for (int p = 0; p < 4; ++p) expected += std::pow((p - measured.y[p]) / 4.0, 2);
  expected *= 2.5 / 4.0;
  CHECK(objective.objective(responses) == Approx(expected).epsilon(1e-13));
  CHECK(objective.target_objectives(responses)[0] == Approx(expected).epsilon(1e-13));
  CHECK_THROWS_WITH(objective.responses({{"other", simulated}}), Catch::Contains("no curve 'c'"));
}

TEST_CASE("Curve mapping is zero on the target itself and on a longer curve containing it", "[identify][metric]") {
  // A hysteresis loop (non-monotone in x): up along y = x^2, back along y = x.
  Curve loop{"x", "y", {}, {}};
  for (int i = 0; i <= 20; ++i) {
    loop.x.push_back(i / 20.0);
    loop.y.push_back(std::pow(i / 20.0, 2));
  }
  for (int i = 19; i >= 0; --i) {
    loop.x.push_back(i / 20.0);
    loop.y.push_back(i / 20.0);
  }
  const CompositeObjective objective({target(loop, CurveMetric::curve_mapping)});
  CHECK(objective.objective(objective.responses({{"c", loop}})) < 1e-6);
  // The computed curve starts with an extra lead-in segment; mapping must find the offset.
  Curve longer{"x", "y", {-0.5, -0.25}, {0.0, 0.0}};
  longer.x.insert(longer.x.end(), loop.x.begin(), loop.x.end());
  longer.y.insert(longer.y.end(), loop.y.begin(), loop.y.end());
  CHECK(objective.objective(objective.responses({{"c", longer}})) < 1e-3);
  // A loop shifted up by 0.1 (0.1 of the y scale max|G| = 1): at zero offset every station is
  // 0.1 away, so the best-aligned distance is at most 0.1^2; sliding along the diagonal
  // return branch can reduce it there (to 0.1^2/2 at best), never on the steep branch.
  Curve shifted = loop;
  for (double& y : shifted.y) y += 0.1;
  const double value = objective.objective(objective.responses({{"c", shifted}}));
  CHECK(value <= 0.01 * 1.02);
  CHECK(value >= 0.005);
}

TEST_CASE("Targets combine by weight", "[identify][metric]") {
  const Curve a{"x", "y", {0, 1}, {1.0, 1.0}};
  auto ta = target(a, CurveMetric::mse, 1.0);
  auto tb = target(a, CurveMetric::mse, 3.0);
  tb.name = std::string(1, 'b');
  const CompositeObjective single({ta});
  const CompositeObjective both({ta, tb});
  const CurveSet sim{{"c", Curve{"x", "y", {0, 1}, {0.5, 1.5}}}};
  CHECK(both.objective(both.responses(sim)) == Approx(4.0 * single.objective(single.responses(sim))).epsilon(1e-14));
}
