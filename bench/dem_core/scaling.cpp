// The box: a face-centred cubic lattice of touching spheres (the drum's material, R = 1 mm,
// Hertz–Mindlin), 10 layers high on a floor between four side planes, gravity -z; the base grows
// with N so every size has the same contacts per particle (6 pairs in the half list). 10..50
// warm-up steps (lists built, first transients) precede the timed steps. Each size runs once per
// PairLoadOrder, in its own child; peak memory is the child's ru_maxrss after the warm-up (2
// threads, slab order: dem_core's defaults) and one forced list rebuild, before the box of
// the stored-order A/B is built.
#include "scaling.hpp"

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>

#include "bench_timing.hpp"
#include "child_process.hpp"
#include "hertz_drum.hpp"

namespace demfit::bench {
namespace {
using namespace dem_core;

Simulation make_box(std::size_t target, bool shuffled, PairLoadOrder order) {
  const HertzDrumSpec spec;  // same material, law, step and skin as the drum
  SimulationSettings settings = hertz_settings(spec, SimulationSettings{}.threads);
  settings.pair_load_order = order;
  Simulation sim(settings);
  add_hertz_material(sim, spec);
  const double r = spec.radius, a = 2.0 * std::sqrt(2.0) * r;  // fcc cell: nearest distance 2R
  const long cells_z = 5,
             side = std::max<long>(1, std::lround(std::sqrt(static_cast<double>(target) / (4.0 * cells_z))));
  std::vector<Vec3> sites;
  const double basis[4][3] = {{0, 0, 0}, {0.5, 0.5, 0}, {0.5, 0, 0.5}, {0, 0.5, 0.5}};
  for (long k = 0; k < cells_z; ++k)
    for (long j = 0; j < side; ++j)
      for (long i = 0; i < side; ++i)
        for (const auto& b : basis) sites.push_back({(i + b[0]) * a, (j + b[1]) * a, (k + b[2]) * a});
  if (shuffled) {
    std::mt19937_64 random(7);
    for (std::size_t n = sites.size(); n > 1; --n) std::swap(sites[n - 1], sites[random() % n]);
  }
  for (const Vec3& x : sites) sim.add_particle(x, r);
  WallContactParameters wall;
  wall.frics = spec.sliding_friction;
  wall.fricd = spec.rolling_friction;
  wall.youngs_modulus = spec.youngs_modulus;
  wall.poisson_ratio = spec.poisson_ratio;
  const double far = (side - 0.5) * a + r;
  sim.add_wall({PlaneGeometry{{0, 0, -r}, {0, 0, 1}}, FixedMotion{}, wall});
  sim.add_wall({PlaneGeometry{{-r, 0, 0}, {1, 0, 0}}, FixedMotion{}, wall});
  sim.add_wall({PlaneGeometry{{far, 0, 0}, {-1, 0, 0}}, FixedMotion{}, wall});
  sim.add_wall({PlaneGeometry{{0, -r, 0}, {0, 1, 0}}, FixedMotion{}, wall});
  sim.add_wall({PlaneGeometry{{0, far, 0}, {0, -1, 0}}, FixedMotion{}, wall});
  return sim;
}

struct ChildLine {
  bool ok = false;
  std::size_t particles = 0, pairs = 0;
  long steps = 0;
  double rate[2][2] = {{0, 0}, {0, 0}};  // [reordered][threads - 1]
  double peak_bytes = 0.0;
};

ChildLine parse_child(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::string word;
  ChildLine c;
  while (in >> word)
    if (word == "scaling-result") {
      in >> c.particles >> c.pairs >> c.steps >> c.rate[0][0] >> c.rate[0][1] >> c.rate[1][0] >> c.rate[1][1] >>
          c.peak_bytes;
      c.ok = static_cast<bool>(in);
    }
  return c;
}

double peak_rss_bytes() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_maxrss) * 1024.0;
}

// Warm-up on 2 threads (lists, first transients), then one forced list rebuild: the peak
// memory includes one.
void warm_up(Simulation& sim, long steps) {
  sim.set_threads(2);
  sim.run_steps(static_cast<std::uint64_t>(std::clamp(steps, 10L, 50L)));
  sim.set_wall_motion(0, FixedMotion{});  // requests a list rebuild
  sim.run_steps(1);
}

const char* order_name(PairLoadOrder order) {
  return order == PairLoadOrder::own_row_first ? "own_row_first" : "ascending_first_member";
}

void print_scaling_rows(const ScalingOptions& o, const std::string& self, const std::filesystem::path& out,
                        PairLoadOrder order) {
  double previous_rss = 0.0, previous_n = 0.0;
  for (const std::size_t n : o.sizes) {
    const long steps = std::max(10L, std::lround(o.work / static_cast<double>(n)));
    const ChildResult child =
        run_child({self, "--scaling-child", std::to_string(n), std::to_string(steps), std::to_string(o.repeats),
                   o.shuffled ? "shuffled" : "lattice", order_name(order)},
                  {}, out);
    const ChildLine c = parse_child(out);
    if (!c.ok) {
      std::printf("%9zu child failed (exit %d), output in %s\n", n, child.exit_code, out.c_str());
      continue;
    }
    const double pn = static_cast<double>(c.particles);
    char marginal[32] = "-";
    if (previous_n > 0.0)
      std::snprintf(marginal, sizeof marginal, "%.0f", (c.peak_bytes - previous_rss) / (pn - previous_n));
    std::printf("%9zu %-22s %7.2f %6ld %7.3g / %5.3g %7.3g / %5.3g %3.2f/%3.2f %11.0f %9s  [%s]\n", c.particles,
                order_name(order), static_cast<double>(c.pairs) / pn, c.steps, c.rate[0][0] / 1e6, c.rate[1][0] / 1e6,
                c.rate[0][1] / 1e6, c.rate[1][1] / 1e6, c.rate[0][1] / c.rate[0][0], c.rate[1][1] / c.rate[1][0],
                c.peak_bytes / pn, marginal, load_average().c_str());
    previous_rss = c.peak_bytes;
    previous_n = pn;
  }
}

}  // namespace

int run_scaling_child(std::size_t particles, long steps, int repeats, bool shuffled, const std::string& order_text) {
  const PairLoadOrder order = order_text == order_name(PairLoadOrder::own_row_first)
                                  ? PairLoadOrder::own_row_first
                                  : PairLoadOrder::ascending_first_member;
  // The peak is taken with the kernel's default slab order (few pairs cross the threads'
  // chunks), before the stored-order box of the A/B is built.
  Simulation reordered = make_box(particles, shuffled, order);
  reordered.set_reorder_particles(true);  // hertz_settings keeps insertion order
  warm_up(reordered, steps);
  const double peak = peak_rss_bytes();
  Simulation plain = make_box(particles, shuffled, order);
  plain.set_reorder_particles(false);
  warm_up(plain, steps);
  std::vector<double> rate[2][2];
  for (int r = 0; r < repeats; ++r)
    for (int threads = 1; threads <= 2; ++threads)
      for (int variant = 0; variant < 2; ++variant) {
        Simulation& sim = variant == 0 ? plain : reordered;
        sim.set_threads(threads);
        const double seconds = wall_seconds_for_steps(sim, static_cast<std::uint64_t>(steps));
        rate[variant][threads - 1].push_back(static_cast<double>(sim.particle_count()) * static_cast<double>(steps) /
                                             seconds);
      }
  std::printf("scaling-result %zu %zu %ld %.6g %.6g %.6g %.6g %.6g\n", plain.particle_count(),
              plain.neighbor_list().pair_count(), steps, median(rate[0][0]), median(rate[0][1]), median(rate[1][0]),
              median(rate[1][1]), peak);
  return 0;
}

void print_scaling_table(const ScalingOptions& o) {
  const std::string self = std::filesystem::read_symlink("/proc/self/exe").string();
  const std::filesystem::path out =
      std::filesystem::temp_directory_path() / ("demfit_bench_scaling_" + std::to_string(getpid()) + ".txt");
  std::printf(
      "scaling: fcc box of touching spheres (drum material), 10 layers, %s order, median of %d; each size in a "
      "child process\n",
      o.shuffled ? "shuffled" : "lattice", o.repeats);
  std::printf(
      "M particle-steps/s as stored / with reorder_particles (slab order at list rebuilds, same run); peak memory\n"
      "with reordering, after a warm-up on 2 threads and one list rebuild; marginal = between successive sizes\n");
  std::printf("%9s %-22s %7s %6s %15s %15s %8s %11s %9s  %s\n", "N", "pair_load_order", "pairs/N", "steps", "1 thread",
              "2 threads", "speedup", "peak B/part", "marg B/p", "load");
  for (const PairLoadOrder order : {PairLoadOrder::ascending_first_member, PairLoadOrder::own_row_first})
    print_scaling_rows(o, self, out, order);
  std::filesystem::remove(out);
}

}  // namespace demfit::bench
