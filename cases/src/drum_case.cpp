// Rotary drum (SPEC 2.2, paper section 3): packed generation of the (coarse-grained) powder in
// the lower part of a horizontal drum, densification under gravity (cached), then rotation at
// the given speed; outputs the drive torque history and the free surface at the end time.
// Frame: drum axis = z (end walls at z = 0 and z = length), gravity -y.
#include "drum_case.hpp"

#include "demfit/cases/case_registry.hpp"
#include "demfit/cases/drum_fill.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
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
#include "demfit/imaging/occupancy.hpp"
#include "demfit/imaging/profile_metrics.hpp"
#include "demfit/imaging/surface.hpp"

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
  CoarseParticle particle;  // monodisperse: the particle; distribution: its smallest one
  long long count = 0;
  double original_total_mass = 0.0;  // M0 [kg]
  double original_count = 0.0;       // N0 (real: the rule's value before rounding)
  double bulk_fraction = 0.0;        // original bulk volume / drum volume (packing start)
  std::vector<double> radii;         // size distribution: the coarse radii [m]; empty = monodisperse
};

double drum_volume(const DrumSpec& d) { return std::numbers::pi * 0.25 * d.diameter * d.diameter * d.length; }

// Original (s = 1) particle count N0 of the fill amount (see FillBy): bulk volumes hold
// phi V_bulk of solid, N0 = solid / E[v].
double original_count(const CaseSpec& spec, double mean_volume) {
  const DrumSpec& d = spec.drum;
  switch (d.fill_by) {
    case FillBy::fill_fraction:
      return d.volume_fraction * d.fill_fraction * drum_volume(d) / mean_volume;
    case FillBy::fill_volume:
      return d.volume_fraction * d.fill_volume_ml * 1e-6 / mean_volume;
    case FillBy::particle_count:
      return static_cast<double>(d.particle_count);
    case FillBy::fill_mass:
      return d.fill_mass / (spec.material.density * mean_volume);
  }
  return 0.0;
}

// Table 2 applied to the drum fill: the original powder's solid volume is phi times the bulk
// fill (fill_fraction of the drum volume); the coarse model carries its Table 2 total mass.
Powder powder_of(const CaseSpec& spec) {
  const DrumSpec& d = spec.drum;
  Powder p;
  if (!d.size_distribution.enabled() && d.fill_by == FillBy::fill_fraction) {
    // The paper's drum, computed exactly as before the general drum existed.
    p.original_total_mass = spec.material.density * d.volume_fraction * d.fill_fraction * drum_volume(d);
    p.particle = coarse_grain(d.coarse_graining, d.scale_factor, d.volume_fraction,
                              {spec.material.radius, spec.material.density});
    p.count = coarse_particle_count(p.particle, p.original_total_mass);
    p.original_count = p.original_total_mass / (spec.material.density * sphere_volume(spec.material.radius));
    p.bulk_fraction = d.fill_fraction;
    if (p.count < 1)
      throw std::runtime_error("drum: the fill holds less than one coarse particle: lower drum.scale_factor");
    return p;
  }
  const SizeDistributionSpec& sizes = d.size_distribution;
  const double mean_volume = sizes.enabled() ? sizes.mean_volume() : sphere_volume(spec.material.radius);
  p.original_count = original_count(spec, mean_volume);
  p.original_total_mass = spec.material.density * p.original_count * mean_volume;
  p.bulk_fraction = p.original_count * mean_volume / (d.volume_fraction * drum_volume(d));
  if (!sizes.enabled()) {
    p.particle = coarse_grain(d.coarse_graining, d.scale_factor, d.volume_fraction,
                              {spec.material.radius, spec.material.density});
    p.count = coarse_particle_count(p.particle, p.original_total_mass);
  } else {
    // Every size of the distribution is coarse-grained alike (Table 2 with r0 = 1 gives the
    // radius factor); SCG count = N0 / s^3, CVF phi N0 / s^3 (the Table 2 total mass).
    const CoarseParticle unit =
        coarse_grain(d.coarse_graining, d.scale_factor, d.volume_fraction, {1.0, spec.material.density});
    p.count =
        std::llround(unit.total_mass_factor * p.original_count / (d.scale_factor * d.scale_factor * d.scale_factor));
    if (p.count >= 1) {
      p.radii = sizes.sample_radii(static_cast<std::size_t>(p.count), static_cast<std::uint64_t>(d.fill_seed));
      for (double& r : p.radii) r *= unit.radius;
    }
    p.particle = coarse_grain(d.coarse_graining, d.scale_factor, d.volume_fraction,
                              {0.5 * sizes.min_diameter(), spec.material.density});
  }
  if (p.count < 1)
    throw std::runtime_error(
        "drum: the fill holds less than one coarse particle: lower drum.scale_factor or raise the fill");
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
  for (const char* k :
       {"rpm", "duration", "torque_interval", "surface_window", "surface_snapshots", "surface_points", "image"}) {
    drum.erase(k);
  }
  return {{"fill_format", 1},
          {"particle", full["particle"]},
          {"contact", full["contact"]},
          {"wall_contact", full["wall_contact"]},
          {"time_step_factor", kFillTimeStepFactor},
          {"drum", drum}};
}

// Fallback when the lattice cannot hold the count (coarse particles only a few diameters shorter
// than the drum length): random sequential addition in the whole drum, seeded, no overlaps.
// With a radius spread s the radii are uniform in [R(1-s), R(1+s)] (a second seeded stream, so
// the monodisperse sequence is unchanged) and the target is the solid volume of `count` spheres.
// Size distribution: the sampled radii, largest first (small ones fill the gaps left), each at
// the first free random position inside the drum for its own radius (at most 200000 tries
// each), seeded by the fill seed.
// Adds the sphere (c, r) to the packing when it overlaps no sphere placed so far (0.01 % margin on
// the squared contact distance); returns whether it was placed.
bool place_if_free(dem_core::Packing& packing, const Vec3& c, double r) {
  for (std::size_t k = 0; k < packing.centers.size(); ++k) {
    const double contact = (packing.radii[k] + r) * (packing.radii[k] + r);
    if (dem_core::norm2(packing.centers[k] - c) < contact * 1.0001) return false;
  }
  packing.centers.push_back(c);
  packing.radii.push_back(r);
  packing.solid_volume += sphere_volume(r);
  return true;
}

std::optional<dem_core::Packing> random_packing_of_radii(const CaseSpec& spec, std::vector<double> radii) {
  std::stable_sort(radii.begin(), radii.end(), std::greater<>());
  std::mt19937_64 engine(static_cast<std::uint64_t>(spec.drum.fill_seed));
  auto uniform = [&engine] { return static_cast<double>(engine() >> 11) * 0x1.0p-53; };
  dem_core::Packing packing;
  for (const double r : radii) {
    const double reach = 0.5 * spec.drum.diameter - r;
    if (reach <= 0.0 || spec.drum.length < 2.0 * r) return std::nullopt;
    bool placed = false;
    for (int attempt = 0; attempt < 200000 && !placed; ++attempt) {
      const Vec3 c{(2.0 * uniform() - 1.0) * reach, (2.0 * uniform() - 1.0) * reach,
                   r + uniform() * (spec.drum.length - 2.0 * r)};
      if (c.x * c.x + c.y * c.y > reach * reach) continue;
      placed = place_if_free(packing, c, r);
    }
    if (!placed) return std::nullopt;
  }
  return packing;
}

std::optional<dem_core::Packing> random_packing(const CaseSpec& spec, const Powder& powder) {
  if (!powder.radii.empty()) return random_packing_of_radii(spec, powder.radii);
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
    const Vec3 c{(2.0 * uniform() - 1.0) * reach, (2.0 * uniform() - 1.0) * reach,
                 r_max + uniform() * (spec.drum.length - 2.0 * r_max)};
    if (c.x * c.x + c.y * c.y > reach * reach) continue;
    if (!place_if_free(packing, c, r)) continue;
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
  dem_core::SimulationSettings settings = simulation_settings(spec);
  settings.gravity = {0.0, -9.81, 0.0};
  settings.threads = options.threads;
  settings.time_step_factor = kFillTimeStepFactor;
  dem_core::Simulation sim(settings);
  sim.add_material(powder_material(spec, powder));
  const double rd = 0.5 * spec.drum.diameter;
  dem_core::PackingRequest request;
  request.radius_min = request.radius_max = powder.particle.radius;
  if (!powder.radii.empty()) {
    // Size distribution: the sampled radii on an fcc lattice sized for the largest one (a cubic
    // one cannot hold the GranuDrum fill: its sites are sized by the largest sphere).
    request.radii = powder.radii;
    request.lattice = dem_core::PackingRequest::Lattice::fcc;
  } else if (spec.material.radius_spread > 0.0) {
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
    for (double fraction = std::min(0.9, 1.2 * powder.bulk_fraction); fraction <= 0.995 && !packing; fraction += 0.05) {
      request.gap = gap;
      request.region = dem_core::DrumSegmentRegion{
          {0, 0, 0}, {0, 0, 1}, rd, spec.drum.length, {0, 1, 0}, dem_core::drum_fill_height(rd, fraction)};
      try {
        packing = dem_core::generate_packing(request);
      } catch (const std::exception& e) { last_error = e.what(); }
    }
    if (packing) break;
  }
  if (!packing) packing = random_packing(spec, powder);
  if (!packing)
    throw std::runtime_error("drum: cannot place " + std::to_string(powder.count) + " particles: " + last_error);
  dem_core::add_packing(sim, *packing);
  add_drum(sim, spec, 0.0);
  if (options.progress) options.progress("densify", 0.0, spec.drum.densify_time);
  dem_core::SettleOptions settle_options;
  settle_options.max_time = spec.drum.densify_time;
  settle_options.frictionless = true;
  if (options.progress)
    settle_options.progress = [&](double elapsed, double end) { options.progress("densify", elapsed, end); };
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

struct RotationRun {
  std::vector<double> times, torques;
  SurfaceProfile surface;
  std::optional<imaging::SurfaceProfile> image_surface;
  CurveTable particles;
  double time_step = 0.0;
  std::uint64_t steps = 0;
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
  const std::size_t shell = add_drum(sim, spec, omega);
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
  auto callback = [&](dem_core::Simulation& s) {
    torque_sum -= sense * (s.wall_torque(shell) + s.wall_torque(shell + 1) + s.wall_torque(shell + 2));
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
  run.particles = CurveTable{{"particle centres at the end time; drum axis z, gravity -y"},
                             {"x_mm", "y_mm", "z_mm", "radius_mm"},
                             std::vector<std::vector<double>>(4)};
  for (std::size_t i = 0; i < sim.particle_count(); ++i) {
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

}  // namespace

}  // namespace demfit::cases::detail

namespace demfit::cases {

DrumFillAmount drum_fill_amount(const CaseSpec& spec) {
  if (spec.kind != CaseKind::rotary_drum) throw std::runtime_error("drum_fill_amount: the case is not a rotary_drum");
  const detail::Powder powder = detail::powder_of(spec);
  return {powder.original_count, powder.count, powder.original_total_mass};
}

}  // namespace demfit::cases

namespace demfit::cases::detail {

CaseResult run_rotary_drum(const CaseSpec& fill_spec, const CaseSpec& spec, const CaseRunOptions& options) {
  const auto start = Clock::now();
  bool generated = false;
  const Powder powder = powder_of(spec);
  precheck_user_time_step(spec, powder.particle.radius, powder.particle.density);
  const Fill fill = cached_fill(
      options.cache_dir, "drum", fill_key(fill_spec), [&] { return pack_and_densify(fill_spec, options); }, &generated);
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
  sum.emplace_back("fill", generated ? "generated and cached" : "read from cache");
  sum.emplace_back("fill wall time [s]", fmt("%.1f", fill_seconds));
  sum.emplace_back("dynamic angle of repose [deg] (surface fit over |x| < R/2)",
                   fmt("%.2f", repose_angle_degrees(run.surface, -0.5 * rd, 0.5 * rd)));
  sum.emplace_back("mean drive torque, second half [N m]", fmt("%.5f", counted ? mean_torque / counted : 0.0));
  if (run.image_surface) {
    sum.emplace_back(
        "surface_angle_deg (dynamic repose angle of free_surface_image, line fit over |x| < R/2; positive = lifted at "
        "x < 0)",
        fmt("%.2f", image_surface_angle(*run.image_surface, 0.5 * rd)));
  }
  sum.emplace_back("time step [s]", fmt("%.3e", run.time_step));
  sum.emplace_back("rotation steps", std::to_string(run.steps));
  sum.emplace_back("rotation wall time [s] (one evaluation)", fmt("%.1f", rotate_seconds));
  return result;
}

}  // namespace demfit::cases::detail
