#include "demfit/rbf_surrogate/design.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

using namespace demfit::rbf_surrogate;

namespace {

// Every column has exactly one point in each of the n equal strata of the region.
bool stratified(const MatrixXd& x, const Box& region) {
  const auto n = x.rows();
  for (Eigen::Index c = 0; c < x.cols(); ++c) {
    std::vector<int> count(n, 0);
    for (Eigen::Index i = 0; i < n; ++i) {
      const double u = (x(i, c) - region.lower[c]) / (region.upper[c] - region.lower[c]);
      const auto s = static_cast<Eigen::Index>(std::floor(u * n));
      if (s < 0 || s >= n) return false;
      ++count[s];
    }
    for (int k : count)
      if (k != 1) return false;
  }
  return true;
}

}  // namespace

TEST_CASE("Maximin Latin hypercube is stratified in every 1-D projection", "[rbf_surrogate][design]") {
  Box region{VectorXd::Zero(4), VectorXd::Ones(4)};
  region.lower << 0.1, 0.0, 0.3, 0.5;
  region.upper << 0.2, 1.0, 0.9, 0.51;
  for (int n : {1, 2, 7, 30}) {
    const MatrixXd x = latin_hypercube_maximin(n, 4, 42, region);
    REQUIRE(x.rows() == n);
    CHECK(stratified(x, region));
  }
}

TEST_CASE("Maximin Latin hypercube has a larger minimum distance than plain LHS on average",
          "[rbf_surrogate][design]") {
  // Independent comparison: mean nearest pair distance over 20 seeds, plain vs optimised.
  const Box unit = Box::unit(3);
  double plain = 0.0, maximin = 0.0;
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    plain += minimum_distance(latin_hypercube_random(25, 3, seed, unit));
    maximin += minimum_distance(latin_hypercube_maximin(25, 3, seed, unit));
  }
  INFO("plain " << plain / 20 << " maximin " << maximin / 20);
  CHECK(maximin > 1.3 * plain);
}

TEST_CASE("Designs are deterministic for a seed and differ between seeds", "[rbf_surrogate][design]") {
  const Box unit = Box::unit(5);
  CHECK(latin_hypercube_maximin(12, 5, 7, unit) == latin_hypercube_maximin(12, 5, 7, unit));
  CHECK(latin_hypercube_maximin(12, 5, 7, unit) != latin_hypercube_maximin(12, 5, 8, unit));
  const MatrixXd existing = latin_hypercube_maximin(10, 5, 1, unit);
  CHECK(space_filling_augment(existing, 4, unit, 3) == space_filling_augment(existing, 4, unit, 3));
}

TEST_CASE("Space-filling augmentation stays in the region and keeps away from existing points",
          "[rbf_surrogate][design]") {
  // Compare with the same number of uniform random points in the region (independent baseline):
  // the nearest distance to the existing + new set must be larger on average.
  Box region{VectorXd::Constant(2, 0.25), VectorXd::Constant(2, 0.75)};
  double augmented = 0.0, random = 0.0;
  std::mt19937_64 rng(5);
  for (std::uint64_t seed = 1; seed <= 10; ++seed) {
    const MatrixXd existing = latin_hypercube_random(15, 2, seed, Box::unit(2));
    const MatrixXd added = space_filling_augment(existing, 5, region, seed);
    REQUIRE(added.rows() == 5);
    for (Eigen::Index i = 0; i < added.rows(); ++i) CHECK(region.contains(added.row(i).transpose(), 1e-12));
    MatrixXd all(20, 2), all_random(20, 2);
    all << existing, added;
    all_random.topRows(15) = existing;
    for (int i = 15; i < 20; ++i)
      for (int c = 0; c < 2; ++c) all_random(i, c) = 0.25 + 0.5 * uniform01(rng);
    augmented += minimum_distance(all);
    random += minimum_distance(all_random);
  }
  INFO("augmented " << augmented / 10 << " random " << random / 10);
  CHECK(augmented > 2.0 * random);
}

TEST_CASE("Uniform mapping of the seeded generator covers the unit interval evenly", "[rbf_surrogate][design]") {
  // Chi-square style check on 10 bins with 100000 draws: each bin within 3 % of 10000.
  std::mt19937_64 rng(123);
  std::vector<int> bins(10, 0);
  for (int i = 0; i < 100000; ++i) {
    const double u = uniform01(rng);
    REQUIRE(u >= 0.0);
    REQUIRE(u < 1.0);
    ++bins[static_cast<int>(u * 10)];
  }
  for (int b : bins) CHECK(std::abs(b - 10000) < 300);
  for (int i = 0; i < 1000; ++i) CHECK(uniform_index(rng, 7) < 7);
}
