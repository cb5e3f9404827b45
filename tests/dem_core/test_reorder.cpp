// SimulationSettings::reorder_particles: slab order at neighbour-list rebuilds moves
// particles in memory, never in space. Runs stay bit-identical between thread counts, particles
// keep their ids, and the physics equals the unreordered run up to floating-point round-off.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <vector>

#include "demfit/dem_core/simulation.hpp"
#include "turning_drum.hpp"

using namespace demfit::dem_core;

namespace {

Simulation turning_drum(int threads, bool reorder) {
  SimulationSettings settings;
  settings.threads = threads;
  settings.reorder_particles = reorder;
  return testing::turning_drum(settings);
}

/// Positions and velocities indexed by particle id (the order the caller added them).
std::vector<Vec3> state_by_id(const Simulation& sim) {
  const std::size_t n = sim.particle_count();
  std::vector<Vec3> state(2 * n);
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint32_t id = sim.particles().id[i];
    state[id] = sim.positions()[i];
    state[n + id] = sim.velocities()[i];
  }
  return state;
}

}  // namespace

TEST_CASE("Reordered runs are bit-identical between 1 and 2 threads and keep every particle id",
          "[dem_core][reorder]") {
  Simulation one = turning_drum(1, true), two = turning_drum(2, true);
  one.run_steps(6000);
  two.run_steps(6000);
  REQUIRE(one.neighbor_list().build_count() > 5);
  bool moved = false;
  std::vector<bool> seen(one.particle_count(), false);
  for (std::size_t i = 0; i < one.particle_count(); ++i) {
    const std::uint32_t id = one.particles().id[i];
    REQUIRE(id < seen.size());
    CHECK_FALSE(seen[id]);
    seen[id] = true;
    moved = moved || id != i;
  }
  CHECK(moved);  // the particles really were reordered
  const std::vector<Vec3> a = state_by_id(one), b = state_by_id(two);
  CHECK(std::memcmp(a.data(), b.data(), a.size() * sizeof(Vec3)) == 0);
  CHECK(std::memcmp(one.particles().id.data(), two.particles().id.data(), one.particle_count() * 4) == 0);
  CHECK(one.wall_torque(0) == two.wall_torque(0));
}

TEST_CASE("Reordering a settled, turning bed changes it only at round-off level: positions by id and torque",
          "[dem_core][reorder]") {
  // Pair members and summation order change with the order, so bits differ. A lost or mis-signed
  // tangential history would move grains by ~1e-5 m over these 1000 steps (friction forces of the
  // order of the weight over 6 ms); round-off stays near 1e-14 m (measured) in a settled bed
  // (falling, colliding grains amplify any 1-ulp change chaotically, hence the settled start).
  Simulation settled = turning_drum(2, false);
  settled.run_steps(12000);
  REQUIRE(settled.contact_count() > 100);  // a bed in contact, not a falling cloud
  Simulation plain = settled, reordered = settled;
  reordered.set_reorder_particles(true);
  plain.run_steps(1000);
  reordered.run_steps(1000);
  const std::vector<Vec3> a = state_by_id(plain), b = state_by_id(reordered);
  double worst = 0.0;
  for (std::size_t i = 0; i < plain.particle_count(); ++i) worst = std::max(worst, norm(a[i] - b[i]));
  CHECK(worst < 1.0e-11);
  CHECK(reordered.wall_torque(0) == Approx(plain.wall_torque(0)).epsilon(1e-6));
  CHECK(reordered.contact_count() == plain.contact_count());
  bool moved = false;
  for (std::size_t i = 0; i < reordered.particle_count(); ++i) moved = moved || reordered.particles().id[i] != i;
  CHECK(moved);
}

TEST_CASE("Removing particles compacts every per-particle array in order and keeps their ids", "[dem_core]") {
  Simulation sim{SimulationSettings{}};
  sim.add_material({1.0e8, 1000.0, 0.3});
  for (int i = 0; i < 5; ++i)
    sim.add_particle({0.01 * i, 0.0, 0.0}, 1.0e-3 * (1 + i), 0, {0.1 * i, 0.0, 0.0}, {0.0, 0.0, 0.01 * i});
  sim.remove_particles({false, true, false, true, false});
  const ParticleState& p = sim.particles();
  REQUIRE(p.size() == 3);
  const int survivors[3] = {0, 2, 4};
  for (int k = 0; k < 3; ++k) {
    const int i = survivors[k];
    CHECK(p.id[k] == static_cast<std::uint32_t>(i));
    CHECK(p.position[k].x == 0.01 * i);
    CHECK(p.radius[k] == 1.0e-3 * (1 + i));
    CHECK(p.velocity[k].x == 0.1 * i);
    // Mass follows the radius: rho 4/3 pi R^3 (independent of the compaction).
    CHECK(p.mass[k] == Approx(1000.0 * 4.0 / 3.0 * 3.141592653589793 * std::pow(p.radius[k], 3)).epsilon(1e-12));
    CHECK(p.inverse_mass[k] == Approx(1.0 / p.mass[k]).epsilon(1e-12));
  }
  CHECK(p.force.size() == 3);
  CHECK(p.shear_compliance.size() == 3);
  CHECK(p.material.size() == 3);
}

TEST_CASE("A bed of more than 4096 spheres is put in the same slab order by 1 and 2 threads", "[dem_core][reorder]") {
  // Above 4096 particles two threads sort halves of the order's keys at once and merge them.
  auto falling_box = [](int threads) {
    SimulationSettings settings;
    settings.threads = threads;
    settings.reorder_particles = true;
    settings.contact = {0.01, 2.0 / 7.0, 0.3, 0.3, 0.4, 0.3, 1.0, 0.05, 1.0};
    Simulation sim(settings);
    sim.add_material({1.0e9, 2500.0, 0.3});
    PackingRequest request;
    request.region = BoxRegion{{0, 0, 0}, {0.04, 0.04, 0.02}};
    request.radius_min = 0.4e-3;
    request.radius_max = 0.5e-3;
    request.count = 5000;
    request.seed = 9;
    add_packing(sim, generate_packing(request));
    sim.run_steps(50);
    return sim;
  };
  const Simulation one = falling_box(1), two = falling_box(2);
  REQUIRE(one.particle_count() == 5000);
  bool reordered = false;
  for (std::size_t i = 0; i < one.particle_count(); ++i) reordered = reordered || one.particles().id[i] != i;
  REQUIRE(reordered);
  CHECK(std::memcmp(one.particles().id.data(), two.particles().id.data(), 5000 * sizeof(std::uint32_t)) == 0);
  CHECK(std::memcmp(one.positions().data(), two.positions().data(), 5000 * sizeof(Vec3)) == 0);
}

namespace {

/// Slab index along `axis` (0 x, 1 y, 2 z) of every particle in memory order, for the cell edge
/// the kernel orders by (2 r_max + skin).
std::vector<long> slabs_in_memory_order(const Simulation& sim, int axis, double cell) {
  auto coordinate = [axis](const Vec3& v) { return axis == 0 ? v.x : axis == 1 ? v.y : v.z; };
  double low = 1e300;
  for (const Vec3& x : sim.positions()) low = std::min(low, coordinate(x));
  std::vector<long> slab;
  for (const Vec3& x : sim.positions()) slab.push_back(static_cast<long>(std::floor((coordinate(x) - low) / cell)));
  return slab;
}

}  // namespace

TEST_CASE("Reordered particles lie in slabs one cell thick across the bed's longest extent", "[dem_core][reorder]") {
  // Why slabs: T threads take contiguous chunks of the order, so a chunk boundary must be a plane
  // section of the bed (few crossing pairs), not the staircase of octant faces a 3-D Morton order
  // gives. Lattices of separated spheres (no contact, no gravity), added in reverse order, long
  // along x and then along z: along memory the slab index of the long axis never decreases.
  for (const int axis : {0, 2}) {
    SimulationSettings settings;
    settings.gravity = {0.0, 0.0, 0.0};
    settings.skin = 0.3e-3;
    Simulation sim(settings);
    sim.add_material({1e9, 2500.0, 0.3});
    const int along = 40, across_a = 6, across_b = 12;
    const double spacing = 2.5e-3, radius = 1e-3;
    for (int a = along - 1; a >= 0; --a)
      for (int b = across_a - 1; b >= 0; --b)
        for (int c = across_b - 1; c >= 0; --c) {
          const Vec3 at =
              axis == 0 ? Vec3{a * spacing, b * spacing, c * spacing} : Vec3{b * spacing, c * spacing, a * spacing};
          sim.add_particle(at, radius);
        }
    sim.run_steps(1);
    REQUIRE(sim.particles().id[0] != 0);  // reordering did move them (else this test proves nothing)
    const std::vector<long> slab = slabs_in_memory_order(sim, axis, 2.0 * radius + settings.skin);
    CHECK(std::is_sorted(slab.begin(), slab.end()));
    CHECK(slab.back() >= along - 2);  // slabs run along the long axis (42 slabs of 2.3 mm over 97.5 mm)
  }
}
