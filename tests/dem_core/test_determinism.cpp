// Determinism (bitwise, with threads) and the neighbour list against brute force.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>
#include <set>
#include <utility>
#include <vector>

#include "demfit/dem_core/packing.hpp"
#include "demfit/dem_core/simulation.hpp"
#include "turning_drum.hpp"
#include "test_particles.hpp"

using namespace demfit::dem_core;
using namespace demfit::dem_core::test;

namespace {

/// A frictional, rolling, damped bed poured into a box; returns the final state as raw bytes.
std::vector<Vec3> run_bed(int threads) {
  SimulationSettings settings;
  settings.threads = threads;
  settings.contact = {0.01, 2.0 / 7.0, 0.3, 0.3, 0.4, 0.3, 1.0, 0.05, 1.0};
  Simulation sim(settings);
  sim.add_material({1.0e9, 2500.0, 0.3});
  const double half = 0.01;
  const Vec3 normals[5] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}};
  for (const Vec3& n : normals) {
    WallSpec w{PlaneGeometry{-half * n, n}};
    w.contact = {0.4, 0.05, 0.3, 1.0};
    sim.add_wall(w);
  }
  PackingRequest request;
  request.region = BoxRegion{{-half, -half, -half}, {half, half, 3 * half}};
  request.radius_min = 0.6e-3;
  request.radius_max = 1.0e-3;
  request.count = 250;
  request.seed = 11;
  add_packing(sim, generate_packing(request));
  sim.run_steps(5000);
  std::vector<Vec3> state(sim.positions().begin(), sim.positions().end());
  state.insert(state.end(), sim.velocities().begin(), sim.velocities().end());
  state.insert(state.end(), sim.angular_velocities().begin(), sim.angular_velocities().end());
  state.push_back({sim.wall_force(4).z, sim.elastic_energy(), static_cast<double>(sim.contact_count())});
  return state;
}

/// n spheres of radius 0.5-1.5 mm at uniformly random places in [0, length] x [0, 0.03] x [0, 0.02] m.
struct RandomSpheres {
  std::vector<Vec3> x;
  std::vector<double> r;
};
RandomSpheres random_spheres(std::uint64_t seed, std::size_t n, double length) {
  std::mt19937_64 rng(seed);
  auto u = [&] { return static_cast<double>(rng() >> 11) * 0x1.0p-53; };
  RandomSpheres s{std::vector<Vec3>(n), std::vector<double>(n)};
  for (std::size_t i = 0; i < n; ++i) {
    s.x[i] = {length * u(), 0.03 * u(), 0.02 * u()};
    s.r[i] = 0.5e-3 + 1.0e-3 * u();
  }
  return s;
}

}  // namespace

TEST_CASE("The neighbour list is the same on 1 2 and 3 threads whatever buffer size it is told to expect",
          "[dem_core][neighbors]") {
  // 9000 spheres: 36 blocks of rows in 2 waves, taken by the threads as they come and copied back
  // in order.
  const std::size_t n = 9000;
  const auto [x, r] = random_spheres(5, n, 0.18);
  NeighborList reference;
  reference.build(x, r, 0.4e-3, 1, false);
  const std::vector<std::uint32_t> rows(reference.row_offsets().begin(), reference.row_offsets().end());
  const std::vector<std::uint32_t> second(reference.second().begin(), reference.second().end());
  REQUIRE(second.size() > 2 * n);  // dense enough that every block holds pairs
  for (std::size_t i = 0; i < n; ++i) CHECK(std::is_sorted(second.begin() + rows[i], second.begin() + rows[i + 1]));
  for (int threads : {1, 2, 3})
    for (std::size_t expected : {std::size_t{0}, second.size() / 7, second.size(), 10 * second.size()}) {
      NeighborList list;
      list.build(x, r, 0.4e-3, threads, false, expected);
      INFO("threads " << threads << ", expected pairs " << expected);
      CHECK(std::equal(rows.begin(), rows.end(), list.row_offsets().begin(), list.row_offsets().end()));
      CHECK(std::equal(second.begin(), second.end(), list.second().begin(), list.second().end()));
    }
}

TEST_CASE("A neighbour list of 40000 spheres built in waves equals a sweep along x", "[dem_core][neighbors]") {
  // Over 128 blocks of 256 rows the build runs in 8 waves; the reference is another algorithm:
  // sort by x and check every pair closer than the largest cutoff in x.
  const std::size_t n = 40000;
  const auto [x, r] = random_spheres(8, n, 0.6);
  const double skin = 0.4e-3, reach = 2 * 1.5e-3 + skin;
  std::vector<std::uint32_t> by_x(n);
  for (std::uint32_t i = 0; i < n; ++i) by_x[i] = i;
  std::sort(by_x.begin(), by_x.end(), [&](std::uint32_t a, std::uint32_t b) { return x[a].x < x[b].x; });
  std::vector<std::pair<std::uint32_t, std::uint32_t>> expected;
  for (std::size_t a = 0; a < n; ++a)
    for (std::size_t b = a + 1; b < n && x[by_x[b]].x - x[by_x[a]].x < reach; ++b) {
      const std::uint32_t i = std::min(by_x[a], by_x[b]), j = std::max(by_x[a], by_x[b]);
      const double c = r[i] + r[j] + skin;
      if (norm2(x[j] - x[i]) < c * c) expected.emplace_back(i, j);
    }
  std::sort(expected.begin(), expected.end());
  for (int threads : {1, 2})
    for (std::size_t hint : {std::size_t{0}, expected.size()}) {
      NeighborList list;
      list.build(x, r, skin, threads, false, hint);
      std::vector<std::pair<std::uint32_t, std::uint32_t>> found;
      for (std::size_t i = 0; i < n; ++i)
        for (std::uint32_t k = list.row_offsets()[i]; k < list.row_offsets()[i + 1]; ++k)
          found.emplace_back(static_cast<std::uint32_t>(i), list.second()[k]);
      INFO("threads " << threads << ", expected pairs " << hint);
      CHECK(found == expected);  // rows ascending, each row sorted: the sorted pair set
    }
}

TEST_CASE("Runs are bit-identical: repeated with 2 threads, and between 1 and 2 threads", "[dem_core][determinism]") {
  const std::vector<Vec3> two_a = run_bed(2);
  const std::vector<Vec3> two_b = run_bed(2);
  const std::vector<Vec3> one = run_bed(1);
  CHECK(two_a.back().z > 0.0);  // contacts happened
  CHECK(bitwise_equal(two_a, two_b));
  // Pair loads are computed per pair and gathered in a fixed order, so the thread count does
  // not change the arithmetic either.
  CHECK(bitwise_equal(one, two_a));
}

TEST_CASE("The Verlet neighbour list equals a brute-force pair search on a random box", "[dem_core][neighbors]") {
  const std::size_t n = 2000;
  const auto [x, r] = random_spheres(3, n, 0.05);
  const double skin = 0.4e-3;
  NeighborList list;
  list.build(x, r, skin, 2);
  std::set<std::pair<std::uint32_t, std::uint32_t>> expected, found;
  for (std::uint32_t i = 0; i < n; ++i)
    for (std::uint32_t j = i + 1; j < n; ++j) {
      const double c = r[i] + r[j] + skin;
      if (norm2(x[j] - x[i]) < c * c) expected.insert({i, j});
    }
  for (std::size_t i = 0; i < n; ++i)
    for (std::uint32_t k = list.row_offsets()[i]; k < list.row_offsets()[i + 1]; ++k)
      found.insert({static_cast<std::uint32_t>(i), list.second()[k]});
  CHECK(found.size() == list.pair_count());  // no duplicates
  CHECK(found == expected);
  CHECK(list.row_offsets()[n] == list.pair_count());
  // The transposed index is consistent with the pair arrays.
  for (std::size_t i = 0; i < n; ++i) {
    for (std::uint32_t c = list.column_offsets()[i]; c < list.column_offsets()[i + 1]; ++c)
      REQUIRE(list.second()[list.column_pairs()[c]] == i);
  }
  CHECK(list.column_offsets()[n] == list.pair_count());
  // Moving one particle by more than half the skin triggers a rebuild; less does not.
  std::vector<Vec3> moved = x;
  moved[17].x += 0.49 * skin;
  CHECK_FALSE(list.needs_rebuild(moved, 1));
  moved[17].x += 0.02 * skin;
  CHECK(list.needs_rebuild(moved, 1));
}

TEST_CASE("Reading the wall loads every step leaves the elastic energy and contact count as a first reading gives") {
  // The wall loads and the pair energy are reduced lazily and apart (a drum reads its torque every
  // step); a stale or half-reduced energy would differ from a twin's first-ever reading.
  SimulationSettings settings;
  settings.threads = 2;
  Simulation poured = testing::turning_drum(settings);
  poured.run_steps(6000);  // grains in contact (the pair-load-order tests' pour)
  Simulation every_step = poured, energy_only = poured, first_reading = poured;
  std::vector<double> energies;
  for (int step = 1; step <= 300; ++step) {
    every_step.step();
    energy_only.step();
    first_reading.step();
    const double torque = every_step.wall(0).torque;
    REQUIRE(std::isfinite(torque));
    if (step % 100 == 0) {
      energies.push_back(every_step.elastic_energy());
      CHECK(energies.back() == energy_only.elastic_energy());
      CHECK(every_step.contact_count() == energy_only.contact_count());
    }
  }
  CHECK(energies.back() == first_reading.elastic_energy());
  CHECK(every_step.contact_count() == first_reading.contact_count());
  CHECK(every_step.contact_count() > 0);
  CHECK(energies[0] != energies[1]);  // the readings follow the bed
  CHECK(energies[1] != energies[2]);
}
