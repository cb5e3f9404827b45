// bench_dem: throughput of the DEM kernel (particle-steps per second) on the docs/spec.md 2.2 drum and the
// docs/spec.md 2.1 pellet bed with 1 and 2 threads, peak memory per particle, the cost of one case
// evaluation; demfit vs LIGGGHTS on the same settled drum and a 10^3..10^6 scaling table.
// Prints numbers; asserts nothing.
#include <sys/resource.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <sstream>
#include <string>

#include "bench_scenarios.hpp"
#include "demfit/dem_core/dem_core.hpp"
#include "demfit/dem_core/memory_retention.hpp"
#include "demfit/dem_core/openmp_waiting.hpp"
#include "drum_comparison.hpp"
#include "mesh_drum.hpp"
#include "physics_check.hpp"
#include "roundoff.hpp"
#include "scaling.hpp"

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
  std::printf(
      "%-22s N=%5zu dt=%.3g s | 1 thread: %.3g particle-steps/s wall, %.3g per CPU-s | 2 threads: %.3g "
      "wall, speed-up %.2f (CPU %.2f s vs %.2f s)\n",
      name, prepared.particle_count(), prepared.time_step(), work / wall[0], work / cpu[0], work / wall[1],
      wall[0] / wall[1], cpu[0], cpu[1]);
}

/// One case evaluation each on 1 thread: s = 4 drum (3 s simulated) and pellet compressions.
void cases(const dem_core::Simulation& bed) {
  {
    const double fill_cpu_start = bench::cpu_seconds();
    dem_core::Simulation s4 = bench::make_drum(4.0, 0.3, 1);
    const double fill_cpu = bench::cpu_seconds() - fill_cpu_start;
    double cpu = 0.0;
    const double t = bench::time_steps(s4, static_cast<std::uint64_t>(2.7 / s4.time_step()), &cpu);
    std::printf(
        "drum s=4: N=%zu, dt=%.3g s, fill + 0.3 s settle %.2f CPU-s, 2.7 s at 60 RPM %.2f s wall, %.2f CPU-s "
        "(1 thread) [target < 15 s for 3 s]\n",
        s4.particle_count(), s4.time_step(), fill_cpu, t, cpu);
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
    std::printf(
        "pellet compression NORMK=%g: N=%zu, dt=%.3g s, %.4f s simulated to %.2f MPa took %.2f s wall, "
        "%.2f CPU-s (1 thread) [target < 30 s]\n",
        normk, p.particle_count(), p.time_step(), simulated, reached / 1e6, t, cpu);
  }
}

}  // namespace

int usage() {
  std::printf(
      "usage: bench_dem [--quick] [--only drum|scaling|roundoff|throughput|cases|mesh|physics]\n"
      "                 [--steps N (drum, 10000)]\n"
      "                 [--repeats N (3)] [--spin-up SECONDS (1.0)] [--dir PATH (LIGGGHTS files)]\n"
      "                 [--mesh SEGMENTS SHELL_RINGS CAP_RINGS (360 1 2)]\n"
      "                 [--scaling-work PARTICLE_STEPS (1e7)] [--scaling-sizes N,N,.. (1000,10000,100000,1000000)]\n"
      "                 [--lattice-order] [--no-liggghts (drum: time demfit only)]\n"
      "                 [--demfit-mesh (drum: demfit on LIGGGHTS' STL drum, one rotating mesh wall)]\n"
      "                 [--physics-time SECONDS (0.5)] [--cohesion J_PER_M3 (35000, the sjkr variant)]\n"
      "                 [--physics-variants cdt,sjkr,sjkr2,epsd2 (cdt,sjkr,epsd2)]\n"
      "                 (physics runs only with --only physics: 10-45 min; its --spin-up default is 0.5 s)\n"
      "                 [--malloc-defaults (glibc's own thresholds instead of retain_freed_memory)]\n");
  return EXIT_FAILURE;
}

int main(int argc, char** argv) {
  dem_core::use_bounded_spin_waiting(argv);  // as the demfit CLI waits
  // As the demfit CLI keeps freed memory, unless --malloc-defaults (an A/B of the retention).
  bool malloc_defaults = false;
  for (int a = 1; a < argc; ++a) malloc_defaults = malloc_defaults || std::string(argv[a]) == "--malloc-defaults";
  const bool retained = !malloc_defaults && dem_core::retain_freed_memory();
  if (argc == 7 && std::string(argv[1]) == "--scaling-child")
    return bench::run_scaling_child(std::stoul(argv[2]), std::stol(argv[3]), std::stoi(argv[4]),
                                    std::string(argv[5]) == "shuffled", argv[6]);
  bool quick = false;
  std::string only;
  bench::DrumComparisonOptions drum;
  drum.dir = std::filesystem::temp_directory_path() / ("demfit_bench_drum_" + std::to_string(getpid()));
  drum.memory_retention =
      retained ? "kept in the process (retain_freed_memory, as the CLI)" : "returned to the kernel (glibc defaults)";
  bench::ScalingOptions scaling;
  bench::MeshDrumOptions mesh_drum;
  bench::PhysicsCheckOptions physics;
  physics.dir = std::filesystem::temp_directory_path() / ("demfit_bench_physics_" + std::to_string(getpid()));
  for (int a = 1; a < argc; ++a) {
    const std::string arg = argv[a];
    const bool has_value = a + 1 < argc;
    if (arg == "--quick")
      quick = true;
    else if (arg == "--only" && has_value)
      only = argv[++a];
    else if (arg == "--steps" && has_value)
      drum.steps = mesh_drum.steps = std::stoul(argv[++a]);
    else if (arg == "--repeats" && has_value)
      drum.repeats = scaling.repeats = mesh_drum.repeats = std::stoi(argv[++a]);
    else if (arg == "--spin-up" && has_value)
      drum.spin_up_time = mesh_drum.spin_up_time = physics.spin_up_time = std::stod(argv[++a]);
    else if (arg == "--dir" && has_value)
      drum.dir = physics.dir = argv[++a];
    else if (arg == "--demfit-mesh")
      drum.demfit_mesh = true;
    else if (arg == "--physics-time" && has_value)
      physics.run_time = std::stod(argv[++a]);
    else if (arg == "--cohesion" && has_value)
      physics.cohesion_energy_density = std::stod(argv[++a]);
    else if (arg == "--physics-variants" && has_value) {
      physics.variants.clear();
      std::stringstream list(argv[++a]);
      for (std::string v; std::getline(list, v, ',');) physics.variants.push_back(v);
    } else if (arg == "--scaling-work" && has_value)
      scaling.work = std::stod(argv[++a]);
    else if (arg == "--no-liggghts")
      drum.liggghts = false;
    else if (arg == "--malloc-defaults")
      continue;  // read above
    else if (arg == "--lattice-order")
      scaling.shuffled = false;
    else if (arg == "--scaling-sizes" && has_value) {
      scaling.sizes.clear();
      std::stringstream list(argv[++a]);
      for (std::string n; std::getline(list, n, ',');) scaling.sizes.push_back(std::stoul(n));
    } else if (arg == "--mesh" && a + 3 < argc) {
      drum.mesh.segments = std::stoi(argv[++a]);
      drum.mesh.shell_rings = std::stoi(argv[++a]);
      drum.mesh.cap_rings = std::stoi(argv[++a]);
      physics.mesh = drum.mesh;
      mesh_drum.segments = drum.mesh.segments, mesh_drum.shell_rings = drum.mesh.shell_rings;
      mesh_drum.cap_rings = drum.mesh.cap_rings;
    } else
      return usage();
  }
  std::setvbuf(stdout, nullptr, _IOLBF, 0);  // progress visible when redirected
  auto wanted = [&](const char* section) { return only.empty() || only == section; };
  std::printf("bench_dem (dem_core)%s, %s\n", quick ? " --quick" : "", dem_core::openmp_waiting_description().c_str());
  if (wanted("drum")) bench::compare_drum_with_liggghts(drum);
  if (wanted("mesh")) bench::compare_meshed_drum(mesh_drum);
  if (only == "physics") {  // long: on request only
    try {
      bench::check_physics_against_liggghts(physics);
    } catch (const std::exception& e) {  // e.g. an unknown --physics-variants name, before any run
      std::fprintf(stderr, "bench_dem: %s\n", e.what());
      return EXIT_FAILURE;
    }
  }
  if (wanted("scaling")) bench::print_scaling_table(scaling);
  if (wanted("roundoff")) bench::print_reordering_roundoff(quick);
  if (wanted("throughput")) {
    const dem_core::Simulation drum_s1 = bench::make_drum(1.0, quick ? 0.02 : 0.1, 2);
    throughput("drum s=1, 60 RPM", drum_s1, quick ? 100 : 400);
  }
  if (wanted("throughput") || wanted("cases")) {
    const dem_core::Simulation bed = bench::make_pellet_bed(0.01, 2.0 / 7.0, quick ? 0.3 : 1.0, 2);
    if (wanted("throughput")) throughput("pellet bed (settled)", bed, quick ? 200 : 1000);
    if (wanted("cases")) cases(bed);
  }
  return EXIT_SUCCESS;
}
