// Rotary drum (docs/spec.md 2.2, paper section 3): the cached fill (drum_powder.cpp), then rotation at
// the given speed; outputs the drive torque history and the free surface at the end time.
// Frame: drum axis = z (end walls at z = 0 and z = length), gravity -y.
#include "drum_case.hpp"
#include "drum_powder.hpp"

#include "demfit/cases/case_registry.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <optional>
#include <stdexcept>

#include "dem_setup.hpp"
#include "run_budget.hpp"
#include "demfit/cases/case_runner.hpp"
#include "demfit/cases/coarse_graining.hpp"
#include "demfit/cases/fill_cache.hpp"
#include "demfit/cases/bed_angles.hpp"
#include "demfit/cases/free_surface.hpp"
#include "demfit/dem_core/overlap_statistics.hpp"
#include "demfit/dem_core/packing.hpp"
#include "demfit/dem_core/simulation.hpp"
#include "demfit/imaging/occupancy.hpp"
#include "demfit/imaging/profile_metrics.hpp"
#include "demfit/imaging/surface.hpp"
#include "number_text.hpp"

namespace demfit::cases::detail {
namespace {

using dem_core::Vec3;
using Clock = std::chrono::steady_clock;

SurfaceProfile surface_now(const dem_core::Simulation& sim, const CaseSpec& spec) {
  std::vector<std::array<double, 3>> positions;
  for (const Vec3& p : sim.positions()) positions.push_back({p.x, p.y, p.z});
  const auto radii = sim.radii();
  const double rd = 0.5 * spec.drum.diameter;
  SurfaceOptions options{-rd, rd, static_cast<int>(spec.drum.surface_points), 0.1};
  return extract_free_surface(positions, std::vector<double>(radii.begin(), radii.end()), options);
}

// Image frame of the GranuDrum photos (imaging/surface.hpp: x right, z up, origin on the axis),
// as seen by a camera at the FRONT end wall (z = 0) looking along +z: x_image = -x, z_image = y.
// The drum turns counter-clockwise about +z (rpm > 0), which this camera sees as clockwise, with
// the bed lifted on the left (x_image < 0), as in the photos.
void add_image_snapshot(imaging::OccupancyAccumulator& image, const dem_core::Simulation& sim) {
  std::vector<double> x, z, r;
  x.reserve(sim.particle_count());
  z.reserve(sim.particle_count());
  for (std::size_t i = 0; i < sim.particle_count(); ++i) {
    x.push_back(-sim.positions()[i].x);
    z.push_back(sim.positions()[i].y);
    r.push_back(sim.radii()[i]);
  }
  image.add_snapshot(x, z, r);
}

// Walls of the rotation stage, all turning about the z axis at `omega` [rad/s]: the analytic
// shell and end disks (add_drum), or the one mesh wall of drum.wall_mesh (shell and both caps).
struct DrumWalls {
  std::size_t first = 0, count = 0;
};
DrumWalls add_rotating_drum(dem_core::Simulation& sim, const CaseSpec& spec, double omega) {
  const DrumSpec& d = spec.drum;
  if (!d.wall_mesh.enabled()) return {add_drum(sim, spec, omega), 3};
  const dem_core::RotatingMotion motion{{0, 0, 0}, {0, 0, 1}, omega};
  const dem_core::Axis axis{{0, 0, 0}, {0, 0, 1}};
  dem_core::MeshGeometry geometry;
  geometry.mesh = drum_wall_mesh(d.wall_mesh, d.diameter, d.length);
  return {sim.add_wall({geometry, motion, spec.wall, axis, "drum_mesh"}), 1};
}

struct RotationRun {
  std::vector<double> times, torques;
  SurfaceProfile surface;
  std::optional<imaging::SurfaceProfile> image_surface;
  CurveTable particles;
  double time_step = 0.0;
  std::uint64_t steps = 0;
  dem_core::OverlapStatistics overlaps{};  // at the end time
};

RotationRun rotate(const CaseSpec& spec, const Powder& powder, const Fill& fill, const CaseRunOptions& options) {
  dem_core::SimulationSettings settings = simulation_settings(spec);
  settings.gravity = {0.0, -9.81, 0.0};
  settings.threads = options.threads;
  settings.time_step = spec.time_step.value;
  settings.time_step_factor = spec.time_step.factor;
  dem_core::Simulation sim(settings);
  sim.add_material(powder_material(spec, powder));
  for (std::size_t i = 0; i < fill.radii.size(); ++i) {
    sim.add_particle({fill.positions[i][0], fill.positions[i][1], fill.positions[i][2]}, fill.radii[i]);
  }
  const double omega = spec.drum.rpm * 2.0 * std::numbers::pi / 60.0;
  const DrumWalls walls = add_rotating_drum(sim, spec, omega);
  check_user_time_step(spec, sim);
  RotationRun run;
  run.time_step = sim.time_step();
  const DrumSpec& d = spec.drum;
  const auto steps_per_sample =
      static_cast<std::uint64_t>(std::max(1.0, std::round(d.torque_interval / run.time_step)));
  std::vector<double> surface_times;
  for (long long k = 0; k < d.surface_snapshots; ++k) {
    const double f =
        d.surface_snapshots == 1 ? 1.0 : static_cast<double>(k) / static_cast<double>(d.surface_snapshots - 1);
    surface_times.push_back(d.duration - d.surface_window * (1.0 - f));
  }
  std::vector<SurfaceProfile> profiles;
  std::optional<imaging::OccupancyAccumulator> image;
  if (d.image.enabled) image.emplace(imaging::DrumFrame{d.diameter}, static_cast<int>(d.image.pixels));
  auto take_surface = [&](const dem_core::Simulation& s) {
    profiles.push_back(surface_now(s, spec));
    if (image) add_image_snapshot(*image, s);
  };
  SnapshotSchedule snapshots(spec.output.snapshot_times, options.snapshot_dir.string(), "drum");
  double torque_sum = 0.0;
  std::uint64_t in_sample = 0;
  // Drive torque: minus the moment the particles exert on the drum about its axis, signed with
  // the rotation direction, so a bed resisting the rotation gives a positive torque (Fig. 5).
  const double sense = omega >= 0.0 ? 1.0 : -1.0;
  std::uint64_t steps_done = 0;
  auto callback = [&](dem_core::Simulation& s) {
    // Progress at least every 256 steps (the printer throttles by wall time), also when a
    // torque sample spans millions of steps.
    if (options.progress && (++steps_done & 255u) == 0) options.progress("rotate", s.time(), d.duration);
    double drum_torque = 0.0;
    for (std::size_t w = walls.first; w < walls.first + walls.count; ++w) drum_torque += s.wall_torque(w);
    torque_sum -= sense * drum_torque;
    snapshots.maybe_write(s, s.time());
    while (profiles.size() < surface_times.size() && s.time() >= surface_times[profiles.size()] - 1e-12)
      take_surface(s);
    if (++in_sample >= steps_per_sample) {
      run.times.push_back(s.time());
      run.torques.push_back(torque_sum / static_cast<double>(in_sample));
      if (!std::isfinite(run.torques.back()))
        throw std::runtime_error("drum run diverged (non-finite torque): lower time_step.factor");
      torque_sum = 0.0;
      in_sample = 0;
      if (options.progress) options.progress("rotate", s.time(), d.duration);
    }
    return true;
  };
  sim.run_until(d.duration, callback, 1);
  while (profiles.size() < surface_times.size()) take_surface(sim);
  run.surface = average_profiles(profiles);
  if (image) {
    // The photo's own extraction on the averaged occupancy (material = covered > half the time).
    imaging::ProfileOptions photo;
    photo.margin = d.image.margin;
    photo.points = static_cast<int>(d.image.points);
    run.image_surface = imaging::extract_surface(image->occupancy(), imaging::DrumFrame{d.diameter},
                                                 imaging::occupancy_profile_options(photo));
  }
  run.steps = sim.step_count();
  run.overlaps = dem_core::pair_overlap_statistics(sim);
  run.particles = CurveTable{{"particle centres at the end time; drum axis z, gravity -y"},
                             {"x_mm", "y_mm", "z_mm", "radius_mm"},
                             std::vector<std::vector<double>>(4)};
  for (std::size_t i : sim.particles().indices_by_id()) {  // the table never shows memory order
    const Vec3 p = sim.positions()[i];
    const double v[4] = {p.x * 1e3, p.y * 1e3, p.z * 1e3, sim.radii()[i] * 1e3};
    for (int c = 0; c < 4; ++c) run.particles.values[c].push_back(v[c]);
  }
  return run;
}

// Dynamic repose angle [deg] of an image-frame profile: least-squares line through the points with
// |x| < half_width, angle -atan(slope), so a bed lifted on the left (the photos) is positive.
double image_surface_angle(const imaging::SurfaceProfile& profile, double half_width) {
  imaging::SurfaceProfile central;
  for (std::size_t k = 0; k < profile.x.size(); ++k) {
    if (std::fabs(profile.x[k]) >= half_width) continue;
    central.x.push_back(profile.x[k]);
    central.z.push_back(profile.z[k]);
  }
  if (central.x.size() < 2) return std::numeric_limits<double>::quiet_NaN();
  return -imaging::fit_surface_line(central).angle_deg;
}

// The final bed's angle by the slab and the instrument definitions (bed_angles.hpp), so a user
// compares like with like: LIGGGHTS dumps read by hand, or the GranuDrum's own number.
void add_bed_angles(std::vector<std::pair<std::string, std::string>>& summary, const CurveTable& particles_mm,
                    double drum_diameter, double drum_length) {
  std::vector<std::array<double, 3>> positions;
  std::vector<double> radii;
  for (std::size_t i = 0; i < particles_mm.values[3].size(); ++i) {
    positions.push_back({particles_mm.values[0][i] * 1e-3, particles_mm.values[1][i] * 1e-3,
                         particles_mm.values[2][i] * 1e-3});
    radii.push_back(particles_mm.values[3][i] * 1e-3);
  }
  const auto angle_text = [](double degrees) {
    return std::isfinite(degrees) ? fmt("%.2f", degrees) : std::string("not defined for this bed");
  };
  summary.emplace_back("dynamic angle of repose [deg] (" + std::string(kSlabSurfaceAngleName) + ", final bed)",
                       angle_text(slab_surface_angle_degrees(positions, radii, drum_length)));
  summary.emplace_back("dynamic angle of repose [deg] (" + std::string(kInstrumentAngleName) + ", final bed)",
                       angle_text(instrument_angle_degrees(positions, radii, drum_diameter, drum_length)));
}

}  // namespace

CaseResult run_rotary_drum(const CaseSpec& fill_spec, const CaseSpec& spec, const CaseRunOptions& options) {
  const auto start = Clock::now();
  bool generated = false;
  const Powder powder = powder_of(spec);
  precheck_user_time_step(spec, powder.particle.radius, powder.particle.density);
  {  // Before any work: the shell must not jump over contacts, and the run must fit the budget.
    const double time_step = planned_time_step(spec, powder.particle.radius, powder.particle.density);
    const double shell_speed = spec.drum.rpm * 2.0 * std::numbers::pi / 60.0 * 0.5 * spec.drum.diameter;
    check_wall_travel_per_step("drum.rpm", shell_speed, powder.particle.radius * (1.0 - spec.material.radius_spread),
                               time_step);
    check_run_budget("drum", static_cast<double>(powder.count), spec.drum.duration, time_step, options);
  }
  // A cached fill is used only with every particle inside the drum (frame: axis = z from 0 to length).
  const double drum_radius = 0.5 * fill_spec.drum.diameter, drum_length = fill_spec.drum.length;
  const auto inside_drum = [&](const Fill& f) {
    for (std::size_t i = 0; i < f.radii.size(); ++i) {
      const auto& p = f.positions[i];
      const double slack = 0.1 * f.radii[i];  // a settled contact overlaps the wall by ~1 % of a radius
      if (std::hypot(p[0], p[1]) + f.radii[i] > drum_radius + slack || p[2] - f.radii[i] < -slack ||
          p[2] + f.radii[i] > drum_length + slack)
        return false;
    }
    return true;
  };
  const Fill fill = cached_fill(
      options.cache_dir, "drum", fill_key(fill_spec), [&] { return pack_and_densify(fill_spec, options); }, &generated,
      inside_drum);
  const double fill_seconds = std::chrono::duration<double>(Clock::now() - start).count();
  const auto rotate_start = Clock::now();
  const RotationRun run = rotate(spec, powder, fill, options);
  const double rotate_seconds = std::chrono::duration<double>(Clock::now() - rotate_start).count();
  CaseResult result;
  constexpr CaseKind kind = CaseKind::rotary_drum;  // curve names and labels: case_registry.cpp
  identify::Curve torque = empty_curve(kind, "torque");
  torque.x = run.times;
  torque.y = run.torques;
  result.curves["torque"] = torque;
  identify::Curve surface = empty_curve(kind, "free_surface");
  for (std::size_t k = 0; k < run.surface.x.size(); ++k) {
    if (!std::isfinite(run.surface.height[k])) continue;
    surface.x.push_back(run.surface.x[k] * 1e3);
    surface.y.push_back(run.surface.height[k] * 1e3);
  }
  if (surface.x.size() < 2) throw std::runtime_error("drum: free surface not found (fewer than 2 points)");
  result.curves["free_surface"] = surface;
  if (run.image_surface) {
    identify::Curve image = empty_curve(kind, "free_surface_image");
    for (std::size_t k = 0; k < run.image_surface->x.size(); ++k) {
      image.x.push_back(run.image_surface->x[k] * 1e3);
      image.y.push_back(run.image_surface->z[k] * 1e3);
    }
    if (image.x.size() < 2) throw std::runtime_error("drum: image free surface not found (fewer than 2 points)");
    result.curves["free_surface_image"] = image;
  }
  result.tables["particles_end"] = run.particles;
  const double rd = 0.5 * spec.drum.diameter;
  double mean_torque = 0.0;
  int counted = 0;
  for (std::size_t i = 0; i < run.times.size(); ++i) {
    if (run.times[i] >= 0.5 * spec.drum.duration) {
      mean_torque += run.torques[i];
      ++counted;
    }
  }
  auto& sum = result.summary;
  sum.emplace_back("model", to_string(spec.drum.coarse_graining) + " s = " + fmt("%g", spec.drum.scale_factor));
  if (spec.law != dem_core::ContactLawKind::lsdyna_linear) sum.emplace_back("contact law", to_string(spec.law));
  sum.emplace_back("particles", std::to_string(fill.radii.size()));
  if (powder.radii.empty()) {
    sum.emplace_back("particle radius [mm]", fmt("%.4f", powder.particle.radius * 1e3));
  } else {
    double mean = 0.0;
    for (double r : fill.radii) mean += r;
    sum.emplace_back("original particles N0 (fill rule)", fmt("%.1f", powder.original_count));
    sum.emplace_back("mean particle radius [mm] (size distribution x coarse-graining factor)",
                     fmt("%.4f", mean / static_cast<double>(fill.radii.size()) * 1e3));
  }
  sum.emplace_back("particle density [kg/m3]", fmt("%.1f", powder.particle.density));
  double total_mass = 0.0;  // summed per particle: radii differ with a radius spread
  for (double r : fill.radii) total_mass += powder.particle.density * sphere_volume(r);
  sum.emplace_back("total particle mass [g]", fmt("%.3f", total_mass * 1e3));
  if (spec.drum.wall_mesh.enabled()) {
    const auto& m = spec.drum.wall_mesh;
    sum.emplace_back("drum wall", m.source == DrumWallMeshSpec::Source::stl
                                      ? "mesh " + m.stl + " (" + std::to_string(m.stl_triangles.size()) + " triangles)"
                                      : "generated mesh, " + std::to_string(m.segments) + " segments, " +
                                            std::to_string(m.shell_rings) + " shell rings, " +
                                            std::to_string(m.cap_rings) + " cap rings");
  }
  sum.emplace_back("fill", generated ? "generated and cached" : "read from cache");
  sum.emplace_back("fill wall time [s]", fmt("%.1f", fill_seconds));
  sum.emplace_back("dynamic angle of repose [deg] (" + std::string(kClusterSurfaceAngleName) + ")",
                   fmt("%.2f", repose_angle_degrees(run.surface, -0.5 * rd, 0.5 * rd)));
  add_bed_angles(sum, run.particles, spec.drum.diameter, spec.drum.length);
  sum.emplace_back("mean drive torque, second half [N m]", fmt("%.5f", counted ? mean_torque / counted : 0.0));
  if (run.image_surface) {
    sum.emplace_back(
        "surface_angle_deg (dynamic repose angle of free_surface_image, line fit over |x| < R/2; positive = lifted at "
        "x < 0)",
        fmt("%.2f", image_surface_angle(*run.image_surface, 0.5 * rd)));
  }
  sum.emplace_back(kParticleOverlapLabel, fmt("%.2f", 100.0 * run.overlaps.mean_relative_overlap) + " / " +
                                              fmt("%.2f", 100.0 * run.overlaps.max_relative_overlap));
  sum.emplace_back("time step [s]", fmt("%.3e", run.time_step));
  sum.emplace_back("rotation steps", std::to_string(run.steps));
  sum.emplace_back("rotation wall time [s] (one evaluation)", fmt("%.1f", rotate_seconds));
  return result;
}

}  // namespace demfit::cases::detail
