// Particle–wall law: static overlaps from the springs in series, wall force and wall torque
// against statics.
#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>

#include "demfit/dem_core/packing.hpp"
#include "demfit/dem_core/simulation.hpp"
#include "test_particles.hpp"

using namespace demfit::dem_core;
using namespace demfit::dem_core::test;

namespace {

/// Moment of the particles' weight about an axis: sum (x_i - a) x m_i g · u.
double weight_moment(const Simulation& sim, const Axis& axis) {
  double m = 0.0;
  for (std::size_t i = 0; i < sim.particle_count(); ++i)
    m += dot(cross(sim.positions()[i] - axis.point, sim.masses()[i] * sim.settings().gravity), axis.direction);
  return m;
}

}  // namespace

TEST_CASE("A sphere resting on a slowly rotating drum wall: overlap m g cos(theta)/k_w and torque = weight moment",
          "[dem_core][walls]") {
  // Drum axis along y through the origin, gravity -z. The sphere sticks to the shell (wall FRICS
  // 0.8 > tan theta) and rolling friction wall FRICD 0.6 > tan theta stops it rolling, so it rides
  // with the drum. Statics: wall normal force m g cos(theta) = k_w delta with k_w = SFP NORMK K R;
  // the wall's torque about the axis equals the moment of the weight (exact in equilibrium, see
  // the couple argument in Simulation::reduce_diagnostics).
  const double r = 2.0e-3, drum_radius = 0.05, omega = 0.1;
  SimulationSettings settings;
  settings.gravity = {0, 0, -kGravity};
  settings.contact.frics = 0.5;
  Simulation sim(settings);
  sim.add_material(kTestMaterial);
  WallSpec shell{CylinderGeometry{{0, -0.01, 0}, {0, 1, 0}, drum_radius, 0.02}};
  shell.motion = RotatingMotion{{0, 0, 0}, {0, 1, 0}, omega};
  shell.contact = {0.8, 0.6, 0.5, 1.0};
  const std::size_t drum = sim.add_wall(shell);
  const double theta0 = 10.0 * std::numbers::pi / 180.0;
  const double k_w = 0.01 * kTestMaterial.bulk_modulus * r;
  const double delta0 = sphere_mass(r) * kGravity * std::cos(theta0) / k_w;
  const double rc = drum_radius - r + delta0;
  // Rotation +omega about +y carries a point at angle theta (from -z towards -x) upwards.
  sim.add_particle({-rc * std::sin(theta0), 0, -rc * std::cos(theta0)}, r);
  sim.run_until(1.0);
  const Vec3 x = sim.positions()[0];
  const double theta = std::atan2(-x.x, -x.z);
  const double overlap = r - (drum_radius - norm(Vec3{x.x, 0, x.z}));
  const double expected_overlap = sphere_mass(r) * kGravity * std::cos(theta) / k_w;
  INFO("theta " << theta << " overlap " << overlap << " expected " << expected_overlap);
  CHECK(theta == Approx(theta0 + omega * sim.time()).epsilon(0.02));
  CHECK(overlap == Approx(expected_overlap).epsilon(0.005));
  const double moment = weight_moment(sim, sim.wall(drum).torque_axis);
  INFO("torque " << sim.wall_torque(drum) << " weight moment " << moment);
  CHECK(sim.wall_torque(drum) == Approx(moment).epsilon(0.005));
}

TEST_CASE("A piston pushing a column of spheres feels the springs in series", "[dem_core][walls]") {
  // N spheres on the z axis between a bottom plane and a piston disk, no gravity. After the
  // piston advanced by D: F = D / (2/k_w + (N-1)/k_n), k_w = NORMK K R, k_n = k_w/2.
  const int n = 5;
  const double r = 1.0e-3, travel = 1.0e-5;
  SimulationSettings settings;
  settings.gravity = {0, 0, 0};
  settings.contact.ndamp = 0.5;
  Simulation sim(settings);
  sim.add_material(kTestMaterial);
  WallSpec bottom{PlaneGeometry{{0, 0, 0}, {0, 0, 1}}};
  bottom.contact.damp = 0.5;
  const std::size_t floor = sim.add_wall(bottom);
  WallSpec piston{DiskGeometry{{0, 0, 2.0 * r * n}, {0, 0, -1}, 3.0 * r}};
  piston.contact.damp = 0.5;
  const std::size_t top = sim.add_wall(piston);
  for (int i = 0; i < n; ++i) sim.add_particle({0, 0, r + 2.0 * r * i}, r);
  const double speed = 2.5e-4;
  sim.set_wall_velocity(top, {0, 0, -speed});
  sim.run_until(travel / speed);
  sim.set_wall_motion(top, FixedMotion{});
  sim.run_until(sim.time() + 0.05);
  const double advanced = -sim.wall(top).displacement.z;
  const double k_w = 0.01 * kTestMaterial.bulk_modulus * r;
  const double expected = advanced / (2.0 / k_w + (n - 1) / (k_w / 2.0));
  INFO("piston force " << sim.wall_force(top).z << " bottom " << sim.wall_force(floor).z << " expected " << expected);
  CHECK(advanced == Approx(travel).epsilon(0.01));
  CHECK(sim.wall_force(top).z == Approx(expected).epsilon(0.005));
  CHECK(-sim.wall_force(floor).z == Approx(expected).epsilon(0.005));
}

TEST_CASE("A bed in a slowly rotating drum loads the drum with the moment of its weight (time average, 3 %)",
          "[dem_core][walls]") {
  // Whole-bed moment balance about the axis: torque of the walls on the bed + weight moment =
  // dL/dt; averaged over a quasi-steady window dL/dt ~ 0, so <wall torque> = <weight moment>.
  const double r = 2.0e-3, drum_radius = 0.03, length = 0.012, omega = 0.5;
  SimulationSettings settings;
  settings.gravity = {0, 0, -kGravity};
  settings.contact = {0.01, 2.0 / 7.0, 0.5, 0.5, 0.5, -1.0, 0.0, 0.1, 1.0};
  Simulation sim(settings);
  sim.add_material(kTestMaterial);
  const Axis axis{{0, 0, 0}, {0, 1, 0}};
  const RotatingMotion rotation{axis.point, axis.direction, omega};
  const WallContactParameters wall_contact{0.5, 0.1, 0.5, 1.0};
  WallSpec shell{CylinderGeometry{{0, 0, 0}, {0, 1, 0}, drum_radius, length}, rotation, wall_contact};
  WallSpec front{DiskGeometry{{0, 0, 0}, {0, 1, 0}, drum_radius}, rotation, wall_contact};
  WallSpec back{DiskGeometry{{0, length, 0}, {0, -1, 0}, drum_radius}, rotation, wall_contact};
  const std::size_t walls[3] = {sim.add_wall(shell), sim.add_wall(front), sim.add_wall(back)};
  PackingRequest request;
  request.region = DrumSegmentRegion{{0, 0, 0}, {0, 1, 0}, drum_radius, length, {0, 0, 1}, 0.02};
  request.radius_min = request.radius_max = r;
  request.count = 120;
  request.gap = 0.05;
  add_packing(sim, generate_packing(request));
  sim.run_until(1.0);  // settle and develop the inclined bed
  double torque = 0.0, moment = 0.0;
  int samples = 0;
  sim.run_until(2.0, [&](Simulation& s) {
    for (std::size_t w : walls) torque += s.wall_torque(w);
    moment += weight_moment(s, axis);
    ++samples;
    return true;
  });
  torque /= samples;
  moment /= samples;
  INFO("mean torque " << torque << " mean weight moment " << moment);
  CHECK(std::fabs(moment) > 1e-4);  // the bed is really inclined
  CHECK(torque == Approx(moment).epsilon(0.03));
}
