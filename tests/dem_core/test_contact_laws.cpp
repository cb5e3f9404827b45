// The contact-law registry (contact_laws.hpp) and the law-owned contact history: the effects
// law's history carries the plastic memory (largest overlap) across neighbour-list and
// wall-slot rebuilds exactly as the tangential spring.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <type_traits>
#include <vector>

#include "demfit/dem_core/contact_laws.hpp"
#include "demfit/dem_core/simulation.hpp"
#include "test_particles.hpp"

using namespace demfit::dem_core;
using namespace demfit::dem_core::test;

namespace {

constexpr double unloading_ratio = 2.0;

struct PlasticRun {
  std::vector<Vec3> state;       // positions, velocities, angular velocities (by particle)
  std::size_t builds = 0;        // neighbour-list builds
  double floor_rebound = 0.0;    // largest upward speed of the bouncing sphere [m/s]
  double pair_separation = 0.0;  // normal separation speed of the colliding pair [m/s]
};

/// A sphere bouncing obliquely on a floor and an oblique pair collision in the air, Walton–Braun
/// plasticity on, no viscous damping, friction and rotation on. `force_rebuilds`: the neighbour
/// list and the wall slots are rebuilt at every step (set_wall_motion requests a rebuild).
PlasticRun plastic_collisions(bool force_rebuilds) {
  SimulationSettings settings;
  settings.contact.frics = 0.3;
  settings.contact.unloading_stiffness_ratio = unloading_ratio;
  settings.time_step_factor = 0.01;
  Simulation sim(settings);
  sim.add_material({1.0e9, 2500.0, 0.3});
  const std::size_t floor = sim.add_wall({PlaneGeometry{{0, 0, 0}, {0, 0, 1}}, FixedMotion{}, {.frics = 0.3}});
  sim.add_particle({0, 0, kSphereRadius + 1e-4}, kSphereRadius, 0, {0.1, 0, -0.5});
  sim.add_particle({0.02 - 1.5e-3, 0, 0.01}, kSphereRadius, 0, {0.5, 0, 0});
  sim.add_particle({0.02 + 1.5e-3, 0.5e-3, 0.01}, kSphereRadius, 0, {-0.5, 0, 0});
  PlasticRun run;
  sim.run_until(3e-3, [&](Simulation& s) {
    run.floor_rebound = std::max(run.floor_rebound, s.velocities()[0].z);
    if (force_rebuilds) s.set_wall_motion(floor, FixedMotion{});
    return true;
  });
  for (auto values : {sim.positions(), sim.velocities(), sim.angular_velocities()})
    run.state.insert(run.state.end(), values.begin(), values.end());
  run.builds = sim.neighbor_list().build_count();
  const Vec3 n = normalized(sim.positions()[2] - sim.positions()[1]);
  run.pair_separation = dot(sim.velocities()[2] - sim.velocities()[1], n);
  return run;
}

}  // namespace

TEST_CASE("Plasticity's largest overlap is carried across neighbour-list and wall-slot rebuilds, bit for bit",
          "[dem_core][effects]") {
  const PlasticRun natural = plastic_collisions(false), rebuilt = plastic_collisions(true);
  CHECK(rebuilt.builds > 20 * natural.builds);  // rebuilt at every step (~2000) vs a few times
  REQUIRE(natural.state.size() == rebuilt.state.size());
  CHECK(std::memcmp(natural.state.data(), rebuilt.state.data(), natural.state.size() * sizeof(Vec3)) == 0);
  // The memory was in use: without it every step would load the virgin (elastic) line and the
  // spheres would rebound at their approach speed. With it the normal restitution is
  // 1/sqrt(ratio) (Walton & Braun 1986); 3 % covers gravity during the contact and the step.
  const double e = 1.0 / std::sqrt(unloading_ratio);
  CHECK(rebuilt.floor_rebound / 0.5 == Approx(e).epsilon(0.03));
  // Pair: approach speed along the line of centres at first touch (offset 0.5 R, distance 2 R).
  const double approach = std::sqrt(1.0 - 0.25 * 0.25);  // |v_rel| cos(asin(0.25)), |v_rel| = 1 m/s
  CHECK(rebuilt.pair_separation / approach == Approx(e).epsilon(0.03));
}

TEST_CASE("Each contact-law kind has one registry row and selects its law type, the effects law only with an effect on",
          "[dem_core]") {
  for (const ContactLawRow& row : kContactLaws) {
    CHECK(contact_law_kind(row.name) == row.kind);
    CHECK(contact_law_name(row.kind) == row.name);
  }
  CHECK_FALSE(contact_law_kind("linear").has_value());
  auto law_of = [](ContactLawKind kind, const ContactParameters& c) {
    return with_contact_law(kind, c, []<class Law>(std::type_identity<Law>) {
      if constexpr (std::is_same_v<Law, LsDynaLinearLaw>) return 0;
      if constexpr (std::is_same_v<Law, LsDynaEffectsLaw>) return 1;
      if constexpr (std::is_same_v<Law, HertzMindlinLaw>) return 2;
      if constexpr (std::is_same_v<Law, HertzEpsd2Law>) return 3;
    });
  };
  ContactParameters c;
  CHECK(law_of(ContactLawKind::lsdyna_linear, c) == 0);
  CHECK(law_of(ContactLawKind::hertz_mindlin, c) == 2);
  c.cohesion_energy_density = 1000.0;  // cohesion is a value of the Hertz law, not another type
  CHECK(law_of(ContactLawKind::hertz_mindlin, c) == 2);
  c.rolling_model = RollingModel::elastic_plastic;
  CHECK(law_of(ContactLawKind::hertz_mindlin, c) == 3);
  c = ContactParameters{};
  c.surface_energy = 0.1;
  CHECK(law_of(ContactLawKind::lsdyna_linear, c) == 1);
  // The plain laws keep 24 bytes per contact; only the effects law pays for its memory.
  CHECK(sizeof(LsDynaLinearLaw::History) == 24);
  CHECK(sizeof(HertzMindlinLaw::History) == 24);
  CHECK(sizeof(LsDynaEffectsLaw::History) == 32);
  CHECK(sizeof(HertzEpsd2Law::History) == 48);  // + the rolling torque
}
