// Round-off replicates (roundoff_replicates.hpp): how a replicate moves a point, and the spread
// and ratio statistics `reproduce table3` reports from them.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>

#include "demfit/identify/roundoff_replicates.hpp"

using namespace demfit::identify;

TEST_CASE("A replicate moves every unit coordinate by whole nudges and stays inside the unit box", "[replicates]") {
  Eigen::VectorXd unit(3);
  unit << 0.25, 1.0, 0.0;
  const Eigen::VectorXd first = replicate_point(unit, 0), third = replicate_point(unit, 2);
  CHECK(first(0) == Approx(0.25 + 1e-7).epsilon(1e-12));
  CHECK(first(1) == Approx(1.0 - 1e-7).epsilon(1e-12));  // the upper edge moves inwards
  CHECK(first(2) == Approx(1e-7).epsilon(1e-9));
  CHECK(third(0) == Approx(0.25 + 3e-7).epsilon(1e-12));
  CHECK(third(1) == Approx(1.0 - 3e-7).epsilon(1e-12));
}

TEST_CASE("Replicate parameters move the study variables by a nudge of their range and leave the rest alone",
          "[replicates]") {
  StudySpec spec;
  spec.variables = {{"friction", 0.1, 0.9, 0.5}, {"stiffness", 0.001, 1.0, 0.01, true}};
  const ParameterSet values{{"friction", 0.5}, {"stiffness", 0.01}, {"held", 3.0}};
  const ParameterSet moved = replicate_parameters(spec, values, 1);  // two nudges
  // Independent computation: linear unit u = (v - lo) / (hi - lo); log unit u = ln(v / lo) / ln(hi / lo).
  CHECK(moved.at("friction") == Approx(0.5 + 2e-7 * 0.8).epsilon(1e-12));
  CHECK(moved.at("stiffness") == Approx(0.01 * std::pow(1000.0, 2e-7)).epsilon(1e-12));
  CHECK(moved.at("stiffness") != values.at("stiffness"));
  CHECK(moved.at("held") == 3.0);
}

TEST_CASE("The replicate spread is the sample mean standard deviation and range", "[replicates]") {
  const ReplicateSpread s = replicate_spread({4.0, 1.0, 3.0, 2.0});
  CHECK(s.count == 4);
  CHECK(s.mean == Approx(2.5));
  CHECK(s.standard_deviation == Approx(std::sqrt(5.0 / 3.0)));
  CHECK(s.lowest == 1.0);
  CHECK(s.highest == 4.0);
  CHECK(replicate_spread({7.0}).standard_deviation == 0.0);
  CHECK_THROWS_AS(replicate_spread({}), std::invalid_argument);
  CHECK_THROWS_AS(replicate_spread({1.0, std::numeric_limits<double>::quiet_NaN()}), std::invalid_argument);
}

TEST_CASE("The ratio of replicated means carries both spreads by first-order propagation", "[replicates]") {
  const ReplicateSpread after{5.0, 1.0, 3.0, 7.0, 8}, before{10.0, 2.0, 7.0, 13.0, 4};
  const RatioOfMeans r = ratio_of_means(after, before);
  // se = 0.5 sqrt(1 / (8 * 25) + 4 / (4 * 100)) = 0.5 sqrt(0.015)
  const double se = 0.5 * std::sqrt(0.015);
  CHECK(r.ratio == Approx(0.5));
  CHECK(r.lower == Approx(0.5 - 2.0 * se));
  CHECK(r.upper == Approx(0.5 + 2.0 * se));
  CHECK_THROWS_AS(ratio_of_means(after, ReplicateSpread{}), std::invalid_argument);
}

TEST_CASE("The ratio range covers the true ratio of means in about 95 percent of sampled replicate sets",
          "[replicates]") {
  // Errors like Table 3's (means 5 and 9 mm, spread ~1 mm, 8 replicates each), 2,000 seeded sets:
  // the ±2 standard-error range should contain 5 / 9 in 90-99 % of them.
  std::mt19937_64 random(20261205);
  std::normal_distribution<double> after_error(5.0, 1.0), before_error(9.0, 1.1);
  int covered = 0;
  const int sets = 2000;
  for (int k = 0; k < sets; ++k) {
    std::vector<double> a(8), b(8);
    for (double& v : a) v = after_error(random);
    for (double& v : b) v = before_error(random);
    const RatioOfMeans r = ratio_of_means(replicate_spread(a), replicate_spread(b));
    covered += r.lower <= 5.0 / 9.0 && 5.0 / 9.0 <= r.upper;
  }
  const double coverage = static_cast<double>(covered) / sets;
  INFO("coverage " << coverage);
  CHECK(coverage >= 0.90);
  CHECK(coverage <= 0.99);
}
