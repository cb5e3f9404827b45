// Meshed against analytic Hertz drum (mesh_drum.hpp).
#include "mesh_drum.hpp"

#include <cmath>
#include <cstdio>
#include <memory>
#include <numbers>
#include <sstream>

#include "bench_timing.hpp"
#include "demfit/dem_core/stl_mesh.hpp"
#include "drum_mesh.hpp"
#include "hertz_drum.hpp"

namespace demfit::bench {
namespace {
using namespace dem_core;

struct RunFigures {
  double torque = 0.0;       ///< mean over the steps of the walls' summed torque about +z [N m]
  double tilt_degrees = 0.0;  ///< mean bed tilt: angle of the centre of mass from straight below the axis
  double seconds = 0.0;      ///< wall-clock time of the steps
  std::size_t list_builds = 0;
};

}  // namespace

Simulation restart_drum(const Simulation& from, const HertzDrumSpec& spec, const SimulationSettings& settings,
                        const std::shared_ptr<const TriangleMesh>& mesh) {
  Simulation sim(settings);
  add_hertz_material(sim, spec);
  const RotatingMotion turning{{0, 0, 0}, {0, 0, 1}, 2.0 * std::numbers::pi * spec.revolutions_per_second};
  const WallContactParameters contact = hertz_wall_contact(spec);
  if (mesh) {
    sim.add_wall({MeshGeometry{mesh}, turning, contact, {}, "drum mesh"});
  } else {
    sim.add_wall({CylinderGeometry{{0, 0, 0}, {0, 0, 1}, spec.drum_radius, spec.depth}, turning, contact, {}, "shell"});
    sim.add_wall({DiskGeometry{{0, 0, 0}, {0, 0, 1}, spec.drum_radius}, turning, contact, {}, "front"});
    sim.add_wall({DiskGeometry{{0, 0, spec.depth}, {0, 0, -1}, spec.drum_radius}, turning, contact, {}, "back"});
  }
  for (std::size_t i = 0; i < from.particle_count(); ++i)
    sim.add_particle(from.positions()[i], from.radii()[i], 0, from.velocities()[i], from.angular_velocities()[i]);
  return sim;
}

SimulationSettings drum_restart_settings(const HertzDrumSpec& spec, int threads) {
  SimulationSettings settings = hertz_settings(spec, threads);
  settings.gravity = {0.0, -spec.gravity, 0.0};
  return settings;
}

namespace {

Simulation restart(const Simulation& from, const HertzDrumSpec& spec, const std::shared_ptr<const TriangleMesh>& mesh,
                   int threads) {
  return restart_drum(from, spec, drum_restart_settings(spec, threads), mesh);
}

RunFigures measure(Simulation& sim, std::uint64_t steps) {
  RunFigures f;
  sim.run_steps(10);  // histories rebuilt, first list built: not timed
  const std::size_t builds = sim.neighbor_list().build_count();
  const std::uint64_t chunk = 50;
  for (std::uint64_t done = 0; done < steps; done += chunk) {
    f.seconds += wall_seconds_for_steps(sim, chunk);
    double torque = 0.0;
    for (std::size_t w = 0; w < sim.wall_count(); ++w) torque += sim.wall_torque(w);
    const Vec3 c = centre_of_mass(sim);
    f.torque += torque;
    f.tilt_degrees += std::atan2(c.x, -c.y) * 180.0 / std::numbers::pi;
  }
  f.list_builds = sim.neighbor_list().build_count() - builds;
  const double samples = static_cast<double>((steps + chunk - 1) / chunk);
  f.torque /= samples;
  f.tilt_degrees /= samples;
  return f;
}

}  // namespace

void compare_meshed_drum(const MeshDrumOptions& o) {
  const HertzDrumSpec spec;
  std::ostringstream stl;
  const std::size_t written =
      write_drum_stl(stl, {spec.drum_radius, spec.depth, 0.0, o.segments, o.shell_rings, o.cap_rings});
  const auto mesh = std::make_shared<const TriangleMesh>(parse_stl(stl.str(), {1.0}, "drum mesh"));
  std::printf("meshed drum: %zu triangles (%d segments, %d shell rings, %d cap rings), %zu contact cells; %s\n",
              written, o.segments, o.shell_rings, o.cap_rings, mesh->cell_count(), load_average().c_str());
  const Simulation settled = make_hertz_drum(spec, o.settle_time, o.spin_up_time, o.threads);
  std::printf("  settled %.2f s + spun up %.2f s with the analytic walls; %s\n", o.settle_time, o.spin_up_time,
              load_average().c_str());
  Simulation analytic = restart(settled, spec, nullptr, o.threads);
  const RunFigures a = measure(analytic, o.steps);
  std::printf("  analytic walls: torque %.5f N m, bed tilt %.2f deg, %.2f s for %llu steps (%zu list builds); %s\n",
              a.torque, a.tilt_degrees, a.seconds, static_cast<unsigned long long>(o.steps), a.list_builds,
              load_average().c_str());
  Simulation meshed = restart(settled, spec, mesh, o.threads);
  const RunFigures m = measure(meshed, o.steps);
  std::printf("  mesh wall:      torque %.5f N m, bed tilt %.2f deg, %.2f s for %llu steps (%zu list builds); %s\n",
              m.torque, m.tilt_degrees, m.seconds, static_cast<unsigned long long>(o.steps), m.list_builds,
              load_average().c_str());
  std::printf("  meshed/analytic: torque %+.2f %% [target +-2 %%], tilt %+.2f deg [target +-1 deg], cost x%.2f "
              "[target <= 1.5]\n",
              100.0 * (m.torque / a.torque - 1.0), m.tilt_degrees - a.tilt_degrees, m.seconds / a.seconds);
}

}  // namespace demfit::bench
