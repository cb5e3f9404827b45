// The Hertz–Mindlin pair law computed several pairs at a time in SIMD lanes
// (src/hertz_pair_lanes.hpp) against the scalar law it replaces (pair_loads with
// HertzMindlinLaw): the same bits for every lane, sticking and sliding, with and without a stored
// spring and spin, in full and partial batches; and whole runs that are bit-identical either way.
#include <catch2/catch.hpp>

#include <cstring>
#include <random>
#include <vector>

#include "contact_loops.hpp"
#include "demfit/dem_core/simulation.hpp"
#include "hertz_pair_lanes.hpp"
#include "test_particles.hpp"
#include "turning_drum.hpp"

using namespace demfit::dem_core;
using namespace demfit::dem_core::test;

namespace {

bool same_bits(const Vec3& a, const Vec3& b) { return std::memcmp(&a, &b, sizeof(Vec3)) == 0; }

/// 2 n particles in n overlapping pairs (2k, 2k+1) with random sizes, overlaps up to 2 % of the
/// radius, velocities, spins (every third pair without spin) and Hertz compliances.
ParticleState overlapping_pairs(std::size_t n, std::mt19937_64& random) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0), positive(0.0, 1.0);
  ParticleState p;
  for (std::size_t k = 0; k < 2 * n; ++k) {
    const double radius = 1e-3 * (0.6 + 0.4 * positive(random));
    Vec3 position{unit(random), unit(random), unit(random)};
    if (k % 2 == 1) {
      const Vec3 direction = normalized({unit(random), unit(random), unit(random)});
      const double distance = (p.radius.back() + radius) * (1.0 - 0.02 * positive(random));
      position = p.position.back() + distance * direction;
    }
    const double mass = 2500.0 * 4.18879 * radius * radius * radius;
    p.position.push_back(position);
    p.velocity.push_back({0.1 * unit(random), 0.1 * unit(random), 0.1 * unit(random)});
    const bool spinning = (k / 2) % 3 != 0;
    p.angular_velocity.push_back(spinning ? Vec3{50 * unit(random), 50 * unit(random), 50 * unit(random)} : Vec3{});
    p.radius.push_back(radius);
    p.mass.push_back(mass);
    p.inverse_mass.push_back(1.0 / mass);
    p.inverse_inertia.push_back(1.0 / (0.4 * mass * radius * radius));
    p.normal_compliance.push_back((1.0 - 0.09) / (1e8 * (1.0 + positive(random))));
    p.shear_compliance.push_back(1.7 / (4e7 * (1.0 + positive(random))));
  }
  return p;
}

}  // namespace

TEST_CASE("The laned Hertz-Mindlin pair law gives the scalar law's loads and springs bit for bit",
          "[dem_core][hertz]") {
  std::mt19937_64 random(17);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const std::size_t pairs = 400;
  const ParticleState p = overlapping_pairs(pairs, random);
  ContactParameters parameters;
  parameters.frics = 0.3;
  parameters.fricr = 0.1;
  parameters.restitution = 0.4;
  const HertzMindlinLaw law = HertzMindlinLaw::for_pairs(parameters);
  // Rolling limited by "no reversal within a step" on some contacts: a long step.
  const StepInputs step{{0, 0, -9.81}, 2e-5, 1e-5, true, 1, true};
  REQUIRE(hertz_lanes_apply(law, step));
  // Stored springs: none, small (sticking) or long (sliding), and one exactly in the tangent plane.
  std::vector<ContactHistory> stored(pairs);
  for (std::size_t k = 0; k < pairs; ++k) {
    const double length = k % 4 == 0 ? 0.0 : (k % 4 == 1 ? 1e-9 : 1e-5);
    stored[k].tangential_displacement = {length * unit(random), length * unit(random), length * unit(random)};
  }
  std::vector<ContactHistory> scalar_history = stored, laned_history = stored;
  std::vector<std::uint8_t> touching(pairs, 1);
  std::size_t sliding = 0, checked = 0;
  // Batches of 1, 2, ..., kPairLanes pairs in turn (partial batches repeat lane 0 in the rest).
  for (std::size_t k = 0, size = 1; k < pairs; k += size, size = size % kPairLanes + 1) {
    PairLaneBatch batch;
    for (std::size_t l = 0; l < size && k + l < pairs; ++l) {
      const auto pair = static_cast<std::uint32_t>(k + l);
      batch.first[batch.count] = 2 * pair;
      batch.second[batch.count] = 2 * pair + 1;
      batch.pair[batch.count] = pair;
      ++batch.count;
    }
    hertz_pair_lanes(law, laned_history.data(), p, step, batch);
    for (int l = 0; l < batch.count; ++l) {
      const std::uint32_t pair = batch.pair[l];
      PairLoads expected;
      REQUIRE(pair_loads(law, scalar_history.data(), touching.data(), p, pair, 2 * pair, 2 * pair + 1, step, expected));
      const PairLoads& got = batch.loads[l];
      CHECK(same_bits(got.force, expected.force));
      CHECK(same_bits(got.torque_first, expected.torque_first));
      CHECK(same_bits(got.torque_second, expected.torque_second));
      CHECK(same_bits(laned_history[pair].tangential_displacement, scalar_history[pair].tangential_displacement));
      // Sliding when the spring was reset to the Coulomb limit: no longer old + v_t dt.
      sliding += norm(scalar_history[pair].tangential_displacement) < 0.5 * norm(stored[pair].tangential_displacement);
      ++checked;
    }
  }
  CHECK(checked == pairs);
  CHECK(sliding > pairs / 10);  // both branches of the Coulomb limit are exercised
  CHECK(sliding < pairs);
}

TEST_CASE("A Hertz-Mindlin turning drum runs bit-identically with the laned and the scalar pair law on 1 and 2 threads",
          "[dem_core][hertz][determinism]") {
  auto run = [](int threads, bool laned) {
    SimulationSettings settings;
    settings.law = ContactLawKind::hertz_mindlin;
    settings.threads = threads;
    settings.reorder_particles = false;
    settings.laned_pair_law = laned;
    Simulation sim = testing::turning_drum(settings, true);
    ContactParameters hertz;
    hertz.frics = 0.4;
    hertz.fricr = 0.05;
    hertz.restitution = 0.5;
    sim.set_contact_parameters(hertz);
    sim.set_gravity({0, -200.0, 0});  // the stiff Hertz step is short: a fast pour fills the bed sooner
    sim.run_steps(15000);
    std::vector<Vec3> state(sim.positions().begin(), sim.positions().end());
    state.insert(state.end(), sim.angular_velocities().begin(), sim.angular_velocities().end());
    state.push_back({sim.wall_torque(0), sim.elastic_energy(), static_cast<double>(sim.contact_count())});
    return std::pair{state, sim.contact_count()};
  };
  const auto [scalar, contacts] = run(1, false);
  REQUIRE(contacts > 100);
  CHECK(bitwise_equal(scalar, run(1, true).first));
  CHECK(bitwise_equal(scalar, run(2, true).first));
}
