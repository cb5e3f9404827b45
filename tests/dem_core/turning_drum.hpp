#pragma once
// The small turning drum of the reordering and pair-load-order tests: a frictional, rolling,
// damped bed of 200 spheres (R 0.6-0.8 mm) poured into a drum of R 12 mm x 8 mm that turns at
// 3 rad/s about z, gravity -y, with a thin skin (0.1 mm) so the list is rebuilt often while
// contacts persist across rebuilds.
#include <random>
#include <utility>

#include "demfit/dem_core/packing.hpp"
#include "demfit/dem_core/simulation.hpp"

namespace demfit::dem_core::testing {

/// `settings` gives the threads and the kernel's orders; the contact law and skin are set here.
/// `shuffled`: the particles are added in a random order (neighbours in space far apart in memory).
inline Simulation turning_drum(SimulationSettings settings, bool shuffled = false) {
  settings.contact = {0.01, 2.0 / 7.0, 0.3, 0.3, 0.4, 0.3, 1.0, 0.05, 1.0};
  settings.skin = 0.1e-3;
  Simulation sim(settings);
  sim.add_material({1.0e9, 2500.0, 0.3});
  const double radius = 0.012, length = 0.008;
  const RotatingMotion turning{{0, 0, 0}, {0, 0, 1}, 3.0};
  const WallContactParameters wall{0.4, 0.05, 0.3, 1.0};
  sim.add_wall({CylinderGeometry{{0, 0, 0}, {0, 0, 1}, radius, length}, turning, wall});
  sim.add_wall({DiskGeometry{{0, 0, 0}, {0, 0, 1}, radius}, turning, wall});
  sim.add_wall({DiskGeometry{{0, 0, length}, {0, 0, -1}, radius}, turning, wall});
  sim.set_gravity({0, -9.81, 0});
  PackingRequest request;
  request.region = DrumSegmentRegion{{0, 0, 0}, {0, 0, 1}, radius, length, {0, 1, 0}, 0.0};
  request.up = {0, 1, 0};
  request.gap = 0.02;
  request.radius_min = 0.6e-3;
  request.radius_max = 0.8e-3;
  request.count = 200;
  request.seed = 5;
  Packing packing = generate_packing(request);
  if (shuffled) {
    std::mt19937_64 random(3);
    for (std::size_t n = packing.centers.size(); n > 1; --n) {
      const std::size_t k = random() % n;
      std::swap(packing.centers[n - 1], packing.centers[k]);
      std::swap(packing.radii[n - 1], packing.radii[k]);
    }
  }
  add_packing(sim, packing);
  return sim;
}

}  // namespace demfit::dem_core::testing
