// Rotary drum (SPEC 2.2, paper section 3): packed generation of the (coarse-grained) powder in
// the lower part of a horizontal drum, densification under gravity (cached), then rotation at
// the given speed; outputs the drive torque history and the free surface at the end time.
// Frame: drum axis = z (end walls at z = 0 and z = length), gravity -y.
#include "drum_case.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <optional>
#include <random>
#include <stdexcept>

#include "dem_setup.hpp"
#include "demfit/cases/coarse_graining.hpp"
#include "demfit/cases/fill_cache.hpp"
#include "demfit/cases/free_surface.hpp"
#include "demfit/dem_core/packing.hpp"
#include "demfit/dem_core/simulation.hpp"

namespace demfit::cases::detail {
namespace {

using dem_core::Vec3;
using Clock = std::chrono::steady_clock;

std::string fmt(const char* pattern, double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, pattern, value);
  return buffer;
}

struct Powder {
  CoarseParticle particle;
  long long count = 0;
  double original_total_mass = 0.0;  // M0 [kg]
};

// Table 2 applied to the drum fill: the original powder's solid volume is phi times the bulk
// fill (fill_fraction of the drum volume); the coarse model carries its Table 2 total mass.
Powder powder_of(const CaseSpec& spec) {
  const DrumSpec& d = spec.drum;
  const double drum_volume = std::numbers::pi * 0.25 * d.diameter * d.diameter * d.length;
  Powder p;
  p.original_total_mass = spec.material.density * d.volume_fraction * d.fill_fraction * drum_volume;
  p.particle = coarse_grain(d.coarse_graining, d.scale_factor, d.volume_fraction,
                            {spec.material.radius, spec.material.density});
  p.count = coarse_particle_count(p.particle, p.original_total_mass);
  if (p.count < 1) throw std::runtime_error("drum: the fill holds less than one coarse particle: lower drum.scale_factor");
  return p;
}

dem_core::Material powder_material(const CaseSpec& spec, const Powder& powder) {
  dem_core::Material m = to_material(spec.material);
  m.density = powder.particle.density;
  return m;
}

// Drum shell and end walls, all rotating about the z axis at `omega` [rad/s]; returns the first
// wall index (three walls: shell, end at z = 0, end at z = length).
std::size_t add_drum(dem_core::Simulation& sim, const CaseSpec& spec, double omega) {
  const double rd = 0.5 * spec.drum.diameter, len = spec.drum.length;
  const auto& contact = spec.wall;
  const dem_core::RotatingMotion motion{{0, 0, 0}, {0, 0, 1}, omega};
  const dem_core::Axis axis{{0, 0, 0}, {0, 0, 1}};
  const std::size_t first =
      sim.add_wall({dem_core::CylinderGeometry{{0, 0, 0}, {0, 0, 1}, rd, len}, motion, contact, axis, "shell"});
  sim.add_wall({dem_core::DiskGeometry{{0, 0, 0}, {0, 0, 1}, rd}, motion, contact, axis, "end_front"});
  sim.add_wall({dem_core::DiskGeometry{{0, 0, len}, {0, 0, -1}, rd}, motion, contact, axis, "end_back"});
  return first;
}

// to_key_json: effects at their off values leave the key (and so the cached fill) as before them.
nlohmann::json fill_key(const CaseSpec& spec) {
  const nlohmann::json full = to_key_json(spec);
  nlohmann::json drum = full["drum"];
  for (const char* k : {"rpm", "duration", "torque_interval", "surface_window", "surface_snapshots", "surface_points"}) {
    drum.erase(k);
  }
  return {{"fill_format", 1}, {"particle", full["particle"]}, {"contact", full["contact"]},
          {"wall_contact", full["wall_contact"]}, {"time_step_factor", kFillTimeStepFactor}, {"drum", drum}};
}

// Fallback when the lattice cannot hold the count (coarse particles only a few diameters shorter
// than the drum length): random sequential addition in the whole drum, seeded, no overlaps.
// With a radius spread s the radii are uniform in [R(1-s), R(1+s)] (a second seeded stream, so
// the monodisperse sequence is unchanged) and the target is the solid volume of `count` spheres.
std::optional<dem_core::Packing> random_packing(const CaseSpec& spec, const Powder& powder) {
  const double spread = spec.material.radius_spread;
  const double r_max = powder.particle.radius * (1.0 + spread);
  const double reach = 0.5 * spec.drum.diameter - r_max;
  if (reach <= 0.0 || spec.drum.length < 2.0 * r_max) return std::nullopt;
  std::mt19937_64 engine(static_cast<std::uint64_t>(spec.drum.fill_seed));
  std::mt19937_64 size_engine(static_cast<std::uint64_t>(spec.drum.fill_seed) + 0x9e3779b97f4a7c15ULL);
  auto uniform = [&engine] { return static_cast<double>(engine() >> 11) * 0x1.0p-53; };
  const double target = static_cast<double>(powder.count) * sphere_volume(powder.particle.radius);
  auto done = [&](const dem_core::Packing& p) {
    return spread > 0.0 ? p.solid_volume >= target : static_cast<long long>(p.centers.size()) >= powder.count;
  };
  dem_core::Packing packing;
  double r = powder.particle.radius;
  bool next_radius = spread > 0.0;  // a new radius for the first sphere and after each placement
  for (long long attempt = 0; attempt < 2000000 && !done(packing); ++attempt) {
    if (next_radius) {
      r = powder.particle.radius * (1.0 + spread * (2.0 * static_cast<double>(size_engine() >> 11) * 0x1.0p-53 - 1.0));
      next_radius = false;
    }
    const Vec3 c{(2.0 * uniform() - 1.0) * reach, (2.0 * uniform() - 1.0) * reach, r_max + uniform() * (spec.drum.length - 2.0 * r_max)};
    if (c.x * c.x + c.y * c.y > reach * reach) continue;
    bool free = true;
    for (std::size_t k = 0; k < packing.centers.size() && free; ++k) {
      const double contact = (packing.radii[k] + r) * (packing.radii[k] + r);
      free = dem_core::norm2(packing.centers[k] - c) >= contact * 1.0001;
    }
    if (!free) continue;
    packing.centers.push_back(c);
    packing.radii.push_back(r);
    packing.solid_volume += sphere_volume(r);
    next_radius = spread > 0.0;
  }
  if (!done(packing)) return std::nullopt;
  return packing;
}

// Packed generation in the lower part of the drum, enlarged until the lattice holds the count
// (the paper's "extending the volume of the packed region"), then frictionless densification
// followed by a short settle with friction (dem_core::settle).
Fill pack_and_densify(const CaseSpec& spec, const CaseRunOptions& options) {
  const Powder powder = powder_of(spec);
  dem_core::SimulationSettings settings;
  settings.contact = spec.contact;
  settings.gravity = {0.0, -9.81, 0.0};
  settings.threads = options.threads;
  settings.time_step_factor = kFillTimeStepFactor;
  dem_core::Simulation sim(settings);
  sim.add_material(powder_material(spec, powder));
  const double rd = 0.5 * spec.drum.diameter;
  dem_core::PackingRequest request;
  request.radius_min = request.radius_max = powder.particle.radius;
  if (spec.material.radius_spread > 0.0) {
    // Polydisperse: the coarse-grained radius gets the same relative spread; the packing keeps
    // the solid volume (hence the total mass of Table 2 and the fill's volume fraction).
    request.radius_spread = spec.material.radius_spread;
    request.solid_volume = static_cast<double>(powder.count) * sphere_volume(powder.particle.radius);
  } else {
    request.count = static_cast<std::size_t>(powder.count);
  }
  request.seed = static_cast<std::uint64_t>(spec.drum.fill_seed);
  request.up = {0, 1, 0};
  std::optional<dem_core::Packing> packing;
  std::string last_error;
  for (double gap : {0.2, 0.1, 0.03}) {
    for (double fraction = std::min(0.9, 1.2 * spec.drum.fill_fraction); fraction <= 0.995 && !packing; fraction += 0.05) {
      request.gap = gap;
      request.region = dem_core::DrumSegmentRegion{{0, 0, 0}, {0, 0, 1}, rd, spec.drum.length, {0, 1, 0},
                                                   dem_core::drum_fill_height(rd, fraction)};
      try {
        packing = dem_core::generate_packing(request);
      } catch (const std::exception& e) {
        last_error = e.what();
      }
    }
    if (packing) break;
  }
  if (!packing) packing = random_packing(spec, powder);
  if (!packing) throw std::runtime_error("drum: cannot place " + std::to_string(powder.count) + " particles: " + last_error);
  dem_core::add_packing(sim, *packing);
  add_drum(sim, spec, 0.0);
  if (options.progress) options.progress("densify", 0.0, spec.drum.densify_time);
  dem_core::SettleOptions settle_options;
  settle_options.max_time = spec.drum.densify_time;
  settle_options.frictionless = true;
  dem_core::settle(sim, settle_options);
  if (options.progress) options.progress("densify", spec.drum.densify_time, spec.drum.densify_time);
  return detail::fill_of(sim);
}

SurfaceProfile surface_now(const dem_core::Simulation& sim, const CaseSpec& spec) {
  std::vector<std::array<double, 3>> positions;
  for (const Vec3& p : sim.positions()) positions.push_back({p.x, p.y, p.z});
  const auto radii = sim.radii();
  const double rd = 0.5 * spec.drum.diameter;
  SurfaceOptions options{-rd, rd, static_cast<int>(spec.drum.surface_points), 0.1};
  return extract_free_surface(positions, std::vector<double>(radii.begin(), radii.end()), options);
}

struct RotationRun {
  std::vector<double> times, torques;
  SurfaceProfile surface;
  CurveTable particles;
  double time_step = 0.0;
  std::uint64_t steps = 0;
};

RotationRun rotate(const CaseSpec& spec, const Powder& powder, const Fill& fill, const CaseRunOptions& options) {
  dem_core::SimulationSettings settings;
  settings.contact = spec.contact;
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
  const std::size_t shell = add_drum(sim, spec, omega);
  check_user_time_step(spec, sim);
  RotationRun run;
  run.time_step = sim.time_step();
  const DrumSpec& d = spec.drum;
  const auto steps_per_sample = static_cast<std::uint64_t>(std::max(1.0, std::round(d.torque_interval / run.time_step)));
  std::vector<double> surface_times;
  for (long long k = 0; k < d.surface_snapshots; ++k) {
    const double f = d.surface_snapshots == 1 ? 1.0 : static_cast<double>(k) / static_cast<double>(d.surface_snapshots - 1);
    surface_times.push_back(d.duration - d.surface_window * (1.0 - f));
  }
  std::vector<SurfaceProfile> profiles;
  SnapshotSchedule snapshots(spec.output.snapshot_times, options.snapshot_dir.string(), "drum");
  double torque_sum = 0.0;
  std::uint64_t in_sample = 0;
  // Drive torque: minus the moment the particles exert on the drum about its axis, signed with
  // the rotation direction, so a bed resisting the rotation gives a positive torque (Fig. 5).
  const double sense = omega >= 0.0 ? 1.0 : -1.0;
  auto callback = [&](dem_core::Simulation& s) {
    torque_sum -= sense * (s.wall_torque(shell) + s.wall_torque(shell + 1) + s.wall_torque(shell + 2));
    snapshots.maybe_write(s, s.time());
    while (profiles.size() < surface_times.size() && s.time() >= surface_times[profiles.size()] - 1e-12) {
      profiles.push_back(surface_now(s, spec));
    }
    if (++in_sample >= steps_per_sample) {
      run.times.push_back(s.time());
      run.torques.push_back(torque_sum / static_cast<double>(in_sample));
      if (!std::isfinite(run.torques.back())) throw std::runtime_error("drum run diverged (non-finite torque): lower time_step.factor");
      torque_sum = 0.0;
      in_sample = 0;
      if (options.progress) options.progress("rotate", s.time(), d.duration);
    }
    return true;
  };
  sim.run_until(d.duration, callback, 1);
  while (profiles.size() < surface_times.size()) profiles.push_back(surface_now(sim, spec));
  run.surface = average_profiles(profiles);
  run.steps = sim.step_count();
  run.particles = CurveTable{{"particle centres at the end time; drum axis z, gravity -y"},
                             {"x_mm", "y_mm", "z_mm", "radius_mm"}, std::vector<std::vector<double>>(4)};
  for (std::size_t i = 0; i < sim.particle_count(); ++i) {
    const Vec3 p = sim.positions()[i];
    const double v[4] = {p.x * 1e3, p.y * 1e3, p.z * 1e3, sim.radii()[i] * 1e3};
    for (int c = 0; c < 4; ++c) run.particles.values[c].push_back(v[c]);
  }
  return run;
}

}  // namespace

CaseResult run_rotary_drum(const CaseSpec& fill_spec, const CaseSpec& spec, const CaseRunOptions& options) {
  const auto start = Clock::now();
  bool generated = false;
  const Powder powder = powder_of(spec);
  precheck_user_time_step(spec, powder.particle.radius, powder.particle.density);
  const Fill fill = cached_fill(options.cache_dir, "drum", fill_key(fill_spec),
                                [&] { return pack_and_densify(fill_spec, options); }, &generated);
  const double fill_seconds = std::chrono::duration<double>(Clock::now() - start).count();
  const auto rotate_start = Clock::now();
  const RotationRun run = rotate(spec, powder, fill, options);
  const double rotate_seconds = std::chrono::duration<double>(Clock::now() - rotate_start).count();
  CaseResult result;
  result.curves["torque"] = identify::Curve{"time_s", "torque_Nm", run.times, run.torques};
  identify::Curve surface{"x_mm", "height_mm", {}, {}};
  for (std::size_t k = 0; k < run.surface.x.size(); ++k) {
    if (!std::isfinite(run.surface.height[k])) continue;
    surface.x.push_back(run.surface.x[k] * 1e3);
    surface.y.push_back(run.surface.height[k] * 1e3);
  }
  if (surface.x.size() < 2) throw std::runtime_error("drum: free surface not found (fewer than 2 points)");
  result.curves["free_surface"] = surface;
  result.tables["particles_end"] = run.particles;
  const double rd = 0.5 * spec.drum.diameter;
  double mean_torque = 0.0;
  int counted = 0;
  for (std::size_t i = 0; i < run.times.size(); ++i) {
    if (run.times[i] >= 0.5 * spec.drum.duration) { mean_torque += run.torques[i]; ++counted; }
  }
  auto& sum = result.summary;
  sum.emplace_back("model", to_string(spec.drum.coarse_graining) + " s = " + fmt("%g", spec.drum.scale_factor));
  sum.emplace_back("particles", std::to_string(fill.radii.size()));
  sum.emplace_back("particle radius [mm]", fmt("%.4f", powder.particle.radius * 1e3));
  sum.emplace_back("particle density [kg/m3]", fmt("%.1f", powder.particle.density));
  double total_mass = 0.0;  // summed per particle: radii differ with a radius spread
  for (double r : fill.radii) total_mass += powder.particle.density * sphere_volume(r);
  sum.emplace_back("total particle mass [g]", fmt("%.3f", total_mass * 1e3));
  sum.emplace_back("fill", generated ? "generated and cached" : "read from cache");
  sum.emplace_back("fill wall time [s]", fmt("%.1f", fill_seconds));
  sum.emplace_back("dynamic angle of repose [deg] (surface fit over |x| < R/2)",
                   fmt("%.2f", repose_angle_degrees(run.surface, -0.5 * rd, 0.5 * rd)));
  sum.emplace_back("mean drive torque, second half [N m]", fmt("%.5f", counted ? mean_torque / counted : 0.0));
  sum.emplace_back("time step [s]", fmt("%.3e", run.time_step));
  sum.emplace_back("rotation steps", std::to_string(run.steps));
  sum.emplace_back("rotation wall time [s] (one evaluation)", fmt("%.1f", rotate_seconds));
  return result;
}

}  // namespace demfit::cases::detail
