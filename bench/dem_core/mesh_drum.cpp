// Meshed against analytic Hertz drum (mesh_drum.hpp).
#include "mesh_drum.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <memory>
#include <numbers>
#include <sstream>
#include <vector>

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
  double cpu_seconds = 0.0;  ///< CPU time of the process over the steps (all threads)
  std::size_t list_builds = 0;
};

void print_run(const char* label, const RunFigures& f, std::uint64_t steps) {
  std::printf("  %storque %.5f N m, bed tilt %.2f deg, %.2f s (CPU %.2f s) for %llu steps (%zu list builds); %s\n",
              label, f.torque, f.tilt_degrees, f.seconds, f.cpu_seconds, static_cast<unsigned long long>(steps),
              f.list_builds, load_average().c_str());
}

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
    const std::clock_t cpu_start = std::clock();
    f.seconds += wall_seconds_for_steps(sim, chunk);
    f.cpu_seconds += static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC;
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
  // Runs alternate (analytic, meshed, analytic, ...) from the same restart, so a change of load
  // touches both sides; the median ratio is the figure.
  std::vector<double> wall_ratio, cpu_ratio;
  RunFigures a, m;
  for (int r = 0; r < std::max(1, o.repeats); ++r) {
    Simulation analytic = restart(settled, spec, nullptr, o.threads);
    a = measure(analytic, o.steps);
    print_run("analytic walls: ", a, o.steps);
    Simulation meshed = restart(settled, spec, mesh, o.threads);
    m = measure(meshed, o.steps);
    print_run("mesh wall:      ", m, o.steps);
    wall_ratio.push_back(m.seconds / a.seconds);
    cpu_ratio.push_back(m.cpu_seconds / a.cpu_seconds);
  }
  std::printf("  meshed/analytic (%d thread%s): torque %+.2f %% [target +-2 %%], tilt %+.2f deg [target +-1 deg], "
              "cost x%.2f [target <= 1.5] (CPU time x%.2f), medians of %zu\n",
              o.threads, o.threads == 1 ? "" : "s", 100.0 * (m.torque / a.torque - 1.0), m.tilt_degrees - a.tilt_degrees,
              median(wall_ratio), median(cpu_ratio), wall_ratio.size());
}

}  // namespace demfit::bench
