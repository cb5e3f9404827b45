// SimulationSettings::pair_load_order: summing each particle's pair loads in
// ascending first member stores nothing per pair. Runs stay bit-identical for any thread count,
// even when neighbours in space are far apart in memory (many pairs cross the threads' chunks),
// and the physics equals the own-row-first order up to floating-point round-off.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <vector>

#include "demfit/dem_core/simulation.hpp"
#include "turning_drum.hpp"
#include "test_particles.hpp"

using namespace demfit::dem_core;
using namespace demfit::dem_core::test;

namespace {

/// The small turning drum with its particles added in a random order and never reordered, so
/// about half the pairs cross between two threads' chunks.
Simulation shuffled_turning_drum(int threads, PairLoadOrder order) {
  SimulationSettings settings;
  settings.threads = threads;
  settings.reorder_particles = false;
  settings.pair_load_order = order;
  return testing::turning_drum(settings, true);
}

std::vector<Vec3> final_state(const Simulation& sim) {
  std::vector<Vec3> state(sim.positions().begin(), sim.positions().end());
  state.insert(state.end(), sim.velocities().begin(), sim.velocities().end());
  state.insert(state.end(), sim.angular_velocities().begin(), sim.angular_velocities().end());
  state.push_back({sim.wall_torque(0), sim.elastic_energy(), static_cast<double>(sim.contact_count())});
  return state;
}

/// Pairs of the current list whose members fall in different halves of the particle range.
std::size_t pairs_crossing_halves(const Simulation& sim) {
  const NeighborList& list = sim.neighbor_list();
  const std::size_t half = sim.particle_count() / 2;
  std::size_t crossing = 0;
  for (std::size_t i = 0; i < half; ++i)
    for (std::uint32_t k = list.row_offsets()[i]; k < list.row_offsets()[i + 1]; ++k)
      crossing += list.second()[k] >= half;
  return crossing;
}

}  // namespace

TEST_CASE("Pair loads summed in ascending first member give bit-identical runs on 1 2 and 3 threads",
          "[dem_core][determinism]") {
  Simulation one = shuffled_turning_drum(1, PairLoadOrder::ascending_first_member);
  Simulation two = shuffled_turning_drum(2, PairLoadOrder::ascending_first_member);
  Simulation three = shuffled_turning_drum(3, PairLoadOrder::ascending_first_member);
  for (Simulation* sim : {&one, &two, &three}) sim->run_steps(6000);
  REQUIRE(one.contact_count() > 50);                                           // grains in contact
  REQUIRE(pairs_crossing_halves(two) > two.neighbor_list().pair_count() / 4);  // chunks really cross
  CHECK(one.neighbor_list().column_offsets().empty());                         // no transposed index is built
  const std::vector<Vec3> a = final_state(one);
  CHECK(bitwise_equal(a, final_state(two)));
  CHECK(bitwise_equal(a, final_state(three)));
}

TEST_CASE("Pair loads in own-row-first order give bit-identical runs on 1 and 2 threads", "[dem_core][determinism]") {
  Simulation one = shuffled_turning_drum(1, PairLoadOrder::own_row_first);
  Simulation two = shuffled_turning_drum(2, PairLoadOrder::own_row_first);
  one.run_steps(6000);
  two.run_steps(6000);
  REQUIRE(one.contact_count() > 50);
  CHECK(one.neighbor_list().column_offsets().size() == one.particle_count() + 1);
  CHECK(bitwise_equal(final_state(one), final_state(two)));
}

TEST_CASE("The two pair-load orders differ only at round-off level on a settled turning bed", "[dem_core]") {
  // Only the order of additions differs, so bits do; a lost load or a mis-signed torque would move
  // grains by ~1e-5 m over these 1000 steps (forces of the order of the weight over 6 ms), while
  // round-off stays near 1e-14 m in a settled bed (the bound of the reordering test).
  Simulation settled = shuffled_turning_drum(2, PairLoadOrder::own_row_first);
  settled.run_steps(12000);
  REQUIRE(settled.contact_count() > 100);
  Simulation own_row = settled, ascending = settled;
  ascending.set_pair_load_order(PairLoadOrder::ascending_first_member);
  own_row.run_steps(1000);
  ascending.run_steps(1000);
  double worst = 0.0, scale = 0.0;
  for (std::size_t i = 0; i < own_row.particle_count(); ++i) {
    worst = std::max(worst, norm(own_row.positions()[i] - ascending.positions()[i]));
    scale = std::max(scale, norm(own_row.velocities()[i]));
  }
  CHECK(worst > 0.0);  // the order really changed
  CHECK(worst < 1.0e-11);
  CHECK(scale > 1e-3);  // the bed turns
  CHECK(ascending.wall_torque(0) == Approx(own_row.wall_torque(0)).epsilon(1e-6));
  CHECK(ascending.contact_count() == own_row.contact_count());
  CHECK(ascending.elastic_energy() == Approx(own_row.elastic_energy()).epsilon(1e-6));
}
