// The kernel comparison against LIGGGHTS. Every figure printed here is measured in this run.
#include "drum_comparison.hpp"

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "bench_timing.hpp"
#include "hertz_drum.hpp"
#include "demfit/dem_core/stl_mesh.hpp"
#include "drum_mesh.hpp"
#include "liggghts_drum.hpp"
#include "mesh_drum.hpp"

namespace demfit::bench {
namespace {
using dem_core::Simulation;

struct Series {
  std::vector<double> rates;  // particle-steps/s per repeat
  [[nodiscard]] double median_rate() const { return median(rates); }
};

// The kernel's defaults (slab order at list rebuilds, pair loads in ascending first member);
// a variant switches one of them off to time that lever.
struct Variant {
  bool reorder = true;
  dem_core::PairLoadOrder order = dem_core::PairLoadOrder::ascending_first_member;
  const char* label = "";
};
const Variant kStoredOrder{false, dem_core::PairLoadOrder::ascending_first_member, " stored order"};
const Variant kOwnRowFirst{true, dem_core::PairLoadOrder::own_row_first, " own_row_first"};

/// Share of the neighbour list's pairs whose second member lies past the row where half of the
/// pairs are reached: the pairs two equal chunks would have to exchange (a property of the
/// particle order, independent of timing; the kernel's measured split sits near the middle).
double crossing_share_at_middle(const dem_core::NeighborList& list) {
  const auto rows = list.row_offsets();
  const auto second = list.second();
  if (rows.size() < 2 || second.empty()) return 0.0;
  const auto half = static_cast<std::uint32_t>(second.size() / 2);
  const auto middle = static_cast<std::uint32_t>(std::lower_bound(rows.begin(), rows.end(), half) - rows.begin());
  std::size_t crossing = 0;
  for (std::uint32_t i = 0; i < middle; ++i)
    for (std::uint32_t k = rows[i]; k < rows[i + 1]; ++k) crossing += second[k] >= middle ? 1 : 0;
  return static_cast<double>(crossing) / static_cast<double>(second.size());
}

/// What the timed runs' drum walls are ("analytic walls" or "mesh N triangles"), printed beside every rate.
struct Walls {
  std::string demfit, liggghts;
};

double time_demfit(const Simulation& prepared, const Walls& walls, int threads, long steps, Simulation* keep,
                   const Variant& v = {}) {
  Simulation sim = prepared;
  sim.set_threads(threads);
  sim.set_reorder_particles(v.reorder);
  sim.set_pair_load_order(v.order);
  const std::size_t builds = sim.neighbor_list().build_count();
  const std::uint64_t faults = minor_page_faults();
  const double seconds = wall_seconds_for_steps(sim, static_cast<std::uint64_t>(steps));
  const std::uint64_t new_pages = minor_page_faults() - faults;
  const double rate = static_cast<double>(sim.particle_count()) * static_cast<double>(steps) / seconds;
  std::printf(
      "  demfit   %d thread%s %8.3f s  %6.3g M particle-steps/s  (%zu list builds, %.1f %% of pairs cross the "
      "middle, %llu page faults)%s  {%s}  [%s]\n",
      threads, threads > 1 ? "s" : " ", seconds, rate / 1e6, sim.neighbor_list().build_count() - builds,
      100.0 * crossing_share_at_middle(sim.neighbor_list()), static_cast<unsigned long long>(new_pages), v.label,
      walls.demfit.c_str(), load_average().c_str());
  if (keep != nullptr) *keep = std::move(sim);
  return rate;
}

double time_liggghts(const std::filesystem::path& dir, const Walls& walls, int px, int py, int pz, LiggghtsRun* keep) {
  const std::string name = "run_" + std::to_string(px) + std::to_string(py) + std::to_string(pz);
  const LiggghtsRun run = run_liggghts_drum(dir, px, py, pz, name);
  if (!run.ok) {
    std::printf("  LIGGGHTS %d %d %d: %s\n", px, py, pz, run.note.c_str());
    return 0.0;
  }
  std::printf(
      "  LIGGGHTS %ld rank%s %d %d %d %8.3f s  %6.3g M particle-steps/s  (%ld list builds, %ld atoms)  {%s}  [%s]\n",
      run.procs, run.procs > 1 ? "s" : " ", px, py, pz, run.loop_seconds, run.particle_steps_per_second() / 1e6,
      run.neighbour_builds, run.atoms, walls.liggghts.c_str(), load_average().c_str());
  if (keep != nullptr) *keep = run;
  return run.particle_steps_per_second();
}

void print_differences(std::size_t triangles, bool demfit_mesh) {
  if (demfit_mesh)
    std::printf(
        "What still differs (and which way it biases the ratio demfit/LIGGGHTS):\n"
        "  - drum wall: both the same triangle mesh (%zu triangles), demfit restarted on it without contact\n"
        "    histories as LIGGGHTS is. No wall bias.\n",
        triangles);
  else
    std::printf(
        "What still differs (and which way it biases the ratio demfit/LIGGGHTS):\n"
        "  - drum wall: LIGGGHTS a triangle mesh (%zu triangles: shell + both end caps, facets within ~1 um of the\n"
        "    cylinder), demfit an analytic cylinder and two disks. Mesh contact search costs more: favours demfit.\n",
        triangles);
  std::printf(
      "  - rolling friction: both constant directional torque (LIGGGHTS `rolling_friction cdt`, chosen over\n"
      "    epsd2 because demfit's model is a constant torque mu_r |F_n| R*); demfit caps the torque at what stops\n"
      "    the relative rotation in one step, cdt does not. Same work per contact: no bias expected.\n"
      "  - neighbour lists: both binned, skin 0.5 mm, rebuilt when a particle moved more than half the skin\n"
      "    (LIGGGHTS `neigh_modify delay 0`, check yes); LIGGGHTS also keeps mesh-element neighbour lists.\n"
      "    Build counts are printed per run; more builds on one side bias against that side.\n"
      "  - start: LIGGGHTS reads positions, velocities and spins but no tangential spring history (restarts at\n"
      "    zero); demfit continues with its history. Physics only, no cost bias.\n"
      "  - timing: LIGGGHTS' `Loop time` excludes its setup (reading, first list build); demfit's time includes\n"
      "    its first list build. Slightly against demfit.\n"
      "  - output: LIGGGHTS computes one thermo line at the first and last step (kinetic energy, centre of\n"
      "    mass); demfit none during the timed steps. Negligible.\n"
      "  - parallelism: demfit OpenMP threads (bounded spin, then sleep: the waiting line above) vs LIGGGHTS MPI\n"
      "    ranks (unbound,\n"
      "    mpi_yield_when_idle 1, best of the splits 2 1 1 and 1 2 1, with ghost-atom exchange). Inherent\n"
      "    to the codes; on a loaded machine MPI ranks suffer more from a preempted partner.\n");
}

}  // namespace

void compare_drum_with_liggghts(const DrumComparisonOptions& o) {
  const HertzDrumSpec spec;
  std::printf("drum: preparing the bed: settle %.2f s, turn %.2f s at 60 RPM (2 threads) ...\n",
              o.settle_time, o.spin_up_time);
  const Simulation bed = make_hertz_drum(spec, o.settle_time, o.spin_up_time, 2);
  std::printf(
      "drum: N=%zu spheres R=%.3g m, drum D=%.3g m x %.3g m, Hertz-Mindlin E=%.3g Pa nu=%.2g e=%.2g mu=%.2g "
      "mu_r=%.2g, dt=%.3g s, skin=%.3g m, %ld steps, t0=%.3f s\n",
      bed.particle_count(), spec.radius, 2 * spec.drum_radius, spec.depth, spec.youngs_modulus, spec.poisson_ratio,
      spec.restitution, spec.sliding_friction, spec.rolling_friction, spec.time_step, spec.skin, o.steps, bed.time());
  std::printf("this host: a fresh page (page fault) costs %.1f us; freed memory %s\n", fresh_page_microseconds(),
              o.memory_retention.c_str());
  const bool have_liggghts = o.liggghts && !liggghts_executable().empty();
  std::size_t triangles = 0;
  if (have_liggghts) {
    triangles = write_liggghts_drum(o.dir, spec, bed, o.steps, o.mesh);
    std::printf("LIGGGHTS files (bed.data, drum.stl with %zu triangles, in.drum) in %s\n", triangles, o.dir.c_str());
  } else {
    std::printf(o.liggghts ? "LIGGGHTS not on PATH: timing demfit only (install: scripts/setup --bench)\n"
                           : "--no-liggghts: timing demfit only\n");
  }
  // demfit's walls: the analytic drum, or (--demfit-mesh) the same STL as LIGGGHTS' read back
  // through dem_core::parse_stl as one rotating mesh wall, the particles restarted without
  // contact histories as LIGGGHTS restarts them.
  Walls walls{"analytic walls", "mesh " + std::to_string(triangles) + " triangles"};
  Simulation demfit_bed = bed;
  if (o.demfit_mesh) {
    std::ostringstream stl;
    const std::size_t meshed = write_drum_stl(stl, {spec.drum_radius, spec.depth, bed.wall(0).rotation_angle,
                                                    o.mesh.segments, o.mesh.shell_rings, o.mesh.cap_rings});
    const auto mesh =
        std::make_shared<const dem_core::TriangleMesh>(dem_core::parse_stl(stl.str(), {1.0}, "drum mesh"));
    demfit_bed = restart_drum(bed, spec, drum_restart_settings(spec, 2), mesh);
    walls.demfit = "mesh " + std::to_string(meshed) + " triangles";
    std::printf("demfit on the STL drum: %zu triangles, %zu contact cells, same shape and angle as LIGGGHTS'\n", meshed,
                mesh->cell_count());
  }
  Series d1, d2, l1, l2, l1_bound, d1_stored, d2_stored, d1_own, d2_own;
  Simulation demfit_end;
  LiggghtsRun liggghts_end;
  for (int r = 0; r < o.repeats; ++r) {
    std::printf("repeat %d of %d:\n", r + 1, o.repeats);
    d1.rates.push_back(time_demfit(demfit_bed, walls, 1, o.steps, &demfit_end));
    if (have_liggghts) {
      l1.rates.push_back(time_liggghts(o.dir, walls, 1, 1, 1, &liggghts_end));
      l1_bound.rates.push_back(liggghts_end.particle_steps_per_second_without_fixes());
    }
    d2.rates.push_back(time_demfit(demfit_bed, walls, 2, o.steps, nullptr));
    d1_stored.rates.push_back(time_demfit(demfit_bed, walls, 1, o.steps, nullptr, kStoredOrder));
    d2_stored.rates.push_back(time_demfit(demfit_bed, walls, 2, o.steps, nullptr, kStoredOrder));
    d1_own.rates.push_back(time_demfit(demfit_bed, walls, 1, o.steps, nullptr, kOwnRowFirst));
    d2_own.rates.push_back(time_demfit(demfit_bed, walls, 2, o.steps, nullptr, kOwnRowFirst));
    if (have_liggghts) {
      const double a = time_liggghts(o.dir, walls, 2, 1, 1, nullptr);
      const double b = time_liggghts(o.dir, walls, 1, 2, 1, nullptr);
      l2.rates.push_back(std::max(a, b));
    }
  }
  std::printf("medians of %d (M particle-steps/s; demfit {%s}, LIGGGHTS {%s})  [%s]\n", o.repeats, walls.demfit.c_str(),
              walls.liggghts.c_str(), load_average().c_str());
  std::printf("  1 core : demfit %.3g  LIGGGHTS %.3g  ratio %.2f   [target >= 2.0]\n", d1.median_rate() / 1e6,
              l1.median_rate() / 1e6, have_liggghts ? d1.median_rate() / l1.median_rate() : 0.0);
  std::printf("  2 cores: demfit %.3g  LIGGGHTS best split %.3g  ratio %.2f   [target >= 2.0]\n",
              d2.median_rate() / 1e6, l2.median_rate() / 1e6,
              have_liggghts ? d2.median_rate() / l2.median_rate() : 0.0);
  std::printf(
      "  1 core, LIGGGHTS counting only its pair + neighbour + comm time (as if its mesh walls and integration\n"
      "         were free): %.3g -> ratio %.2f (a lower bound on demfit's lead without the mesh)\n",
      l1_bound.median_rate() / 1e6, have_liggghts ? d1.median_rate() / l1_bound.median_rate() : 0.0);
  std::printf(
      "  demfit without reorder_particles (stored order; the default reorders into slabs at rebuilds):\n"
      "         1 thread %.3g (default x%.2f faster), 2 threads %.3g (default x%.2f), speed-up %.2f\n",
      d1_stored.median_rate() / 1e6, d1.median_rate() / d1_stored.median_rate(), d2_stored.median_rate() / 1e6,
      d2.median_rate() / d2_stored.median_rate(), d2_stored.median_rate() / d1_stored.median_rate());
  std::printf(
      "  demfit with pair_load_order own_row_first (per-pair stored loads gathered; the cases' default):\n"
      "         1 thread %.3g (default x%.2f faster), 2 threads %.3g (default x%.2f), speed-up %.2f\n",
      d1_own.median_rate() / 1e6, d1.median_rate() / d1_own.median_rate(), d2_own.median_rate() / 1e6,
      d2.median_rate() / d2_own.median_rate(), d2_own.median_rate() / d1_own.median_rate());
  std::printf("  speed-up 1 -> 2 cores: demfit %.2f [target >= 1.85]", d2.median_rate() / d1.median_rate());
  if (have_liggghts) std::printf("  LIGGGHTS %.2f", l2.median_rate() / l1.median_rate());
  std::printf("\n");
  const dem_core::Vec3 c = centre_of_mass(demfit_end);
  std::printf(
      "same-physics check after %ld steps: translational KE demfit %.4g J, LIGGGHTS %.4g J; centre of mass "
      "x,y demfit %.4g %.4g m, LIGGGHTS %.4g %.4g m\n",
      o.steps, translational_kinetic_energy(demfit_end), liggghts_end.kinetic_energy, c.x, c.y, liggghts_end.centre_x,
      liggghts_end.centre_y);
  print_differences(triangles, o.demfit_mesh);
  std::printf(
      "These figures were measured on a shared machine unless the load averages above are ~0: re-run on a "
      "quiet machine for the record.\n");
}

}  // namespace demfit::bench
