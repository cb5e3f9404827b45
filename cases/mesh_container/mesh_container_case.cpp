// The mesh_container run (docs/mesh-container.md): the particles are placed on a jittered lattice
// in the fill box (sites touching a mesh are skipped), fall under gravity (-z) into the user's STL
// geometry and settle while the moving parts start at their times; the selected curves are
// sampled every output interval. Particles that fall past the geometry land on a catch floor (a
// plane below every mesh), so none is lost: the mass is conserved and countable.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <random>
#include <stdexcept>

#include "dem_setup.hpp"
#include "mesh_container_case.hpp"
#include "run_budget.hpp"
#include "demfit/cases/case_registry.hpp"
#include "demfit/dem_core/simulation.hpp"
#include "number_text.hpp"

namespace demfit::cases::detail {
namespace {

using dem_core::Vec3;
using Clock = std::chrono::steady_clock;
constexpr double kGravity = 9.81;    // [m/s^2], along -z
constexpr double kLatticeGap = 0.1;  // site spacing 2 r_max (1 + gap)

Vec3 vec(const std::array<double, 3>& a) { return {a[0], a[1], a[2]}; }
double omega_of(const MeshPartSpec& part) { return part.rpm * 2.0 * std::numbers::pi / 60.0; }

// The particles' radii [m]: sampled from the size distribution, or the particle radius with its
// relative spread (uniform in [R(1 - s), R(1 + s)]), seeded by fill_seed.
std::vector<double> particle_radii(const CaseSpec& spec) {
  const MeshContainerSpec& m = spec.mesh_container;
  const auto count = static_cast<std::size_t>(m.particle_count);
  const auto seed = static_cast<std::uint64_t>(m.fill_seed);
  if (m.size_distribution.enabled()) return m.size_distribution.sample_radii(count, seed);
  std::vector<double> radii(count, spec.material.radius);
  const double s = spec.material.radius_spread;
  if (s > 0.0) {
    std::mt19937_64 engine(seed + 0x9e3779b97f4a7c15ULL);
    for (double& r : radii) r *= 1.0 + s * (2.0 * static_cast<double>(engine() >> 11) * 0x1.0p-53 - 1.0);
  }
  return radii;
}

// Lattice sites of the fill box from the lowest layer up (x fastest), each jittered within its
// free gap; sites closer than r_max (1 + gap) to a mesh are skipped. Throws naming fill_box when
// the box holds fewer sites than particles.
std::vector<Vec3> fill_positions(const CaseSpec& spec, double r_max,
                                 const std::vector<const dem_core::TriangleMesh*>& meshes) {
  const MeshContainerSpec& m = spec.mesh_container;
  const double a = 2.0 * r_max * (1.0 + kLatticeGap), jitter = r_max * kLatticeGap;
  std::array<long long, 3> n{};
  for (int k = 0; k < 3; ++k)
    n[k] = std::max(0LL, static_cast<long long>(std::floor((m.fill_upper[k] - m.fill_lower[k] - 2.0 * r_max) / a)) + 1);
  std::mt19937_64 engine(static_cast<std::uint64_t>(m.fill_seed));
  auto uniform = [&engine] { return 2.0 * static_cast<double>(engine() >> 11) * 0x1.0p-53 - 1.0; };
  std::vector<Vec3> sites;
  const auto wanted = static_cast<std::size_t>(m.particle_count);
  for (long long k = 0; k < n[2] && sites.size() < wanted; ++k)
    for (long long j = 0; j < n[1] && sites.size() < wanted; ++j)
      for (long long i = 0; i < n[0] && sites.size() < wanted; ++i) {
        Vec3 c{m.fill_lower[0] + r_max + static_cast<double>(i) * a,
               m.fill_lower[1] + r_max + static_cast<double>(j) * a,
               m.fill_lower[2] + r_max + static_cast<double>(k) * a};
        c = c + Vec3{uniform() * jitter, uniform() * jitter, uniform() * jitter};
        bool free = true;
        for (const dem_core::TriangleMesh* mesh : meshes)
          free = free && !mesh->any_within(c, r_max * (1.0 + kLatticeGap));
        if (free) sites.push_back(c);
      }
  if (sites.size() < wanted)
    throw std::runtime_error("'mesh_container.fill_box' holds " + std::to_string(sites.size()) +
                             " lattice sites clear of the meshes for particles of radius " + fmt("%.4g", r_max) +
                             " m, fewer than particle_count = " + std::to_string(wanted) +
                             ": enlarge the box (its top may rise above the meshes) or lower particle_count");
  return sites;
}

struct Setup {
  std::vector<std::size_t> part_wall;  // wall index of each mesh part
  double catch_floor_z = 0.0;          // [m]
  double total_mass = 0.0;             // [kg]
};

// Mesh walls (fixed until their start time), the catch floor, and the particles.
Setup build(dem_core::Simulation& sim, const CaseSpec& spec) {
  const MeshContainerSpec& m = spec.mesh_container;
  Setup setup;
  std::vector<std::shared_ptr<const dem_core::TriangleMesh>> meshes;
  std::vector<const dem_core::TriangleMesh*> raw;
  double low = std::numeric_limits<double>::infinity(), high = -low;
  for (const MeshPartSpec& part : m.meshes) {
    meshes.push_back(std::make_shared<const dem_core::TriangleMesh>(*part.triangles));
    raw.push_back(meshes.back().get());
    low = std::min(low, meshes.back()->lower().z);
    high = std::max(high, meshes.back()->upper().z);
  }
  const std::vector<double> radii = particle_radii(spec);
  const double r_max = *std::max_element(radii.begin(), radii.end());
  const std::vector<Vec3> sites = fill_positions(spec, r_max, raw);
  for (std::size_t i = 0; i < radii.size(); ++i) sim.add_particle(sites[i], radii[i]);
  for (double mass : sim.masses()) setup.total_mass += mass;
  for (std::size_t p = 0; p < m.meshes.size(); ++p) {
    const MeshPartSpec& part = m.meshes[p];
    dem_core::WallSpec wall{dem_core::MeshGeometry{meshes[p]}, dem_core::FixedMotion{}, spec.wall, {}, part.name};
    // The torque of a rotating part is about its rotation axis from the start (also before it turns).
    if (part.motion == MeshMotion::rotation)
      wall.torque_axis = dem_core::Axis{vec(part.axis_point), vec(part.axis_direction)};
    setup.part_wall.push_back(sim.add_wall(wall));
  }
  // Catch floor: a mesh height plus ten radii below the lowest mesh point and the counting plane.
  const double bottom = m.discharge_mass.enabled ? std::min(low, m.discharge_mass.plane_z) : low;
  setup.catch_floor_z = bottom - (high - low) - 10.0 * r_max;
  sim.add_wall({dem_core::PlaneGeometry{{0, 0, setup.catch_floor_z}, {0, 0, 1}},
                dem_core::FixedMotion{},
                spec.wall,
                {},
                "catch_floor"});
  return setup;
}

// Starts the motions whose start time has come (once each).
void start_motions(dem_core::Simulation& sim, const MeshContainerSpec& m, const Setup& setup,
                   std::vector<bool>& started) {
  for (std::size_t p = 0; p < m.meshes.size(); ++p) {
    const MeshPartSpec& part = m.meshes[p];
    if (started[p] || part.motion == MeshMotion::fixed || sim.time() + 1e-12 < part.start_time) continue;
    started[p] = true;
    if (part.motion == MeshMotion::rotation)
      sim.set_wall_motion(setup.part_wall[p],
                          dem_core::RotatingMotion{vec(part.axis_point), vec(part.axis_direction), omega_of(part)});
    else
      sim.set_wall_motion(setup.part_wall[p], dem_core::TranslatingMotion{vec(part.velocity)});
  }
}

// The fastest surface speed [m/s] of a moving part: |v|, or |omega| times its farthest vertex
// from the axis.
double part_speed(const MeshPartSpec& part) {
  if (part.motion == MeshMotion::translation) return std::hypot(part.velocity[0], part.velocity[1], part.velocity[2]);
  if (part.motion == MeshMotion::fixed) return 0.0;
  const Vec3 p = vec(part.axis_point), d = dem_core::normalized(vec(part.axis_direction));
  double reach = 0.0;
  for (const dem_core::Triangle& t : *part.triangles)
    for (const Vec3& v : t) {
      const Vec3 rel = v - p;
      reach = std::max(reach, dem_core::norm(rel - d * dem_core::dot(rel, d)));
    }
  return std::fabs(omega_of(part)) * reach;
}

struct Sample {
  double time = 0, discharged = 0, retained = 0, torque = 0, heap = 0, kinetic = 0;
};

struct Run {
  std::vector<Sample> samples;
  Setup setup;
  double time_step = 0.0;
  std::uint64_t steps = 0;
  CurveTable particles;
};

Sample sample_now(const dem_core::Simulation& s, const MeshContainerSpec& m) {
  Sample out;
  out.time = s.time();
  std::vector<std::array<double, 3>> resting;
  std::vector<double> resting_radii;
  for (std::size_t i = 0; i < s.particle_count(); ++i) {
    const Vec3 p = s.positions()[i];
    (m.discharge_mass.enabled && p.z < m.discharge_mass.plane_z ? out.discharged : out.retained) += s.masses()[i];
    if (m.heap_angle.enabled && dem_core::norm(s.velocities()[i]) < m.heap_angle.rest_speed) {
      resting.push_back({p.x, p.y, p.z});
      resting_radii.push_back(s.radii()[i]);
    }
  }
  out.heap = m.heap_angle.enabled ? heap_angle_degrees(resting, resting_radii, m.heap_angle)
                                  : std::numeric_limits<double>::quiet_NaN();
  out.kinetic = s.kinetic_energy();
  return out;
}

Run pour(const CaseSpec& spec, const CaseRunOptions& options) {
  const MeshContainerSpec& m = spec.mesh_container;
  dem_core::SimulationSettings settings = simulation_settings(spec);
  settings.gravity = {0.0, 0.0, -kGravity};
  settings.threads = options.threads;
  settings.time_step = spec.time_step.value;
  settings.time_step_factor = spec.time_step.factor;
  dem_core::Simulation sim(settings);
  sim.add_material(to_material(spec.material));
  Run run;
  run.setup = build(sim, spec);
  check_user_time_step(spec, sim);
  run.time_step = sim.time_step();
  std::vector<bool> started(m.meshes.size(), false);
  start_motions(sim, m, run.setup, started);
  std::size_t torque_wall = 0;
  double sense = 1.0;
  for (std::size_t p = 0; p < m.meshes.size(); ++p)
    if (m.moving_part_torque.enabled && m.meshes[p].name == m.moving_part_torque.mesh) {
      torque_wall = run.setup.part_wall[p];
      sense = m.meshes[p].rpm >= 0.0 ? 1.0 : -1.0;
    }
  // Sample k is taken at the first step that reaches k x output_interval (Simulation::reached),
  // so a run holds floor(duration / output_interval) samples whatever the time step.
  long long next_sample = 1;
  SnapshotSchedule snapshots(spec.output.snapshot_times, options.snapshot_dir.string(), "mesh_container");
  double torque_sum = 0.0;
  std::uint64_t in_sample = 0, steps_done = 0;
  auto callback = [&](dem_core::Simulation& s) {
    if (options.progress && (++steps_done & 255u) == 0) options.progress("pour", s.time(), m.duration);
    start_motions(s, m, run.setup, started);
    // Drive torque: minus the particles' moment on the part about its axis, signed with the
    // rotation, so a bed resisting the part gives a positive torque (as the drum's).
    if (m.moving_part_torque.enabled) torque_sum -= sense * s.wall_torque(torque_wall);
    snapshots.maybe_write(s, s.time());
    ++in_sample;
    if (!s.reached(static_cast<double>(next_sample) * m.output_interval)) return true;
    while (s.reached(static_cast<double>(next_sample) * m.output_interval)) ++next_sample;  // interval < step
    Sample out = sample_now(s, m);
    out.torque = torque_sum / static_cast<double>(in_sample);
    if (!std::isfinite(out.torque) || !std::isfinite(out.kinetic))
      throw std::runtime_error("mesh_container run diverged (non-finite torque or energy): lower time_step.factor");
    run.samples.push_back(out);
    torque_sum = 0.0;
    in_sample = 0;
    return true;
  };
  sim.run_until(m.duration, callback, 1);
  run.steps = sim.step_count();
  run.particles = CurveTable{{"particle centres at the end time; gravity -z"},
                             {"x_mm", "y_mm", "z_mm", "radius_mm"},
                             std::vector<std::vector<double>>(4)};
  for (std::size_t i : sim.particles().indices_by_id()) {
    const Vec3 p = sim.positions()[i];
    const double v[4] = {p.x * 1e3, p.y * 1e3, p.z * 1e3, sim.radii()[i] * 1e3};
    for (int c = 0; c < 4; ++c) run.particles.values[c].push_back(v[c]);
  }
  return run;
}

void check_before_run(const CaseSpec& spec, const CaseRunOptions& options) {
  const MeshContainerSpec& m = spec.mesh_container;
  const std::vector<double> radii = particle_radii(spec);
  const double smallest = *std::min_element(radii.begin(), radii.end());
  precheck_user_time_step(spec, spec.material.radius, spec.material.density);
  const double time_step = planned_time_step(spec, spec.material.radius, spec.material.density);
  for (std::size_t p = 0; p < m.meshes.size(); ++p)
    check_wall_travel_per_step("mesh_container.meshes[" + std::to_string(p) + "].motion", part_speed(m.meshes[p]),
                               smallest, time_step);
  check_run_budget("mesh_container", static_cast<double>(m.particle_count), m.duration, time_step, options);
}

}  // namespace

namespace {

// Mean discharge rate [kg/s]: least-squares slope of discharged mass against time over the
// samples between 20 % and 80 % of the final discharged mass (the steady part of the flow);
// NaN when fewer than two samples lie there.
double discharge_rate(const std::vector<Sample>& samples) {
  if (samples.empty()) return std::numeric_limits<double>::quiet_NaN();
  const double final_mass = samples.back().discharged;
  double n = 0, st = 0, sm = 0, stt = 0, stm = 0;
  for (const Sample& s : samples) {
    if (s.discharged < 0.2 * final_mass || s.discharged > 0.8 * final_mass) continue;
    n += 1;
    st += s.time;
    sm += s.discharged;
    stt += s.time * s.time;
    stm += s.time * s.discharged;
  }
  if (n < 2 || n * stt - st * st <= 0.0) return std::numeric_limits<double>::quiet_NaN();
  return (n * stm - st * sm) / (n * stt - st * st);
}

// Beverloo, Leniger & van de Velde (1961): W = C rho_b sqrt(g) (D0 - k d)^(5/2), C = 0.58,
// k = 1.5, bulk density rho_b = 0.6 rho_p (assumed). An order-of-magnitude reference only.
double beverloo_rate(double orifice, double mean_diameter, double density) {
  const double free = orifice - 1.5 * mean_diameter;
  if (free <= 0.0) return 0.0;
  return 0.58 * 0.6 * density * std::sqrt(kGravity) * std::pow(free, 2.5);
}

void add_curves(CaseResult& result, const Run& run, const MeshContainerSpec& m) {
  constexpr CaseKind kind = CaseKind::mesh_container;  // curve names and labels: case_registry.cpp
  identify::Curve heap = empty_curve(kind, "heap_angle"), discharge = empty_curve(kind, "discharge_mass"),
                  torque = empty_curve(kind, "moving_part_torque");
  for (const Sample& s : run.samples) {
    if (std::isfinite(s.heap)) {  // no heap yet (fewer than two occupied annuli): no point
      heap.x.push_back(s.time);
      heap.y.push_back(s.heap);
    }
    discharge.x.push_back(s.time);
    discharge.y.push_back(s.discharged);
    torque.x.push_back(s.time);
    torque.y.push_back(s.torque);
  }
  if (m.heap_angle.enabled) {
    if (heap.x.size() < 2)
      throw std::runtime_error(
          "mesh_container: the heap was found at fewer than 2 sample times: check outputs.heap_angle (center, base_z, "
          "r_min, r_max) against the pedestal, or raise duration");
    result.curves["heap_angle"] = heap;
  }
  if (m.discharge_mass.enabled) result.curves["discharge_mass"] = discharge;
  if (m.moving_part_torque.enabled) result.curves["moving_part_torque"] = torque;
  CurveTable history{
      {"mesh_container history: discharged = centres below outputs.discharge_mass.plane_z (0 without "
       "a discharge output), retained = the others; drive torque on the torque part; "
       "heap angle by: " +
       std::string(kHeapAngleDefinition)},
      {"time_s", "discharged_mass_kg", "retained_mass_kg", "drive_torque_Nm", "heap_angle_deg", "kinetic_energy_J"},
      std::vector<std::vector<double>>(6)};
  for (const Sample& s : run.samples) {
    const double v[6] = {s.time, s.discharged, s.retained, s.torque, s.heap, s.kinetic};
    for (int c = 0; c < 6; ++c) history.values[c].push_back(v[c]);
  }
  result.tables["history"] = history;
  result.tables["particles_end"] = run.particles;
}

void add_summary(CaseResult& result, const Run& run, const CaseSpec& spec, double seconds) {
  const MeshContainerSpec& m = spec.mesh_container;
  auto& sum = result.summary;
  if (spec.law != dem_core::ContactLawKind::lsdyna_linear) sum.emplace_back("contact law", to_string(spec.law));
  sum.emplace_back("particles", std::to_string(run.particles.values[3].size()));
  double mean_diameter = 0.0;
  for (double r : run.particles.values[3]) mean_diameter += 2e-3 * r;
  mean_diameter /= static_cast<double>(run.particles.values[3].size());
  sum.emplace_back("mean particle diameter [mm]", fmt("%.4f", mean_diameter * 1e3));
  sum.emplace_back("total particle mass [kg]", fmt("%.6g", run.setup.total_mass));
  sum.emplace_back("catch floor z [m] (particles falling past the meshes land here)",
                   fmt("%.5g", run.setup.catch_floor_z));
  const Sample& last = run.samples.back();
  if (m.heap_angle.enabled)
    sum.emplace_back("heap angle at the end [deg] (" + std::string(kHeapAngleDefinition) + ")", fmt("%.2f", last.heap));
  if (m.discharge_mass.enabled) {
    sum.emplace_back("discharged mass at the end [kg]", fmt("%.6g", last.discharged));
    const double rate = discharge_rate(run.samples);
    sum.emplace_back(
        "mean discharge rate [kg/s] (slope between 20 % and 80 % of the final discharged mass)",
        std::isfinite(rate) ? fmt("%.5g", rate) : std::string("not defined (too few samples in the flow)"));
    if (m.discharge_mass.orifice_diameter > 0.0)
      sum.emplace_back(
          "Beverloo reference rate [kg/s] (C 0.58, k 1.5, bulk density 0.6 rho_p; order of magnitude only)",
          fmt("%.5g", beverloo_rate(m.discharge_mass.orifice_diameter, mean_diameter, spec.material.density)));
  }
  if (m.moving_part_torque.enabled) {
    double mean = 0.0;
    int counted = 0;
    for (const Sample& s : run.samples)
      if (s.time >= 0.5 * m.duration) {
        mean += s.torque;
        ++counted;
      }
    sum.emplace_back("mean drive torque of '" + m.moving_part_torque.mesh + "', second half [N m]",
                     fmt("%.6g", counted ? mean / counted : 0.0));
  }
  sum.emplace_back("time step [s]", fmt("%.3e", run.time_step));
  sum.emplace_back("steps", std::to_string(run.steps));
  sum.emplace_back("wall time [s] (one evaluation)", fmt("%.1f", seconds));
}

}  // namespace

CaseResult run_mesh_container(const CaseSpec& spec, const CaseRunOptions& options) {
  check_before_run(spec, options);
  const auto start = Clock::now();
  const Run run = pour(spec, options);
  if (run.samples.empty()) throw std::runtime_error("mesh_container: no sample taken: lower output_interval");
  CaseResult result;
  add_curves(result, run, spec.mesh_container);
  add_summary(result, run, spec, std::chrono::duration<double>(Clock::now() - start).count());
  return result;
}

}  // namespace demfit::cases::detail
