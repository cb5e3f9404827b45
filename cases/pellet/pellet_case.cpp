// Pellet compression (docs/spec.md 2.1, paper section 2): pour and settle the pellets in the rigid
// cylinder (cached), then push a piston down at constant speed until the piston pressure reaches
// P_max, optionally unload, and report pressure against bed volume.
#include "pellet_case.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <stdexcept>

#include "dem_setup.hpp"
#include "run_budget.hpp"
#include "demfit/cases/case_registry.hpp"
#include "demfit/cases/coarse_graining.hpp"
#include "demfit/cases/fill_cache.hpp"
#include "demfit/dem_core/packing.hpp"
#include "demfit/dem_core/simulation.hpp"
#include "demfit/identify/study_warnings.hpp"
#include "number_text.hpp"

namespace demfit::cases::detail {
namespace {

using dem_core::Vec3;
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

double container_radius(const CaseSpec& spec) { return 0.5 * spec.pellet.container_diameter; }

// Everything the settled fill depends on; the cache key.
// to_key_json: effects at their off values leave the key (and so the cached fill) as before them.
nlohmann::json fill_key(const CaseSpec& spec) {
  return detail::fill_key_of(spec, "pellet", {"piston_speed", "max_pressure", "max_travel", "unload", "curve_points"});
}

// Adds the bottom plate (disk at z = 0) and the container wall (cylinder of `height`).
void add_container(dem_core::Simulation& sim, const CaseSpec& spec, double height) {
  const double rc = container_radius(spec);
  const auto& wall = spec.wall;
  sim.add_wall({dem_core::DiskGeometry{{0, 0, 0}, {0, 0, 1}, rc}, dem_core::FixedMotion{}, wall, {}, "bottom"});
  sim.add_wall(
      {dem_core::CylinderGeometry{{0, 0, 0}, {0, 0, 1}, rc, height}, dem_core::FixedMotion{}, wall, {}, "container"});
}

// Pours the pellets: a jittered lattice in a tall cylinder above the bottom, settled under
// gravity with NORMK = fill_normk (softer => larger stable step; the piston stage re-equilibrates
// the tiny gravity overlaps at the evaluated stiffness within a few steps).
Fill pour_and_settle(const CaseSpec& spec, const CaseRunOptions& options) {
  dem_core::SimulationSettings settings;
  settings.contact = spec.contact;
  settings.reorder_particles = spec.numerics.reorder_particles;
  settings.pair_load_order = spec.numerics.pair_load_order;
  settings.contact.normk = spec.pellet.fill_normk;
  settings.threads = options.threads;
  settings.time_step_factor = kFillTimeStepFactor;
  dem_core::Simulation sim(settings);
  sim.add_material(to_material(spec.material));
  const double spread = spec.material.radius_spread;
  const double r = spec.material.radius * (1.0 + spread);  // largest radius (sets the lattice)
  const double rc = container_radius(spec);
  // Lattice spacing 2r(1 + gap): layers of ~pi (rc - r)^2 / (2.4 r)^2 sites; leave 50 % margin.
  const double per_layer = std::max(1.0, std::numbers::pi * std::pow(rc - r, 2) / std::pow(2.4 * r, 2));
  const double height = 1.5 * 2.4 * r * (static_cast<double>(spec.pellet.particle_count) / per_layer + 2.0);
  dem_core::PackingRequest request;
  request.region = dem_core::CylinderRegion{{0, 0, 0}, {0, 0, 1}, rc, height};
  request.radius_min = request.radius_max = spec.material.radius;
  if (spread > 0.0) {
    // Polydisperse: the same solid volume as particle_count pellets of the nominal radius
    // (same mass of pellets, same bed volume), so fewer, on average larger spheres.
    request.radius_spread = spread;
    request.solid_volume = static_cast<double>(spec.pellet.particle_count) * sphere_volume(spec.material.radius);
  } else {
    request.count = static_cast<std::size_t>(spec.pellet.particle_count);
  }
  request.seed = static_cast<std::uint64_t>(spec.pellet.fill_seed);
  dem_core::add_packing(sim, dem_core::generate_packing(request));
  add_container(sim, spec, height + 2.0 * r);
  if (options.progress) options.progress("settle", 0.0, spec.pellet.settle_time);
  // Frictionless settling first, then friction restored (dem_core::settle densification): a
  // frictional lattice pour arches in a cylinder only ~10 pellets wide and stays near phi = 0.5;
  // docs/spec.md 2.1 asks for a random packing near phi = 0.6 filling the 64 mm container.
  dem_core::SettleOptions settle_options;
  settle_options.max_time = spec.pellet.settle_time;
  settle_options.frictionless = true;
  settle_options.refriction_time = 0.1;
  if (options.progress)
    settle_options.progress = [&](double elapsed, double end) { options.progress("settle", elapsed, end); };
  dem_core::settle(sim, settle_options);
  if (options.progress) options.progress("settle", spec.pellet.settle_time, spec.pellet.settle_time);
  return detail::fill_of(sim);
}

// One averaged sample of the compression.
struct Sample {
  double time = 0, travel = 0, volume_cm3 = 0, pressure_mpa = 0, piston_force = 0, bottom_force = 0, kinetic = 0,
         elastic = 0;
};

struct CompressionRun {
  std::vector<Sample> samples;
  std::size_t loading_end = 0;  // samples [0, loading_end) are the loading branch
  bool reached_max_pressure = false;
  double time_step = 0.0;
  std::uint64_t steps = 0;
  double bed_top = 0.0;
};

CompressionRun compress(const CaseSpec& spec, const Fill& fill, const CaseRunOptions& options);

identify::Curve resample_by_volume(const std::vector<Sample>& s, std::size_t end, long long points,
                                   double Sample::*y_field, const identify::CurveDescriptor& labels);

}  // namespace

CaseResult run_pellet_compression(const CaseSpec& fill_spec, const CaseSpec& spec, const CaseRunOptions& options) {
  precheck_user_time_step(spec, spec.material.radius, spec.material.density);
  {  // Before any work: the wall must not jump over contacts, and the run must fit the budget.
    const double time_step = planned_time_step(spec, spec.material.radius, spec.material.density);
    check_wall_travel_per_step("pellet.piston_speed", spec.pellet.piston_speed,
                               spec.material.radius * (1.0 - spec.material.radius_spread), time_step);
    check_run_budget("pellet compression", static_cast<double>(spec.pellet.particle_count),
                     spec.pellet.settle_time + spec.pellet.max_travel / spec.pellet.piston_speed, time_step, options);
  }
  const auto start = Clock::now();
  bool generated = false;
  // A cached fill is used only with every pellet inside the container (axis z, bottom at z = 0).
  const double container = container_radius(fill_spec);
  const auto inside_container = [&](const Fill& f) {
    for (std::size_t i = 0; i < f.radii.size(); ++i) {
      const double slack = 0.1 * f.radii[i];  // a settled contact overlaps a wall by ~1 % of a radius
      if (std::hypot(f.positions[i][0], f.positions[i][1]) + f.radii[i] > container + slack ||
          f.positions[i][2] - f.radii[i] < -slack)
        return false;
    }
    return true;
  };
  const Fill fill = cached_fill(
      options.cache_dir, "pellet", fill_key(fill_spec), [&] { return pour_and_settle(fill_spec, options); },
      &generated, inside_container);
  const double fill_seconds = seconds_since(start);
  const auto compress_start = Clock::now();
  const CompressionRun run = compress(spec, fill, options);
  const double compress_seconds = seconds_since(compress_start);

  CaseResult result;
  const long long points = spec.pellet.curve_points;
  constexpr CaseKind kind = CaseKind::pellet_compression;  // curve names and labels: case_registry.cpp
  result.curves["pressure_volume"] = resample_by_volume(run.samples, run.loading_end, points, &Sample::pressure_mpa,
                                                        case_curve(kind, "pressure_volume"));
  result.curves["bottom_force_volume"] = resample_by_volume(run.samples, run.loading_end, points, &Sample::bottom_force,
                                                            case_curve(kind, "bottom_force_volume"));
  if (spec.pellet.unload) {
    identify::Curve cycle = empty_curve(kind, "pressure_volume_cycle");
    for (const Sample& s : run.samples) {
      cycle.x.push_back(s.volume_cm3);
      cycle.y.push_back(s.pressure_mpa);
    }
    result.curves["pressure_volume_cycle"] = cycle;
  }
  CurveTable history{
      {"pellet compression history (docs/spec.md 2.1); piston force and bottom force are the forces the pellets exert"},
      {"time_s", "piston_travel_mm", "volume_cm3", "pressure_MPa", "piston_force_N", "bottom_force_N",
       "kinetic_energy_J", "elastic_energy_J"},
      std::vector<std::vector<double>>(8)};
  double worst_ratio = 0.0;
  // docs/spec.md 2.1: the compression is quasi-static while the bed's kinetic energy stays below 1 % of
  // its elastic energy. The study warns when a run crosses it (identify::kQuasiStaticCurve).
  constexpr double quasi_static_limit = 0.01;
  identify::Curve quasi_static = empty_curve(kind, identify::kQuasiStaticCurve);
  for (std::size_t i = 0; i < run.samples.size(); ++i) {
    const Sample& s = run.samples[i];
    const double values[8] = {s.time,         s.travel * 1e3, s.volume_cm3, s.pressure_mpa,
                              s.piston_force, s.bottom_force, s.kinetic,    s.elastic};
    for (int c = 0; c < 8; ++c) history.values[c].push_back(values[c]);
    // Quasi-static check (docs/spec.md 2.1) once the bed carries load (> 10 % of P_max).
    if (i < run.loading_end && s.pressure_mpa * 1e6 > 0.1 * spec.pellet.max_pressure && s.elastic > 0.0) {
      worst_ratio = std::max(worst_ratio, s.kinetic / s.elastic);
      quasi_static.x.push_back(s.volume_cm3);
      quasi_static.y.push_back(s.kinetic / s.elastic / quasi_static_limit);
    }
  }
  if (!quasi_static.x.empty()) result.curves[identify::kQuasiStaticCurve] = quasi_static;
  result.tables["history"] = history;
  const Sample& last_loading = run.samples.at(run.loading_end - 1);
  auto& sum = result.summary;
  sum.emplace_back("pellets", std::to_string(fill.radii.size()));
  sum.emplace_back("fill", generated ? "generated and cached" : "read from cache");
  sum.emplace_back("fill wall time [s]", fmt("%.1f", fill_seconds));
  sum.emplace_back("bed height before compression [mm]", fmt("%.2f", run.bed_top * 1e3));
  sum.emplace_back("bed volume before compression [cm3]", fmt("%.3f", run.samples.front().volume_cm3));
  double solid = 0.0;
  for (double r : fill.radii) solid += 4.0 / 3.0 * std::numbers::pi * r * r * r;
  sum.emplace_back("solid fraction of the fill (under the piston)",
                   fmt("%.3f", solid * 1e6 / run.samples.front().volume_cm3));
  sum.emplace_back("volume at the end of loading [cm3]", fmt("%.3f", last_loading.volume_cm3));
  sum.emplace_back("pressure at the end of loading [MPa]", fmt("%.3f", last_loading.pressure_mpa));
  sum.emplace_back("reached max_pressure", run.reached_max_pressure ? "yes" : "no (stopped at max_travel)");
  sum.emplace_back("max kinetic/elastic energy under load [%] (quasi-static if < 1)", fmt("%.3f", 100.0 * worst_ratio));
  sum.emplace_back("time step [s]", fmt("%.3e", run.time_step));
  sum.emplace_back("compression steps", std::to_string(run.steps));
  sum.emplace_back("compression wall time [s] (one evaluation)", fmt("%.1f", compress_seconds));
  return result;
}

namespace {

CompressionRun compress(const CaseSpec& spec, const Fill& fill, const CaseRunOptions& options) {
  dem_core::SimulationSettings settings;
  settings.contact = spec.contact;
  settings.reorder_particles = spec.numerics.reorder_particles;
  settings.pair_load_order = spec.numerics.pair_load_order;
  settings.threads = options.threads;
  settings.time_step = spec.time_step.value;
  settings.time_step_factor = spec.time_step.factor;
  dem_core::Simulation sim(settings);
  sim.add_material(to_material(spec.material));
  double top = 0.0;
  for (std::size_t i = 0; i < fill.radii.size(); ++i) {
    const auto& p = fill.positions[i];
    sim.add_particle({p[0], p[1], p[2]}, fill.radii[i]);
    top = std::max(top, p[2] + fill.radii[i]);
  }
  const double rc = container_radius(spec);
  const double area = std::numbers::pi * rc * rc;
  add_container(sim, spec, std::max(spec.pellet.container_height, top) + 4.0 * spec.material.radius);
  const double speed = spec.pellet.piston_speed;
  const std::size_t piston = sim.add_wall({dem_core::DiskGeometry{{0, 0, top}, {0, 0, -1}, rc},
                                           dem_core::TranslatingMotion{{0, 0, -speed}},
                                           spec.wall,
                                           {},
                                           "piston"});
  check_user_time_step(spec, sim);
  CompressionRun run;
  run.bed_top = top;
  run.time_step = sim.time_step();
  // Samples average the wall forces over 0.05 mm of piston travel (contact noise).
  const auto steps_per_sample = static_cast<std::uint64_t>(std::max(1.0, std::round(0.05e-3 / speed / run.time_step)));
  const double end_time = spec.pellet.max_travel / speed;
  SnapshotSchedule snapshots(spec.output.snapshot_times, options.snapshot_dir.string(), "compression");
  Sample sum;
  std::uint64_t in_sample = 0;
  bool unloading = false;
  std::uint64_t steps_done = 0;
  auto callback = [&](dem_core::Simulation& s) {
    // Progress at least every 256 steps (the printer throttles by wall time), also when a
    // sample spans millions of steps.
    if (options.progress && (++steps_done & 255u) == 0)
      options.progress(unloading ? "unload" : "compress", s.time(), end_time);
    sum.piston_force += s.wall_force(piston).z;  // particles push the piston up (+z)
    sum.bottom_force -= s.wall_force(0).z;       // and the bottom plate down (-z)
    if (++in_sample < steps_per_sample) return true;
    Sample out;
    out.time = s.time();
    const double z_piston = top + s.wall(piston).displacement.z;
    out.travel = top - z_piston;
    out.volume_cm3 = area * z_piston * 1e6;
    out.piston_force = sum.piston_force / in_sample;
    out.bottom_force = sum.bottom_force / in_sample;
    out.pressure_mpa = out.piston_force / area * 1e-6;
    out.kinetic = s.kinetic_energy();
    out.elastic = s.elastic_energy();
    run.samples.push_back(out);
    sum = Sample{};
    in_sample = 0;
    snapshots.maybe_write(s, s.time());
    if (options.progress) options.progress(unloading ? "unload" : "compress", s.time(), end_time);
    if (!std::isfinite(out.piston_force))
      throw std::runtime_error("pellet compression diverged (non-finite piston force): lower time_step.factor");
    if (!unloading && out.pressure_mpa * 1e6 >= spec.pellet.max_pressure) {
      run.reached_max_pressure = true;
      run.loading_end = run.samples.size();
      if (!spec.pellet.unload) return false;
      unloading = true;
      s.set_wall_velocity(piston, {0, 0, speed});
      return true;
    }
    if (unloading) return out.piston_force > 0.0 && out.travel > 0.0;
    return out.travel < spec.pellet.max_travel;
  };
  sim.run_until(2.0 * end_time + 1.0, callback, 1);
  if (run.loading_end == 0) run.loading_end = run.samples.size();
  if (run.samples.size() < 2)
    throw std::runtime_error("pellet compression produced fewer than 2 samples: increase pellet.max_travel");
  run.steps = sim.step_count();
  return run;
}

// `points` values at equal volume spacing along the loading branch, interpolated linearly
// between samples (the piston moves at constant speed, so volume is monotone).
identify::Curve resample_by_volume(const std::vector<Sample>& s, std::size_t end, long long points,
                                   double Sample::*y_field, const identify::CurveDescriptor& labels) {
  identify::Curve curve{labels.x_label, labels.y_label, {}, {}};
  end = std::clamp<std::size_t>(end, 2, s.size());
  const double v0 = s.front().volume_cm3;
  const double v1 = s[end - 1].volume_cm3;
  std::size_t j = 0;
  for (long long k = 0; k < points; ++k) {
    const double v = v0 + (v1 - v0) * static_cast<double>(k) / static_cast<double>(points - 1);
    while (j + 2 < end && s[j + 1].volume_cm3 > v) ++j;
    const double va = s[j].volume_cm3, vb = s[j + 1].volume_cm3;
    const double w = va == vb ? 0.0 : std::clamp((v - va) / (vb - va), 0.0, 1.0);
    curve.x.push_back(v);
    curve.y.push_back((1.0 - w) * s[j].*y_field + w * s[j + 1].*y_field);
  }
  return curve;
}

}  // namespace
}  // namespace demfit::cases::detail
