// Overlap statistics: what the drum summary reports so a user can judge a soft-spring answer.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdint>
#include <vector>

#include "demfit/dem_core/overlap_statistics.hpp"
#include "demfit/dem_core/simulation.hpp"

using namespace demfit::dem_core;

TEST_CASE("A pair's overlap is reported relative to the smaller radius", "[dem_core][overlap]") {
  Simulation sim;
  sim.add_material(Material{});
  sim.add_particle({0, 0, 0}, 1e-3);
  sim.add_particle({2.9e-3, 0, 0}, 2e-3);  // overlap 3.0 - 2.9 = 0.1 mm
  sim.add_particle({0, 0.05, 0}, 1e-3);    // alone
  const OverlapStatistics stats = pair_overlap_statistics(sim);
  CHECK(stats.contacts == 1);
  CHECK(stats.mean_relative_overlap == Approx(0.1).epsilon(1e-9));
  CHECK(stats.max_relative_overlap == Approx(0.1).epsilon(1e-9));
}

TEST_CASE("Spheres that only touch or stand apart count no overlap", "[dem_core][overlap]") {
  Simulation sim;
  sim.add_material(Material{});
  sim.add_particle({0, 0, 0}, 1e-3);
  sim.add_particle({2.0e-3, 0, 0}, 1e-3);  // touching, overlap 0
  sim.add_particle({0, 3e-3, 0}, 1e-3);
  const OverlapStatistics stats = pair_overlap_statistics(sim);
  CHECK(stats.contacts == 0);
  CHECK(stats.mean_relative_overlap == 0.0);
  CHECK(stats.max_relative_overlap == 0.0);
}

TEST_CASE("Overlap statistics of a crowded cloud agree with a count over every pair", "[dem_core][overlap]") {
  Simulation sim;
  sim.add_material(Material{});
  std::uint64_t state = 12345;  // a fixed linear congruential sequence: the same cloud everywhere
  auto uniform = [&state] {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    return static_cast<double>(state >> 11) / 9007199254740992.0;
  };
  std::vector<Vec3> centres;
  std::vector<double> radii;
  for (int k = 0; k < 300; ++k) {
    centres.push_back({0.02 * uniform(), 0.02 * uniform(), 0.02 * uniform()});
    radii.push_back(0.5e-3 + 0.7e-3 * uniform());
    sim.add_particle(centres.back(), radii.back());
  }
  std::size_t contacts = 0;
  double sum = 0.0, largest = 0.0;
  for (std::size_t i = 0; i < centres.size(); ++i) {
    for (std::size_t j = i + 1; j < centres.size(); ++j) {
      const double overlap = radii[i] + radii[j] - norm(centres[j] - centres[i]);
      if (overlap <= 0.0) continue;
      ++contacts;
      sum += overlap / std::min(radii[i], radii[j]);
      largest = std::max(largest, overlap / std::min(radii[i], radii[j]));
    }
  }
  REQUIRE(contacts > 20);  // the cloud is crowded enough to test something
  const OverlapStatistics stats = pair_overlap_statistics(sim);
  CHECK(stats.contacts == contacts);
  CHECK(stats.mean_relative_overlap == Approx(sum / static_cast<double>(contacts)).epsilon(1e-12));
  CHECK(stats.max_relative_overlap == Approx(largest).epsilon(1e-12));
}
