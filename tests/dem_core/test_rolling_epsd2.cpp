// The epsd2 rolling spring of the Hertz–Mindlin law (ElasticPlasticRolling, contact_law_parts.hpp):
// its stiffness k_t R*^2, the cap mu_r R* F_n, the rolling period of a sphere on a floor, and the
// torque's sign when a pair's members swap roles.
#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>
#include <vector>

#include <cstring>

#include "demfit/dem_core/contact_laws.hpp"
#include "demfit/dem_core/packing.hpp"
#include "demfit/dem_core/pair_history_permutation.hpp"
#include "demfit/dem_core/simulation.hpp"
#include "test_particles.hpp"

using namespace demfit::dem_core;
using namespace demfit::dem_core::test;

namespace {

constexpr double kShear = kHertzYoung / (2.0 * (1.0 + kHertzPoisson));  // G [Pa]

/// Two equal spheres of radius 1 mm pressed together by `overlap` [m] and turning relative to
/// each other at `spin` [rad/s] (no sliding velocity).
ContactGeometry pressed_pair(double overlap, const Vec3& spin) {
  const double r = 1.0e-3, m = kHertzDensity * 4.0 / 3.0 * std::numbers::pi * r * r * r;
  ContactGeometry g;
  g.normal = {0, 0, 1};
  g.overlap = overlap;
  g.relative_angular_velocity = spin;
  g.effective_mass = 0.5 * m;
  g.effective_radius = 0.5 * r;
  g.first_radius = r;
  g.second_radius = r;
  g.normal_compliance = 2.0 * (1.0 - kHertzPoisson * kHertzPoisson) / kHertzYoung;
  g.shear_compliance = 2.0 * (2.0 - kHertzPoisson) / kShear;
  g.inverse_inertia_sum = 2.0 / (0.4 * m * r * r);
  return g;
}

HertzEpsd2Law pair_law(double rolling_friction) {
  ContactParameters p;
  p.frics = 0.5;  // rotation on
  p.fricr = rolling_friction;
  p.restitution = 1.0;
  p.rolling_model = RollingModel::elastic_plastic;
  return HertzEpsd2Law::for_pairs(p);
}

/// A cohesive bed with the epsd2 spring poured into a box (rolling friction on pairs and walls);
/// `reorder`: slab order at rebuilds; `force_rebuilds`: neighbour list and wall slots rebuilt at
/// every step. Returns positions, velocities and angular velocities, then (contacts, list builds).
std::vector<Vec3> epsd2_bed(int threads, bool reorder, bool force_rebuilds) {
  SimulationSettings settings;
  settings.law = ContactLawKind::hertz_mindlin;
  settings.threads = threads;
  settings.reorder_particles = reorder;
  settings.contact.restitution = 0.5;
  settings.contact.frics = 0.5;
  settings.contact.fricr = 0.3;
  settings.contact.rolling_model = RollingModel::elastic_plastic;
  settings.contact.cohesion_energy_density = 2.0e4;
  Simulation sim(settings);
  sim.add_material(kHertzMaterial);
  const double half = 0.006;
  for (const Vec3& n : {Vec3{1, 0, 0}, Vec3{-1, 0, 0}, Vec3{0, 1, 0}, Vec3{0, -1, 0}, Vec3{0, 0, 1}}) {
    WallSpec w{PlaneGeometry{-half * n, n}};
    w.contact.frics = 0.5;
    w.contact.fricd = 0.3;
    sim.add_wall(w);
  }
  PackingRequest request;
  request.region = BoxRegion{{-half, -half, -half}, {half, half, 2 * half}};
  request.radius_min = 0.6e-3;
  request.radius_max = 1.0e-3;
  request.count = 120;
  request.seed = 5;
  add_packing(sim, generate_packing(request));
  sim.run_until(0.06, [&](Simulation& s) {
    if (force_rebuilds) s.set_wall_motion(0, FixedMotion{});
    return true;
  });
  std::vector<Vec3> state(sim.positions().begin(), sim.positions().end());
  for (auto values : {sim.velocities(), sim.angular_velocities()})
    state.insert(state.end(), values.begin(), values.end());
  state.push_back(
      {static_cast<double>(sim.contact_count()), static_cast<double>(sim.neighbor_list().build_count()), 0.0});
  return state;
}

bool same_motion(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), (a.size() - 1) * sizeof(Vec3)) == 0;
}

}  // namespace

TEST_CASE("A cohesive epsd2 bed runs bit-identically on 1 and 2 threads and across forced list rebuilds",
          "[dem_core][rolling][determinism]") {
  const std::vector<Vec3> one = epsd2_bed(1, true, false), two = epsd2_bed(2, true, false);
  INFO("contacts " << one.back().x << ", list builds " << one.back().y);
  CHECK(one.back().x > 50.0);  // the bed has landed: many contacts carry rolling torques
  CHECK(same_motion(one, two));
  // Insertion order: the rolling torques are carried through a rebuild at every step exactly.
  const std::vector<Vec3> natural = epsd2_bed(1, false, false), rebuilt = epsd2_bed(1, false, true);
  CHECK(rebuilt.back().y > 20.0 * natural.back().y);
  CHECK(same_motion(natural, rebuilt));
}

TEST_CASE("The epsd2 torque grows as -k_t R*^2 times the rolling rotation, twist about the normal excluded",
          "[dem_core][rolling]") {
  const double overlap = 1.0e-5, dt = 1.0e-6;
  const Vec3 spin{3.0, -2.0, 7.0};  // the z part is twist about the normal
  const ContactGeometry g = pressed_pair(overlap, spin);
  const HertzEpsd2Law law = pair_law(10.0);  // cap far away
  HertzEpsd2Law::History history;
  const int steps = 20;
  ContactForce f;
  for (int k = 0; k < steps; ++k) f = law.force(g, history, dt);
  // k_t = 8 G* a, G* = 1/sum((2 - nu)/G), a = sqrt(R* delta) (Hertz–Mindlin), R* = R/2.
  const double r_star = 0.5e-3;
  const double k_t = 8.0 * (kShear / (2.0 * (2.0 - kHertzPoisson))) * std::sqrt(r_star * overlap);
  const double k_r = k_t * r_star * r_star;
  const Vec3 expected = -(k_r * dt * steps) * Vec3{spin.x, spin.y, 0.0};
  INFO("torque (" << f.rolling_torque.x << ", " << f.rolling_torque.y << ", " << f.rolling_torque.z << ")");
  CHECK(f.rolling_torque.x == Approx(expected.x).epsilon(1e-12));
  CHECK(f.rolling_torque.y == Approx(expected.y).epsilon(1e-12));
  CHECK(f.rolling_torque.z == 0.0);
  CHECK(norm(history.rolling_torque - f.rolling_torque) == 0.0);  // kept in the contact history
}

TEST_CASE("Under a steady rolling rotation the epsd2 torque saturates at mu_r R* F_n (1e-9)", "[dem_core][rolling]") {
  const double overlap = 1.0e-5, dt = 1.0e-6, mu_r = 0.1;
  const Vec3 spin{40.0, 30.0, 5.0};
  const ContactGeometry g = pressed_pair(overlap, spin);
  const HertzEpsd2Law law = pair_law(mu_r);
  HertzEpsd2Law::History history;
  ContactForce f;
  for (int k = 0; k < 20000; ++k) f = law.force(g, history, dt);
  const double r_star = 0.5e-3;
  const double e_star = kHertzYoung / (2.0 * (1.0 - kHertzPoisson * kHertzPoisson));
  const double f_n = 4.0 / 3.0 * e_star * std::sqrt(r_star) * std::pow(overlap, 1.5);
  const double cap = mu_r * r_star * f_n;
  INFO("|M_r| " << norm(f.rolling_torque) << " N m, cap " << cap << " N m");
  CHECK(norm(f.rolling_torque) == Approx(cap).epsilon(1e-9));
  // Opposing the rolling part of the spin: M_r = -cap (40, 30, 0)/50.
  CHECK(f.rolling_torque.x == Approx(-0.8 * cap).epsilon(1e-9));
  CHECK(f.rolling_torque.y == Approx(-0.6 * cap).epsilon(1e-9));
}

TEST_CASE("A sphere spun slightly on a floor rocks at the epsd2 period 2 pi sqrt(I/(k_t R^2)) (2 %)",
          "[dem_core][rolling]") {
  // Rigid floor without sliding friction (wall FRICS = 0): no tangential force, so the centre
  // stays and the spin sees only the rolling spring. I_eff = I = 2/5 m R^2 (the floor does not
  // turn); k_r = k_t R*^2 with R* = R, k_t = 8 G* a, G* = G/(2 - nu), a = sqrt(R delta) at the
  // static Hertz overlap delta = (m g / (4/3 E* sqrt(R)))^(2/3), E* = E/(1 - nu^2).
  const double r = 1.0e-3, g = 9.81;
  const double m = kHertzDensity * 4.0 / 3.0 * std::numbers::pi * r * r * r;
  const double delta =
      std::pow(m * g / (4.0 / 3.0 * kHertzYoung / (1.0 - kHertzPoisson * kHertzPoisson) * std::sqrt(r)), 2.0 / 3.0);
  const double k_t = 8.0 * kShear / (2.0 - kHertzPoisson) * std::sqrt(r * delta);
  const double inertia = 0.4 * m * r * r;
  const double period = 2.0 * std::numbers::pi * std::sqrt(inertia / (k_t * r * r));

  SimulationSettings settings;
  settings.law = ContactLawKind::hertz_mindlin;
  settings.contact.restitution = 0.3;
  settings.contact.frics = 0.5;  // rotation on
  settings.contact.rolling_model = RollingModel::elastic_plastic;
  settings.gravity = {0, 0, -g};
  Simulation sim(settings);
  sim.add_material(kHertzMaterial);
  WallContactParameters floor;
  floor.frics = 0.0;
  floor.fricd = 1.0;  // wall rolling friction: the cap stays far above the spring's torque
  sim.add_wall({PlaneGeometry{{0, 0, 0}, {0, 0, 1}}, FixedMotion{}, floor});
  sim.add_particle({0, 0, r}, r);
  sim.run_until(0.03);  // settle (normal damping)
  sim.set_particle_velocity(0, {0, 0, 0}, {0.5, 0, 0});
  // Peak torque sqrt(k_r I) 0.5 rad/s is below the cap mu_r R m g:
  REQUIRE(std::sqrt(k_t * r * r * inertia) * 0.5 < 0.5 * r * m * g);
  std::vector<double> crossings;  // downward zero crossings of omega_x [s]
  double previous = 0.5, previous_time = sim.time();
  sim.run_until(sim.time() + 10.5 * period, [&](Simulation& s) {
    const double w = s.angular_velocities()[0].x;
    if (previous > 0.0 && w <= 0.0)
      crossings.push_back(previous_time + (s.time() - previous_time) * previous / (previous - w));
    previous = w;
    previous_time = s.time();
    return true;
  });
  REQUIRE(crossings.size() >= 9);
  const double measured = (crossings.back() - crossings.front()) / static_cast<double>(crossings.size() - 1);
  INFO("period " << measured << " s, expected " << period << " s, step " << sim.time_step() << " s");
  CHECK(measured == Approx(period).epsilon(0.02));
}

TEST_CASE("An epsd2 rolling torque is negated with the tangential spring when a pair's members swap roles",
          "[dem_core][rolling]") {
  const RollingSpringHistory h{{1.0, 2.0, 3.0}, {4.0, -5.0, 6.0}};
  const RollingSpringHistory kept = as_carried(h, 7u);
  const RollingSpringHistory swapped = as_carried(h, 7u | kSwappedPair);
  CHECK(norm(kept.rolling_torque - h.rolling_torque) == 0.0);
  CHECK(norm(swapped.rolling_torque + h.rolling_torque) == 0.0);
  CHECK(norm(swapped.tangential_displacement + h.tangential_displacement) == 0.0);
}
