// bench_dem: throughput of the DEM kernel (particle-steps per second) on the SPEC 2.2 drum and the
// SPEC 2.1 pellet bed with 1 and 2 threads, peak memory per particle, the cost of one case
// evaluation, and the ratio to LIGGGHTS on an equivalent problem. Prints numbers; asserts nothing.
#include <sys/resource.h>

#include <cstdio>
#include <cstdlib>
#include <string>

#include "bench_scenarios.hpp"
#include "demfit/dem_core/dem_core.hpp"
#include "liggghts_compare.hpp"

using namespace demfit;

namespace {


void throughput(const char* name, const dem_core::Simulation& prepared, std::uint64_t steps) {
  double wall[2] = {0, 0}, cpu[2] = {0, 0};
  for (int threads = 1; threads <= 2; ++threads) {
    dem_core::Simulation sim = prepared;  // same state for both thread counts
    sim.set_threads(threads);
    wall[threads - 1] = bench::time_steps(sim, steps, &cpu[threads - 1]);
  }
  const double work = static_cast<double>(prepared.particle_count()) * static_cast<double>(steps);
  std::printf("%-22s N=%5zu dt=%.3g s | 1 thread: %.3g particle-steps/s wall, %.3g per CPU-s | 2 threads: %.3g "
              "wall, speed-up %.2f (CPU %.2f s vs %.2f s)\n", name, prepared.particle_count(), prepared.time_step(),
              work / wall[0], work / cpu[0], work / wall[1], wall[0] / wall[1], cpu[0], cpu[1]);
}

/// One case evaluation each on 1 thread: s = 4 drum (3 s simulated) and pellet compressions.
void cases(const dem_core::Simulation& bed) {
  {
    const double fill_cpu_start = bench::cpu_seconds();
    dem_core::Simulation s4 = bench::make_drum(4.0, 0.3, 1);
    const double fill_cpu = bench::cpu_seconds() - fill_cpu_start;
    double cpu = 0.0;
    const double t = bench::time_steps(s4, static_cast<std::uint64_t>(2.7 / s4.time_step()), &cpu);
    std::printf("drum s=4: N=%zu, dt=%.3g s, fill + 0.3 s settle %.2f CPU-s, 2.7 s at 60 RPM %.2f s wall, %.2f CPU-s "
                "(1 thread) [target < 15 s for 3 s]\n", s4.particle_count(), s4.time_step(), fill_cpu, t, cpu);
  }
  for (double normk : {0.01, 0.875046}) {
    dem_core::Simulation p = bed;
    p.set_threads(1);
    dem_core::ContactParameters c = p.settings().contact;
    c.normk = normk;
    c.sheark = normk > 0.1 ? 0.299582 : 2.0 / 7.0;
    p.set_contact_parameters(c);
    double simulated = 0.0, reached = 0.0, cpu = 0.0;
    const double t = bench::time_compression(p, 0.05, 3.0e6, simulated, reached, &cpu);
    std::printf("pellet compression NORMK=%g: N=%zu, dt=%.3g s, %.4f s simulated to %.2f MPa took %.2f s wall, "
                "%.2f CPU-s (1 thread) [target < 30 s]\n", normk, p.particle_count(), p.time_step(), simulated,
                reached / 1e6, t, cpu);
  }
}

void compare(bool quick) {
  const bench::LiggghtsComparison cmp = bench::compare_with_liggghts(quick ? 3000 : 10000);
  std::printf("box settle, Hertz-Mindlin, N=%ld, dt=%.3g s, %ld steps: demfit %.2f CPU-s (1 thread)\n",
              cmp.particles, cmp.time_step, cmp.steps, cmp.demfit_seconds);
  if (!cmp.ran) {
    std::printf("LIGGGHTS comparison skipped: %s\n", cmp.note.c_str());
    return;
  }
  std::printf("LIGGGHTS (%ld atoms): loop %.2f s wall, process %.2f CPU-s -> speed ratio demfit/LIGGGHTS = %.2f "
              "(CPU, incl. LIGGGHTS setup) / %.2f (vs its loop wall time) [target >= 1.0] (%s)\n",
              cmp.liggghts_particles, cmp.liggghts_seconds, cmp.liggghts_cpu_seconds,
              cmp.liggghts_cpu_seconds / cmp.demfit_seconds, cmp.liggghts_seconds / cmp.demfit_seconds,
              cmp.note.c_str());
  std::printf("same physics check: kinetic energy at the end demfit %.4g J, LIGGGHTS %.4g J (translational)\n",
              cmp.demfit_kinetic_energy, cmp.liggghts_kinetic_energy);
}

}  // namespace

int main(int argc, char** argv) {
  bool quick = false;
  std::string only;
  for (int a = 1; a < argc; ++a) {
    const std::string arg = argv[a];
    if (arg == "--quick") quick = true;
    else if (arg == "--only" && a + 1 < argc) only = argv[++a];
    else {
      std::printf("usage: bench_dem [--quick] [--only throughput|cases|liggghts]\n");
      return EXIT_FAILURE;
    }
  }
  std::setvbuf(stdout, nullptr, _IOLBF, 0);  // progress visible when redirected
  auto wanted = [&](const char* section) { return only.empty() || only == section; };
  std::printf("bench_dem (dem_core)%s\n", quick ? " --quick" : "");
  if (wanted("throughput")) {
    const dem_core::Simulation drum = bench::make_drum(1.0, quick ? 0.02 : 0.1, 2);
    throughput("drum s=1, 60 RPM", drum, quick ? 100 : 400);
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    std::printf("peak memory (maxrss) %.1f MB = %.0f bytes per drum particle (includes the process baseline)\n",
                usage.ru_maxrss / 1024.0, usage.ru_maxrss * 1024.0 / static_cast<double>(drum.particle_count()));
  }
  if (wanted("throughput") || wanted("cases")) {
    const dem_core::Simulation bed = bench::make_pellet_bed(0.01, 2.0 / 7.0, quick ? 0.3 : 1.0, 2);
    if (wanted("throughput")) throughput("pellet bed (settled)", bed, quick ? 200 : 1000);
    if (wanted("cases")) cases(bed);
  }
  if (wanted("liggghts")) compare(quick);
  return EXIT_SUCCESS;
}
