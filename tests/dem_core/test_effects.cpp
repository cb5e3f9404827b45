// Effects library (contact_effects.hpp): plasticity, cohesion and nonlinear stiffness
// against closed-form results (polydispersity and the bookkeeping: test_effects_bookkeeping.cpp).
// Every expected number is derived here.
#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>

#include "demfit/dem_core/contact_law_linear.hpp"
#include "demfit/dem_core/simulation.hpp"
#include "test_particles.hpp"

using namespace demfit::dem_core;
using namespace demfit::dem_core::test;

namespace {

/// Pair spring of two equal spheres (series): k_n = NORMK K R / 2.
double pair_stiffness(const ContactParameters& c) { return c.normk * kTestMaterial.bulk_modulus * kSphereRadius / 2.0; }

struct Impact {
  double restitution;  // separation speed / approach speed
  double duration;     // [s] from first to last overlap (interpolated inside the step)
};

/// Two equal spheres approaching head-on along x at relative speed `speed`, no gravity.
Impact pair_impact(const ContactParameters& contact, double speed, double factor, double skin = 0.0) {
  SimulationSettings settings;
  settings.skin = skin;  // 0 = default (0.3 R)
  settings.gravity = {0, 0, 0};
  settings.contact = contact;
  settings.time_step_factor = factor;
  Simulation sim(settings);
  sim.add_material(kTestMaterial);
  sim.add_particle({-kSphereRadius - 1e-6, 0, 0}, kSphereRadius, 0, {0.5 * speed, 0, 0});
  sim.add_particle({kSphereRadius + 1e-6, 0, 0}, kSphereRadius, 0, {-0.5 * speed, 0, 0});
  const double dt = sim.time_step();
  double start = -1.0, end = -1.0;
  for (int s = 0; s < 10000000 && end < 0.0; ++s) {
    sim.step();
    const double distance = sim.positions()[1].x - sim.positions()[0].x;
    const double closing = sim.velocities()[1].x - sim.velocities()[0].x;
    const double previous = distance - dt * closing;
    if (distance < 2.0 * kSphereRadius && start < 0.0)
      start = sim.time() - dt * (2.0 * kSphereRadius - distance) / (previous - distance);
    if (distance >= 2.0 * kSphereRadius && start >= 0.0)
      end = sim.time() - dt * (distance - 2.0 * kSphereRadius) / (distance - previous);
  }
  return {(sim.velocities()[1].x - sim.velocities()[0].x) / speed, end - start};
}

/// A sphere moving at `speed` against a fixed plane x = 0 (normal +x), no gravity.
double wall_restitution(const ContactParameters& contact, double speed, double factor) {
  SimulationSettings settings;
  settings.gravity = {0, 0, 0};
  settings.contact = contact;
  settings.time_step_factor = factor;
  Simulation sim(settings);
  sim.add_material(kTestMaterial);
  sim.add_wall({PlaneGeometry{{0, 0, 0}, {1, 0, 0}}});
  sim.add_particle({kSphereRadius + 1e-6, 0, 0}, kSphereRadius, 0, {-speed, 0, 0});
  while (sim.velocities()[0].x < 0.0 || sim.positions()[0].x < kSphereRadius) sim.step();
  return sim.velocities()[0].x / speed;
}

/// Settles one sphere on a plane z = 0 under gravity (-g_z) and returns its overlap.
double resting_overlap(const ContactParameters& contact, double gravity) {
  SimulationSettings settings;
  settings.gravity = {0, 0, -gravity};
  settings.contact = contact;
  Simulation sim(settings);
  sim.add_material(kTestMaterial);
  WallSpec floor{PlaneGeometry{{0, 0, 0}, {0, 0, 1}}};
  floor.contact.damp = 0.5;
  sim.add_wall(floor);
  sim.add_particle({0, 0, kSphereRadius}, kSphereRadius);
  sim.run_until(0.05);
  return kSphereRadius - sim.positions()[0].z;
}

}  // namespace

TEST_CASE("Plasticity: the Walton-Braun spring loads with k1, unloads and reloads with k2 = ratio k1, never pulls",
          "[dem_core][effects]") {
  // Direct evaluation of the normal part against F = k1 delta (virgin), F = k2 (delta - delta0),
  // delta0 = delta_max (1 - k1/k2) below delta_max, F = 0 below delta0 (tolerance 1e-12 relative).
  const double k1 = 5000.0, ratio = 2.5, k2 = ratio * k1;
  EffectsNormal normal;
  normal.unloading_ratio = ratio;
  ContactGeometry g;
  g.normal = {1, 0, 0};
  g.effective_mass = 1e-5;
  g.effective_radius = 0.5e-3;
  g.normal_compliance = 1.0 / k1;
  double h = 0.0;  // the contact's largest overlap, kept by the simulation per contact
  const double delta_max = 4e-6, delta0 = delta_max * (1.0 - k1 / k2);
  for (double d : {1e-6, 2e-6, 4e-6}) {
    g.overlap = d;
    CHECK(normal.evaluate(g, &h).force == Approx(k1 * d).epsilon(1e-12));
  }
  CHECK(h == delta_max);
  for (double d : {3.5e-6, 3e-6, 2.5e-6}) {  // unloading
    g.overlap = d;
    const auto r = normal.evaluate(g, &h);
    CHECK(r.force == Approx(k2 * (d - delta0)).epsilon(1e-12));
    CHECK(r.energy == Approx(0.5 * k2 * (d - delta0) * (d - delta0)).epsilon(1e-12));  // recoverable part
  }
  g.overlap = 0.5 * delta0;  // below delta0: no force, and in particular no attraction
  CHECK(normal.evaluate(g, &h).force == 0.0);
  g.overlap = 3.8e-6;  // reloading stays on the k2 line below delta_max ...
  CHECK(normal.evaluate(g, &h).force == Approx(k2 * (3.8e-6 - delta0)).epsilon(1e-12));
  g.overlap = 5e-6;  // ... and continues on the loading line beyond it
  CHECK(normal.evaluate(g, &h).force == Approx(k1 * 5e-6).epsilon(1e-12));
  CHECK(h == 5e-6);
}

TEST_CASE(
    "Plasticity: undamped head-on restitution is 1/sqrt(ratio) for pairs and walls, also with a stiffness exponent",
    "[dem_core][effects]") {
  // Energy absorbed on loading (area under k1 delta up to delta_max) vs returned on unloading
  // (area under k2 (delta - delta0)): e^2 = k1/k2 (Walton & Braun 1986); for the power-law
  // variant both areas scale as F_max/(n+1) times their spans, ratio again k1/k2. Tolerance 1 %
  // (time discretisation at factor 0.01).
  for (double ratio : {1.5, 2.0, 4.0}) {
    for (double exponent : {1.0, 1.5}) {
      ContactParameters c;
      c.unloading_stiffness_ratio = ratio;
      c.stiffness_exponent = exponent;
      const double expected = 1.0 / std::sqrt(ratio);
      INFO("ratio " << ratio << " exponent " << exponent);
      CHECK(pair_impact(c, 0.2, 0.01).restitution == Approx(expected).epsilon(0.01));
      CHECK(wall_restitution(c, 0.1, 0.01) == Approx(expected).epsilon(0.01));
    }
  }
}

TEST_CASE("Plasticity: the largest overlap survives neighbour-list rebuilds during a contact", "[dem_core][effects]") {
  // A skin of 1e-7 m (0.01 % of R) makes the list rebuild about every step of the impact; the
  // restitution must still be 1/sqrt(ratio) (1 %), as without rebuilds.
  ContactParameters c;
  c.unloading_stiffness_ratio = 2.0;
  CHECK(pair_impact(c, 0.2, 0.01, 1e-7).restitution == Approx(1.0 / std::sqrt(2.0)).epsilon(0.01));
}

TEST_CASE("Cohesion: a sphere resting on a plane sinks to (m g + F_c)/k_wall with F_c = 1.5 pi gamma R",
          "[dem_core][effects]") {
  // Wall contact: R* = R, k_w = NORMK K R. gamma chosen so that F_c = 2 m g. Tolerance 0.2 %.
  ContactParameters c;
  const double weight = sphere_mass(kSphereRadius) * 9.81;
  c.surface_energy = 2.0 * weight / (1.5 * std::numbers::pi * kSphereRadius);
  const double k_wall = c.normk * kTestMaterial.bulk_modulus * kSphereRadius;
  const double f_c = 1.5 * std::numbers::pi * c.surface_energy * kSphereRadius;
  CHECK(resting_overlap(c, 9.81) == Approx((weight + f_c) / k_wall).epsilon(0.002));
}

TEST_CASE("Cohesion: a sphere hangs under a ceiling when F_c > m g and drops off when F_c < m g",
          "[dem_core][effects]") {
  // Ceiling plane z = 0 with normal -z, sphere below it, gravity -z. Hanging equilibrium needs
  // k_w delta = F_c - m g > 0 (overlap (F_c - m g)/k_w, tolerance 0.5 %); otherwise it falls.
  const double weight = sphere_mass(kSphereRadius) * 9.81;
  const double k_wall = 0.01 * kTestMaterial.bulk_modulus * kSphereRadius;
  for (double pull_over_weight : {1.0 / 0.9, 1.0 / 1.1}) {
    ContactParameters c;
    const double f_c = pull_over_weight * weight;
    c.surface_energy = f_c / (1.5 * std::numbers::pi * kSphereRadius);
    SimulationSettings settings;
    settings.contact = c;
    Simulation sim(settings);
    sim.add_material(kTestMaterial);
    WallSpec ceiling{PlaneGeometry{{0, 0, 0}, {0, 0, -1}}};
    ceiling.contact.damp = 0.5;
    sim.add_wall(ceiling);
    sim.add_particle({0, 0, -kSphereRadius + 0.5 * f_c / k_wall}, kSphereRadius);  // touching, at rest
    sim.run_until(0.05);
    const double overlap = kSphereRadius + sim.positions()[0].z;
    INFO("F_c / m g = " << pull_over_weight);
    if (f_c > weight)
      CHECK(overlap == Approx((f_c - weight) / k_wall).epsilon(0.005));
    else
      CHECK(overlap < -kSphereRadius);  // fell more than a radius away
  }
}

TEST_CASE("Cohesion: a pair separates only above the speed that pays the pull-off work F_c^2/(2 k_n)",
          "[dem_core][effects]") {
  // Free pair at its cohesive equilibrium delta_e = F_c/k_n (elastic push = pull-off force,
  // R* = R/2). Pulling the contact open from delta_e to 0 costs int (F_c - k delta) = F_c^2/(2k),
  // so the critical relative speed is v_c = F_c/sqrt(k m*) and a faster pair leaves with
  // sqrt(v^2 - v_c^2) (tolerance 1 %); a slower pair stays in contact (undamped, 10 periods).
  // The pull-off force drops to zero at zero overlap within one step, a work error of up to
  // F_c v dt: a small factor 0.001 keeps it below 0.5 % of F_c^2/(2k).
  ContactParameters c;
  c.surface_energy = 0.05;
  const double k = pair_stiffness(c);
  const double m_star = 0.5 * sphere_mass(kSphereRadius);
  const double f_c = 1.5 * std::numbers::pi * c.surface_energy * 0.5 * kSphereRadius;
  const double v_c = f_c / std::sqrt(k * m_star);
  const double period = 2.0 * std::numbers::pi * std::sqrt(m_star / k);
  for (double v_over_vc : {0.9, 1.1}) {
    SimulationSettings settings;
    settings.gravity = {0, 0, 0};
    settings.contact = c;
    settings.time_step_factor = 0.001;
    Simulation sim(settings);
    sim.add_material(kTestMaterial);
    const double gap = kSphereRadius - 0.5 * f_c / k;  // centres at 2R - delta_e
    const double v = v_over_vc * v_c;
    sim.add_particle({-gap, 0, 0}, kSphereRadius, 0, {-0.5 * v, 0, 0});
    sim.add_particle({gap, 0, 0}, kSphereRadius, 0, {0.5 * v, 0, 0});
    bool separated = false;
    while (sim.time() < 10.0 * period) {
      sim.step();
      separated = separated || sim.positions()[1].x - sim.positions()[0].x > 2.0 * kSphereRadius;
    }
    INFO("v / v_c = " << v_over_vc);
    if (v_over_vc < 1.0) {
      CHECK_FALSE(separated);
    } else {
      REQUIRE(separated);
      const double leaving = sim.velocities()[1].x - sim.velocities()[0].x;
      CHECK(leaving == Approx(std::sqrt(v * v - v_c * v_c)).epsilon(0.01));
    }
  }
}

TEST_CASE("Cohesion presses the surfaces together: a sphere that slides on a tilted plane without it sticks with it",
          "[dem_core][effects]") {
  // Gravity tilted by theta against the plane z = 0, wall FRICS mu, particle FRICS 0 (no
  // rotation, so the sphere can only slide). Coulomb limit mu x repulsive load = mu (m g cos +
  // F_c): with tan theta = 1.5 mu it slides without cohesion (acceleration g (sin - mu cos),
  // distance 1/2 a t^2, 2 %) and sticks with F_c = m g cos theta (limit 2 mu m g cos > m g sin).
  const double mu = 0.3, theta = std::atan(1.5 * mu), g = 9.81, t_end = 0.05;
  const double weight = sphere_mass(kSphereRadius) * g;
  for (bool cohesive : {false, true}) {
    SimulationSettings settings;
    settings.gravity = {g * std::sin(theta), 0, -g * std::cos(theta)};
    if (cohesive) settings.contact.surface_energy = weight * std::cos(theta) / (1.5 * std::numbers::pi * kSphereRadius);
    Simulation sim(settings);
    sim.add_material(kTestMaterial);
    WallSpec floor{PlaneGeometry{{0, 0, 0}, {0, 0, 1}}};
    floor.contact.frics = mu;
    floor.contact.damp = 0.5;
    sim.add_wall(floor);
    const double k_wall = 0.01 * kTestMaterial.bulk_modulus * kSphereRadius;
    const double load = weight * std::cos(theta) + (cohesive ? weight * std::cos(theta) : 0.0);
    sim.add_particle({0, 0, kSphereRadius - load / k_wall}, kSphereRadius);  // at its static overlap
    sim.run_until(t_end);
    const double travel = sim.positions()[0].x;
    INFO("cohesion " << cohesive << " travel " << travel);
    if (cohesive)
      CHECK(std::fabs(travel) < 1e-3 * kSphereRadius);
    else
      CHECK(travel == Approx(0.5 * g * (std::sin(theta) - mu * std::cos(theta)) * t_end * t_end).epsilon(0.02));
  }
}

TEST_CASE("Stiffness exponent: a resting sphere sinks to d_ref (m g/(k d_ref))^(1/n) with d_ref = 0.01 R",
          "[dem_core][effects]") {
  // Wall contact (R* = R): F = k d_ref (delta/d_ref)^n balances m g. Gravity 500 m/s^2 puts the
  // overlap well below d_ref, where the exponent matters (linear: m g/k). Tolerance 0.3 %.
  const double gravity = 500.0;
  const double k = 0.01 * kTestMaterial.bulk_modulus * kSphereRadius;
  const double d_ref = 0.01 * kSphereRadius;
  const double load = sphere_mass(kSphereRadius) * gravity;
  for (double n : {1.0, 1.5, 2.0}) {
    ContactParameters c;
    c.stiffness_exponent = n;
    INFO("exponent " << n);
    CHECK(resting_overlap(c, gravity) == Approx(d_ref * std::pow(load / (k * d_ref), 1.0 / n)).epsilon(0.003));
  }
}

TEST_CASE("Stiffness exponent: an elastic impact lasts 2 (delta_max/v) sqrt(pi) Gamma(1+1/p)/Gamma(1/2+1/p), p = n+1",
          "[dem_core][effects]") {
  // F = K delta^n with K = k d_ref^(1-n): energy conservation gives delta_max =
  // (p m* v^2/(2K))^(1/p) and the duration 2 int_0^dmax d delta / v(delta) in closed form (for
  // n = 1.5 this is Hertz's 2.94 delta_max/v). Restitution 1 (energy conserved): 0.5 %; duration 1 %.
  for (double n : {1.5, 2.0}) {
    ContactParameters c;
    c.stiffness_exponent = n;
    const double k = pair_stiffness(c);
    const double d_ref = 0.01 * 0.5 * kSphereRadius;  // R* = R/2
    const double big_k = k * std::pow(d_ref, 1.0 - n);
    const double m_star = 0.5 * sphere_mass(kSphereRadius);
    const double v = 0.2, p = n + 1.0;
    const double delta_max = std::pow(p * m_star * v * v / (2.0 * big_k), 1.0 / p);
    const double expected =
        2.0 * delta_max / v * std::sqrt(std::numbers::pi) * std::tgamma(1.0 + 1.0 / p) / std::tgamma(0.5 + 1.0 / p);
    const Impact impact = pair_impact(c, v, 0.01);
    INFO("exponent " << n << " delta_max/R " << delta_max / kSphereRadius);
    CHECK(impact.restitution == Approx(1.0).epsilon(0.005));
    CHECK(impact.duration == Approx(expected).epsilon(0.01));
  }
}

TEST_CASE(
    "Stiffness exponent and plasticity shrink the automatic step by the tangent stiffness at 5 % overlap, "
    "and a 5 % overlap impact stays energy-conserving at that step",
    "[dem_core][effects]") {
  // Undamped, no rotation: automatic step = 0.15 2 pi / omega_n, omega_n^2 = scale k_n/m*, scale =
  // ratio n (delta/d_ref)^(n-1) at delta = 5 % of R for a pair (delta/d_ref = 10).
  const ContactParameters plain;
  for (const auto& [ratio, n] : {std::pair{1.0, 1.5}, std::pair{2.0, 1.0}, std::pair{2.0, 1.5}}) {
    ContactParameters c;
    c.unloading_stiffness_ratio = ratio;
    c.stiffness_exponent = n;
    auto step_of = [](const ContactParameters& p) {
      SimulationSettings s;
      s.contact = p;
      Simulation sim(s);
      sim.add_material(kTestMaterial);
      sim.add_particle({0, 0, 0}, kSphereRadius);
      return sim.time_step();
    };
    const double scale = ratio * n * std::pow(10.0, n - 1.0);
    INFO("ratio " << ratio << " n " << n);
    CHECK(step_of(c) == Approx(step_of(plain) / std::sqrt(scale)).epsilon(1e-12));
  }
  // Impact reaching 5 % of R with n = 1.5 at the default factor 0.15: energy kept within 1 %.
  ContactParameters c;
  c.stiffness_exponent = 1.5;
  const double k = pair_stiffness(c), d_ref = 0.005 * kSphereRadius, m_star = 0.5 * sphere_mass(kSphereRadius);
  const double delta_max = 0.05 * kSphereRadius, p = 2.5;
  const double v = std::sqrt(2.0 * k * std::pow(d_ref, -0.5) * std::pow(delta_max, p) / (p * m_star));
  CHECK(pair_impact(c, v, 0.15).restitution == Approx(1.0).epsilon(0.01));
}

TEST_CASE("Effects at their off values give the plain LS-DYNA law's loads", "[dem_core][effects]") {
  // The simulation never uses the effects law with every effect off (it selects the plain law,
  // hence bit-identical results); the effects law itself must still agree with it (1e-13).
  ContactParameters p;
  p.ndamp = 0.3;
  p.tdamp = 0.2;
  p.frics = 0.4;
  p.fricr = 0.1;
  p.sheark = 0.3;
  CHECK_FALSE(p.effects_enabled());
  const LsDynaLinearLaw plain = LsDynaLinearLaw::for_pairs(p);
  const LsDynaEffectsLaw effects = LsDynaEffectsLaw::for_pairs(p);
  ContactGeometry g;
  g.normal = normalized(Vec3{1, 2, 2});
  g.overlap = 3e-6;
  g.contact_velocity = {0.01, -0.02, 0.005};
  g.relative_angular_velocity = {1.0, 0.0, -2.0};
  g.effective_mass = 5e-6;
  g.effective_radius = 0.5e-3;
  g.normal_compliance = 2e-4;
  g.inverse_inertia_sum = 1e9;
  LsDynaLinearLaw::History h1;
  LsDynaEffectsLaw::History h2;
  for (int step = 0; step < 5; ++step) {
    const ContactForce a = plain.force(g, h1, 1e-6);
    const ContactForce b = effects.force(g, h2, 1e-6);
    CHECK(norm(a.force - b.force) <= 1e-13 * norm(a.force));
    CHECK(norm(a.rolling_torque - b.rolling_torque) <= 1e-13 * norm(a.rolling_torque));
    CHECK(b.elastic_energy == Approx(a.elastic_energy).epsilon(1e-13));
    g.overlap += 1e-7;
  }
}
