// The physics cross-check (physics_check.hpp). Every figure printed here is measured in this run.
#include "physics_check.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <future>
#include <stdexcept>

#include "bench_timing.hpp"
#include "demfit/cases/bed_angles.hpp"
#include "demfit/dem_core/overlap_statistics.hpp"
#include "mesh_drum.hpp"
#include "physics_liggghts.hpp"

namespace demfit::bench {
namespace {
using dem_core::Simulation;

LawVariant variant_named(const std::string& name, double cohesion) {
  if (name == "cdt") return {"cdt"};
  if (name == "sjkr") return {"sjkr", cohesion, dem_core::CohesionModel::sjkr};
  if (name == "sjkr2") return {"sjkr2", cohesion, dem_core::CohesionModel::sjkr2};
  if (name == "epsd2") return {"epsd2", 0.0, dem_core::CohesionModel::sjkr, dem_core::RollingModel::elastic_plastic};
  throw std::runtime_error("--physics-variants: unknown variant '" + name + "' (use cdt, sjkr, sjkr2, epsd2)");
}

struct DemfitRun {
  PhysicsRun figures;
  double max_relative_overlap = 0.0;  ///< largest pair overlap / radius seen at the window ends
};

/// demfit's run of one variant: the same windows and snapshots the LIGGGHTS input asks for
/// (torque and centre of mass sampled every 10th step of each window).
DemfitRun run_demfit(const Simulation& bed, const HertzDrumSpec& spec, const LawVariant& v, long steps,
                     long window_steps) {
  dem_core::SimulationSettings settings = drum_restart_settings(spec, 1);
  settings.contact.cohesion_energy_density = v.cohesion_energy_density;
  settings.contact.cohesion_model = v.cohesion;
  settings.contact.rolling_model = v.rolling;
  Simulation sim = restart_drum(bed, spec, settings, nullptr);
  DemfitRun run;
  for (long done = 0; done < steps; done += window_steps) {
    double torque = 0.0, centre = 0.0;
    int samples = 0;
    for (long s = 0; s < window_steps; s += 10) {
      run.figures.wall_seconds += wall_seconds_for_steps(sim, 10);
      double walls = 0.0;
      for (std::size_t w = 0; w < sim.wall_count(); ++w) walls += sim.wall_torque(w);
      torque -= walls;  // the drive balances the moment the bed exerts on the walls
      centre += centre_of_mass(sim).x;
      ++samples;
    }
    const double t = static_cast<double>(done + window_steps) * spec.time_step;
    run.figures.windows.push_back({t, torque / samples, centre / samples});
    BedSnapshot snap;
    snap.time = t;
    for (std::size_t i = 0; i < sim.particle_count(); ++i) {
      const dem_core::Vec3& x = sim.positions()[i];
      snap.positions.push_back({x.x, x.y, x.z});
      snap.radii.push_back(sim.radii()[i]);
    }
    run.figures.snapshots.push_back(std::move(snap));
    run.max_relative_overlap =
        std::max(run.max_relative_overlap, dem_core::pair_overlap_statistics(sim).max_relative_overlap);
  }
  run.figures.ok = true;
  return run;
}

struct Summary {
  double torque = 0.0, gravity_moment = 0.0;  ///< means over the second half [N m]
  double angle = 0.0, angle_spread = 0.0;     ///< slab angle mean and standard deviation [deg]
  int angles = 0;
};

Summary summarise(const PhysicsRun& run, double run_time, double bed_mass, double gravity, double depth) {
  Summary s;
  int n = 0;
  for (const WindowFigures& w : run.windows)
    if (w.time > 0.5 * run_time + 1e-9) {
      s.torque += w.drive_torque;
      s.gravity_moment += bed_mass * gravity * w.centre_x;
      ++n;
    }
  if (n > 0) {
    s.torque /= n;
    s.gravity_moment /= n;
  }
  std::vector<double> angles;
  for (const BedSnapshot& b : run.snapshots)
    if (b.time > 0.5 * run_time + 1e-9)
      angles.push_back(cases::slab_surface_angle_degrees(b.positions, b.radii, depth));
  for (double a : angles) s.angle += a;
  s.angles = static_cast<int>(angles.size());
  if (s.angles > 0) s.angle /= s.angles;
  for (double a : angles) s.angle_spread += (a - s.angle) * (a - s.angle);
  if (s.angles > 1) s.angle_spread = std::sqrt(s.angle_spread / (s.angles - 1));
  return s;
}

void print_series(const char* code, const PhysicsRun& run) {
  std::printf("    %-8s drive torque per window [N m]:", code);
  for (const WindowFigures& w : run.windows) std::printf(" %.5f", w.drive_torque);
  std::printf("\n");
}

void print_differences(double cohesion) {
  std::printf(
      "What differs between the two runs besides the codes (LIGGGHTS 3.8 source read: cohesion_model_sjkr.h,\n"
      "rolling_model_cdt.h, rolling_model_epsd2.h, normal_model_hertz.h, tangential_model_history.h,\n"
      "surface_model_default.h, fix_wall_gran_base.h, fix_mesh_surface_stress):\n"
      "  - walls: LIGGGHTS the STL mesh, demfit the analytic cylinder and disks.\n"
      "  - drive torque: LIGGGHTS' mesh/surface/stress sums the moments of the contact forces only; demfit's wall\n"
      "    torque also counts the rolling couples -M_r of the wall contacts (the gravity moment M g x_c counts\n"
      "    everything in both).\n"
      "  - rolling on a moving wall: LIGGGHTS takes the particle's own spin (R - delta/2)/(R - delta) omega_i as the\n"
      "    relative rotation (the mesh's rotation is not subtracted); demfit omega_i - omega_wall.\n"
      "  - cdt magnitude: LIGGGHTS mu_r k_n delta R* (elastic Hertz force only), demfit mu_r |F_n| R* with F_n the\n"
      "    repulsive force including its damping, capped at what stops the relative rotation in one step.\n"
      "  - tangential spring: LIGGGHTS projects the stored spring on the tangent plane (length not kept) and\n"
      "    limits only the elastic part (damping added when sticking); demfit keeps its length and limits elastic\n"
      "    plus damping.\n"
      "  - epsd2: same k_r = k_t R*^2 (k_t = 8 G* a) and cap mu_r R* |F_n|; LIGGGHTS keeps the stored torque as\n"
      "    is, demfit turns it into the current tangent plane (length kept).\n"
      "  - sjkr (k_c = %.4g J/m^3, pairs and walls): same lens area (pairs) and plane cap delta (2R - delta)\n"
      "    (walls); friction and rolling limits see the repulsive force only in both (LIGGGHTS' default\n"
      "    tangential_reduce off).\n",
      cohesion);
}

}  // namespace

void check_physics_against_liggghts(const PhysicsCheckOptions& o) {
  const HertzDrumSpec spec;
  if (liggghts_executable().empty()) {
    std::printf("physics: LIGGGHTS not on PATH (install: scripts/setup --bench): nothing to compare\n");
    return;
  }
  std::vector<LawVariant> variants;
  for (const std::string& name : o.variants) variants.push_back(variant_named(name, o.cohesion_energy_density));
  const long window_steps = std::lround(o.window / spec.time_step);
  const long steps = window_steps * std::lround(o.run_time / o.window);
  std::printf("physics: preparing the bed: settle %.2f s, turn %.2f s at 60 RPM with cdt (1 thread) ... [%s]\n",
              o.settle_time, o.spin_up_time, load_average().c_str());
  const Simulation bed = make_hertz_drum(spec, o.settle_time, o.spin_up_time, 1);
  double mass = 0.0;
  for (std::size_t i = 0; i < bed.particle_count(); ++i) mass += bed.masses()[i];
  const std::size_t triangles = write_liggghts_drum(o.dir, spec, bed, steps, o.mesh);
  std::printf(
      "physics: N=%zu, bed mass %.5g kg, t0=%.3f s; each variant %.3f s (%ld steps of %.3g s), windows of %.3f s;\n"
      "  LIGGGHTS files in %s (drum.stl %zu triangles); demfit 1 thread, LIGGGHTS 1 rank, run side by side\n",
      bed.particle_count(), mass, bed.time(), static_cast<double>(steps) * spec.time_step, steps, spec.time_step,
      o.window, o.dir.c_str(), triangles);
  std::printf("%-6s | %-29s | %-29s | %-27s | %s\n", "law", "drive torque [N m] d / L", "gravity moment [N m] d / L",
              "slab angle [deg] d / L", "wall s d / L, load");
  std::vector<std::string> rows;
  for (const LawVariant& v : variants) {
    write_physics_input(o.dir, spec, v, steps, window_steps);
    auto liggghts = std::async(std::launch::async, [&] { return run_liggghts_physics(o.dir, v, spec.time_step); });
    const DemfitRun d = run_demfit(bed, spec, v, steps, window_steps);
    const PhysicsRun l = liggghts.get();
    std::printf("  %s (%s): demfit largest pair overlap %.2f %% of the radius\n", v.name.c_str(),
                liggghts_model_words(v).c_str(), 100.0 * d.max_relative_overlap);
    print_series("demfit", d.figures);
    if (!l.ok) {
      std::printf("    LIGGGHTS: %s\n", l.note.c_str());
      continue;
    }
    print_series("LIGGGHTS", l);
    const Summary a = summarise(d.figures, o.run_time, mass, spec.gravity, spec.depth);
    const Summary b = summarise(l, o.run_time, mass, spec.gravity, spec.depth);
    char row[600];
    std::snprintf(row, sizeof row,
                  "%-6s | %.5f / %.5f (%+5.1f %%) | %.5f / %.5f (%+5.1f %%) | %5.2f+-%.2f / %5.2f+-%.2f (%+.2f) | "
                  "%.0f / %.0f, %s",
                  v.name.c_str(), a.torque, b.torque, 100.0 * (a.torque / b.torque - 1.0), a.gravity_moment,
                  b.gravity_moment, 100.0 * (a.gravity_moment / b.gravity_moment - 1.0), a.angle, a.angle_spread,
                  b.angle, b.angle_spread, a.angle - b.angle, d.figures.wall_seconds, l.wall_seconds,
                  load_average().c_str());
    std::printf("%s\n", row);
    rows.emplace_back(row);
  }
  std::printf(
      "summary (second-half means; slab angle over the second half's snapshots; targets: torque within 5 %%,\n"
      "slab angle within 2 deg of LIGGGHTS):\n");
  for (const std::string& r : rows) std::printf("%s\n", r.c_str());
  print_differences(o.cohesion_energy_density);
}

}  // namespace demfit::bench
