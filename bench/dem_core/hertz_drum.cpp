// The Hertz benchmark drum built with the public dem_core API.
#include "hertz_drum.hpp"

#include <numbers>

#include "demfit/dem_core/packing.hpp"

namespace demfit::bench {
using namespace dem_core;

SimulationSettings hertz_settings(const HertzDrumSpec& spec, int threads) {
  SimulationSettings settings;
  settings.law = ContactLawKind::hertz_mindlin;
  settings.threads = threads;
  settings.contact.restitution = spec.restitution;
  settings.contact.frics = spec.sliding_friction;
  settings.contact.fricr = spec.rolling_friction;
  settings.time_step = spec.time_step;
  settings.skin = spec.skin;
  // The bed is prepared in insertion order, as a run without reordering would hold it; the timed
  // default runs reorder at their first rebuild, the stored-order A/B keeps it.
  settings.reorder_particles = false;
  return settings;
}

void add_hertz_material(Simulation& sim, const HertzDrumSpec& spec) {
  // Material takes K; E = 3 K (1 - 2 nu).
  sim.add_material({spec.youngs_modulus / (3.0 * (1.0 - 2.0 * spec.poisson_ratio)), spec.density, spec.poisson_ratio});
}

WallContactParameters hertz_wall_contact(const HertzDrumSpec& spec) {
  WallContactParameters wall;
  wall.frics = spec.sliding_friction;
  wall.fricd = spec.rolling_friction;  // FRICD on a wall = rolling friction
  wall.youngs_modulus = spec.youngs_modulus;
  wall.poisson_ratio = spec.poisson_ratio;
  return wall;
}

Simulation make_hertz_drum(const HertzDrumSpec& spec, double settle_time, double spin_up_time, int threads) {
  SimulationSettings settings = hertz_settings(spec, threads);
  settings.gravity = {0.0, -spec.gravity, 0.0};
  Simulation sim(settings);
  add_hertz_material(sim, spec);
  const WallContactParameters wall = hertz_wall_contact(spec);
  const RotatingMotion still{{0, 0, 0}, {0, 0, 1}, 0.0};
  sim.add_wall({CylinderGeometry{{0, 0, 0}, {0, 0, 1}, spec.drum_radius, spec.depth}, still, wall, {}, "shell"});
  sim.add_wall({DiskGeometry{{0, 0, 0}, {0, 0, 1}, spec.drum_radius}, still, wall, {}, "front"});
  sim.add_wall({DiskGeometry{{0, 0, spec.depth}, {0, 0, -1}, spec.drum_radius}, still, wall, {}, "back"});
  PackingRequest request;
  request.region = DrumSegmentRegion{{0, 0, 0},  {0, 0, 1}, spec.drum_radius,
                                     spec.depth, {0, 1, 0}, drum_fill_height(spec.drum_radius, 0.65)};
  request.radius_min = request.radius_max = spec.radius;
  request.count = spec.particles;
  request.up = {0, 1, 0};
  request.gap = 0.08;
  add_packing(sim, generate_packing(request));
  sim.run_until(settle_time);
  for (std::size_t w = 0; w < 3; ++w)
    sim.set_wall_angular_velocity(w, 2.0 * std::numbers::pi * spec.revolutions_per_second);
  sim.run_until(sim.time() + spin_up_time);
  return sim;
}

double translational_kinetic_energy(const Simulation& sim) {
  double e = 0.0;
  for (std::size_t i = 0; i < sim.particle_count(); ++i) e += 0.5 * sim.masses()[i] * norm2(sim.velocities()[i]);
  return e;
}

Vec3 centre_of_mass(const Simulation& sim) {
  Vec3 sum{};
  double mass = 0.0;
  for (std::size_t i = 0; i < sim.particle_count(); ++i) {
    sum += sim.masses()[i] * sim.positions()[i];
    mass += sim.masses()[i];
  }
  return (1.0 / mass) * sum;
}

}  // namespace demfit::bench
