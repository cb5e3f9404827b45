#pragma once
// The Hertz–Mindlin rotating drum that bench_dem times in demfit and in LIGGGHTS:
// inner diameter 100 mm x depth 20 mm, 6,996 spheres of radius 1 mm, E 5 MPa, nu 0.3,
// rho 2500 kg/m^3, restitution 0.5, sliding friction 0.4, rolling friction 0.1 (particles and
// walls alike; the walls have the particles' elastic constants, as LIGGGHTS' mesh of atom type 1),
// 60 RPM about +z, gravity -y, dt 1e-5 s, neighbour skin 0.5 mm.
#include <cstddef>

#include "demfit/dem_core/simulation.hpp"

namespace demfit::bench {

struct HertzDrumSpec {
  double drum_radius = 0.05;  ///< [m]
  double depth = 0.02;        ///< [m] (axial length, z from 0 to depth)
  double radius = 1.0e-3;     ///< particle radius [m]
  std::size_t particles = 6996;
  double youngs_modulus = 5.0e6;  ///< [Pa]
  double poisson_ratio = 0.3;
  double density = 2500.0;  ///< [kg/m^3]
  double restitution = 0.5;
  double sliding_friction = 0.4;
  double rolling_friction = 0.1;
  double revolutions_per_second = 1.0;  ///< 60 RPM
  double gravity = 9.81;                ///< [m/s^2] along -y
  double time_step = 1.0e-5;            ///< [s]
  double skin = 0.5e-3;                 ///< [m]
};

/// The spec's contact law, friction, time step and skin (gravity left at its default), and the
/// spec's material added to a simulation: shared by the drum and the scaling box.
dem_core::SimulationSettings hertz_settings(const HertzDrumSpec& spec, int threads);
void add_hertz_material(dem_core::Simulation& sim, const HertzDrumSpec& spec);
/// The walls' contact parameters: the particles' friction, rolling friction and elastic constants.
dem_core::WallContactParameters hertz_wall_contact(const HertzDrumSpec& spec);

/// The drum filled (seeded lattice packing in the lower part), settled for `settle_time` [s] with
/// the drum at rest, then turned at the spec's speed for `spin_up_time` [s] so that the flow is
/// steady. Walls: 0 = shell, 1 = front disk (z = 0), 2 = back disk (z = depth), all rotating.
dem_core::Simulation make_hertz_drum(const HertzDrumSpec& spec, double settle_time, double spin_up_time, int threads);

/// Translational kinetic energy sum 1/2 m v^2 [J] (what LIGGGHTS' thermo `ke` reports).
double translational_kinetic_energy(const dem_core::Simulation& sim);
/// Centre of mass [m].
dem_core::Vec3 centre_of_mass(const dem_core::Simulation& sim);

}  // namespace demfit::bench
