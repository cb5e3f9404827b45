// Drum and pellet-bed scenarios for bench_dem.
#include "bench_scenarios.hpp"

#include <algorithm>
#include <chrono>
#include <ctime>
#include <cmath>
#include <numbers>

#include "demfit/dem_core/packing.hpp"

namespace demfit::bench {
using namespace dem_core;

namespace {
double now() { return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count(); }
}  // namespace

Simulation make_drum(double scale, double settle_time, int threads) {
  const double drum_radius = 0.05, length = 0.025, radius = 1.0e-3 * scale;
  SimulationSettings settings;
  settings.threads = threads;
  settings.gravity = {0, -9.81, 0};                                       // axis along z, gravity perpendicular
  settings.contact = {0.01, 0.0029, 0.5, 0.5, 0.3, -1.0, 0.0, 0.1, 1.0};  // Table 3 initial values
  Simulation sim(settings);
  sim.add_material({1.0e9, 2500.0, 0.3});
  const WallContactParameters wall{0.3, 0.3, 0.5, 1.0};
  const RotatingMotion still{{0, 0, 0}, {0, 0, 1}, 0.0};
  sim.add_wall({CylinderGeometry{{0, 0, 0}, {0, 0, 1}, drum_radius, length}, still, wall, {}, "shell"});
  sim.add_wall({DiskGeometry{{0, 0, 0}, {0, 0, 1}, drum_radius}, still, wall, {}, "front"});
  sim.add_wall({DiskGeometry{{0, 0, length}, {0, 0, -1}, drum_radius}, still, wall, {}, "back"});
  // Solid volume = 0.64 x 30 % of the drum; generated loosely in the lower 65 % and settled.
  const double drum_volume = std::numbers::pi * drum_radius * drum_radius * length;
  PackingRequest request;
  request.region =
      DrumSegmentRegion{{0, 0, 0}, {0, 0, 1}, drum_radius, length, {0, 1, 0}, drum_fill_height(drum_radius, 0.65)};
  request.radius_min = request.radius_max = radius;
  request.solid_volume = 0.64 * 0.3 * drum_volume;
  request.up = {0, 1, 0};
  request.gap = scale > 1.0 ? 0.01 : 0.08;  // few axial layers at s = 4: pack tighter
  add_packing(sim, generate_packing(request));
  sim.run_until(settle_time);
  for (std::size_t w = 0; w < 3; ++w) sim.set_wall_angular_velocity(w, 2.0 * std::numbers::pi);  // 60 RPM
  return sim;
}

Simulation make_pellet_bed(double normk, double sheark, double settle_time, int threads) {
  const double cylinder_radius = 0.018, radius = 1.86e-3;
  SimulationSettings settings;
  settings.threads = threads;
  settings.contact = {normk, sheark, 0.5, 0.5, 0.3, -1.0, 0.0, 0.1, 1.0};  // docs/spec.md 2.1 choices
  Simulation sim(settings);
  sim.add_material({1.767e9, 1000.0, 0.4});
  const WallContactParameters wall{0.3, 0.0, 0.5, 1.0};
  sim.add_wall({PlaneGeometry{{0, 0, 0}, {0, 0, 1}}, FixedMotion{}, wall, {}, "bottom"});
  sim.add_wall({CylinderGeometry{{0, 0, 0}, {0, 0, 1}, cylinder_radius, 0.3}, FixedMotion{}, wall, {}, "shell"});
  PackingRequest request;
  request.region = CylinderRegion{{0, 0, 0}, {0, 0, 1}, cylinder_radius, 0.3};
  request.radius_min = request.radius_max = radius;
  request.count = 1450;
  request.gap = 0.05;
  add_packing(sim, generate_packing(request));
  // Densified (frictionless) settling reaches phi ~ 0.60 and a 64 mm bed, as docs/spec.md 2.1 asks.
  settle(sim, {.max_time = settle_time, .frictionless = true});
  const double top = bed_height(sim, {0, 0, 1}, 0.01) + 0.2 * radius;
  sim.add_wall({DiskGeometry{{0, 0, top}, {0, 0, -1}, cylinder_radius}, FixedMotion{}, wall, {}, "piston"});
  return sim;
}

double cpu_seconds() { return static_cast<double>(std::clock()) / CLOCKS_PER_SEC; }

double time_steps(Simulation& sim, std::uint64_t steps, double* cpu) {
  const double start = now(), cpu_start = cpu_seconds();
  sim.run_steps(steps);
  if (cpu != nullptr) *cpu = cpu_seconds() - cpu_start;
  return now() - start;
}

double time_compression(Simulation& sim, double speed, double pressure, double& simulated, double& reached,
                        double* cpu) {
  const double area = std::numbers::pi * 0.018 * 0.018;
  sim.set_wall_velocity(2, {0, 0, -speed});
  const double t0 = sim.time(), start = now(), cpu_start = cpu_seconds();
  sim.run_until(
      sim.time() + 1.0, [&](Simulation& s) { return s.wall_force(2).z / area < pressure; }, 10);
  simulated = sim.time() - t0;
  reached = sim.wall_force(2).z / area;
  if (cpu != nullptr) *cpu = cpu_seconds() - cpu_start;
  return now() - start;
}

}  // namespace demfit::bench
