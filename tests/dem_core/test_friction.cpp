// Sliding and rolling friction against rigid-body mechanics.
#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>

#include "demfit/dem_core/simulation.hpp"
#include "test_particles.hpp"

using namespace demfit::dem_core;
using namespace demfit::dem_core::test;

namespace {

/// A sphere resting (at its static overlap) on the plane z = 0.
Simulation sphere_on_plane(const WallContactParameters& wall, const Vec3& velocity, const Vec3& spin) {
  SimulationSettings settings;
  settings.gravity = {0, 0, -kGravity};
  settings.contact.frics = 0.5;  // > 0 so that rotation is enabled (FRICS = 0 freezes rotation)
  Simulation sim(settings);
  sim.add_material(kTestMaterial);
  WallSpec plane{PlaneGeometry{{0, 0, 0}, {0, 0, 1}}};
  plane.contact = wall;
  sim.add_wall(plane);
  const double k = 0.01 * kTestMaterial.bulk_modulus * kSphereRadius;  // wall spring NORMK K R
  sim.add_particle({0, 0, kSphereRadius - sphere_mass(kSphereRadius) * kGravity / k}, kSphereRadius, 0, velocity, spin);
  return sim;
}

}  // namespace

TEST_CASE("A sphere launched sliding decelerates at mu g and rolls at 5/7 of its launch speed",
          "[dem_core][friction]") {
  const double mu = 0.3, v0 = 1.0;
  WallContactParameters wall;
  wall.frics = mu;
  wall.damp = 0.3;  // damps the stick oscillation; the sliding force stays limited to mu |F_n|
  Simulation sim = sphere_on_plane(wall, {v0, 0, 0}, {});
  // Rigid body: sliding ends at t* = 2 v0 / (7 mu g); then v = 5/7 v0 (no rolling friction).
  const double t_star = 2.0 * v0 / (7.0 * mu * kGravity);
  sim.run_until(0.5 * t_star);
  const double deceleration = (v0 - sim.velocities()[0].x) / sim.time();
  sim.run_until(3.0 * t_star);
  const double rolling_speed = sim.velocities()[0].x;
  const double spin = sim.angular_velocities()[0].y;
  INFO("deceleration " << deceleration << " expected " << mu * kGravity << "; rolling speed " << rolling_speed);
  CHECK(deceleration == Approx(mu * kGravity).epsilon(0.01));    // 1 %
  CHECK(rolling_speed == Approx(5.0 / 7.0 * v0).epsilon(0.01));  // 1 %
  CHECK(spin * kSphereRadius == Approx(rolling_speed).epsilon(0.01));  // rolling without slip
}

TEST_CASE("Wall rolling friction (wall FRICD) decelerates a rolling sphere at 5/7 mu_r g", "[dem_core][friction]") {
  // Constant torque M = mu_r m g R opposing the spin; rolling without slip: (m + I/R^2) a = -M/R
  // with I = 2/5 m R^2 gives a = -5/7 mu_r g.
  const double mu_r = 0.05, v0 = 0.5;
  WallContactParameters wall;
  wall.frics = 0.5;  // enough to keep rolling without slip (needs 2/7 mu_r)
  wall.fricd = mu_r;
  wall.damp = 0.3;
  Simulation sim = sphere_on_plane(wall, {v0, 0, 0}, {0, v0 / kSphereRadius, 0});
  const double expected = 5.0 / 7.0 * mu_r * kGravity;
  sim.run_until(0.05);
  const double v1 = sim.velocities()[0].x, t1 = sim.time();
  sim.run_until(0.10);
  const double v2 = sim.velocities()[0].x, t2 = sim.time();
  const double deceleration = (v1 - v2) / (t2 - t1);
  INFO("deceleration " << deceleration << " expected " << expected);
  CHECK(deceleration == Approx(expected).epsilon(0.01));
  // It stops (the limiter prevents reversing the spin) and stays put.
  sim.run_until(v0 / expected + 0.05);
  CHECK(std::fabs(sim.velocities()[0].x) < 1e-3 * v0);
}

TEST_CASE("Particle-particle rolling friction (FRICR) decelerates the relative spin at mu_r F_n R* (1/I_i + 1/I_j)",
          "[dem_core][friction]") {
  // Sphere A balanced on sphere B, B on a frictionless plane; A spins about the vertical (the
  // contact normal), so only the rolling-resistance torque acts: M = FRICR |F_n| R*, F_n = m_A g.
  const double mu_r = 0.1, spin0 = 200.0;
  SimulationSettings settings;
  settings.gravity = {0, 0, -kGravity};
  settings.contact.frics = 0.5;
  settings.contact.fricr = mu_r;
  settings.contact.ndamp = 0.5;
  Simulation sim(settings);
  sim.add_material(kTestMaterial);
  WallSpec plane{PlaneGeometry{{0, 0, 0}, {0, 0, 1}}};
  plane.contact.damp = 0.5;
  sim.add_wall(plane);
  const double m = sphere_mass(kSphereRadius);
  const double k = 0.01 * kTestMaterial.bulk_modulus * kSphereRadius;
  const double z_b = kSphereRadius - 2.0 * m * kGravity / k;              // wall spring carries both weights
  const double z_a = z_b + 2.0 * kSphereRadius - m * kGravity / (k / 2);  // pair spring k/2 carries A
  sim.add_particle({0, 0, z_b}, kSphereRadius);
  sim.add_particle({0, 0, z_a}, kSphereRadius, 0, {}, {0, 0, spin0});
  const double inertia = 0.4 * m * kSphereRadius * kSphereRadius;
  const double expected = mu_r * m * kGravity * (kSphereRadius / 2) * (2.0 / inertia);  // d(omega_A - omega_B)/dt
  sim.run_until(0.01);
  const double w1 = sim.angular_velocities()[1].z - sim.angular_velocities()[0].z, t1 = sim.time();
  sim.run_until(0.03);
  const double w2 = sim.angular_velocities()[1].z - sim.angular_velocities()[0].z, t2 = sim.time();
  const double deceleration = (w1 - w2) / (t2 - t1);
  INFO("relative spin deceleration " << deceleration << " expected " << expected);
  CHECK(deceleration == Approx(expected).epsilon(0.01));
}

TEST_CASE("Hertz-Mindlin law: a sliding sphere also decelerates at mu g and rolls at 5/7 v0", "[dem_core][friction]") {
  // Same rigid-body result as for the linear law; only the springs differ (Hertz/Mindlin).
  const double mu = 0.3, v0 = 1.0;
  SimulationSettings settings;
  settings.law = ContactLawKind::hertz_mindlin;
  settings.gravity = {0, 0, -kGravity};
  settings.contact.frics = 0.5;
  settings.contact.restitution = 0.3;
  Simulation sim(settings);
  sim.add_material(kTestMaterial);
  WallSpec plane{PlaneGeometry{{0, 0, 0}, {0, 0, 1}}};
  plane.contact.frics = mu;
  sim.add_wall(plane);
  // Hertz static overlap on a rigid plane: m g = 4/3 E* sqrt(R) delta^{3/2}, E* = E/(1-nu^2).
  const double e_star = 3.0 * kTestMaterial.bulk_modulus * (1.0 - 2.0 * kTestMaterial.poisson_ratio) /
                        (1.0 - kTestMaterial.poisson_ratio * kTestMaterial.poisson_ratio);
  const double delta =
      std::pow(3.0 * sphere_mass(kSphereRadius) * kGravity / (4.0 * e_star * std::sqrt(kSphereRadius)), 2.0 / 3.0);
  sim.add_particle({0, 0, kSphereRadius - delta}, kSphereRadius, 0, {v0, 0, 0});
  const double t_star = 2.0 * v0 / (7.0 * mu * kGravity);
  sim.run_until(0.5 * t_star);
  const double deceleration = (v0 - sim.velocities()[0].x) / sim.time();
  sim.run_until(3.0 * t_star);
  INFO("deceleration " << deceleration << " rolling speed " << sim.velocities()[0].x);
  CHECK(deceleration == Approx(mu * kGravity).epsilon(0.01));
  CHECK(sim.velocities()[0].x == Approx(5.0 / 7.0 * v0).epsilon(0.01));
}
