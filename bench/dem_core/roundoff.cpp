// Both variants start from one prepared state (copied), so only the reordering differs.
#include "roundoff.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

#include "bench_scenarios.hpp"

namespace demfit::bench {
namespace {
using dem_core::Simulation;

struct Curve {
  std::vector<double> values;
  [[nodiscard]] double mean() const {
    double s = 0.0;
    for (double v : values) s += v;
    return values.empty() ? 0.0 : s / static_cast<double>(values.size());
  }
};

/// Largest |a - b| over the common samples, relative to the largest |a|.
double relative_difference(const Curve& a, const Curve& b) {
  double worst = 0.0, scale = 0.0;
  for (std::size_t k = 0; k < std::min(a.values.size(), b.values.size()); ++k) {
    worst = std::max(worst, std::fabs(a.values[k] - b.values[k]));
    scale = std::max(scale, std::fabs(a.values[k]));
  }
  return scale > 0.0 ? worst / scale : 0.0;
}

/// The control: the same state, not reordered, with particle 0 given the velocity change that
/// moves it by ~4 ulp of its position in one step (a round-off-sized change that survives).
Simulation nudged(const Simulation& prepared) {
  Simulation sim = prepared;
  dem_core::Vec3 v = sim.velocities()[0];
  const double x = std::fabs(sim.positions()[0].x) + 1e-3;
  v.x += 4.0 * (std::nextafter(x, 1.0e300) - x) / sim.time_step();
  sim.set_particle_velocity(0, v, sim.angular_velocities()[0]);
  return sim;
}

Curve drum_torque(const Simulation& prepared, bool reorder, double duration) {
  Simulation sim = prepared;
  sim.set_reorder_particles(reorder);
  Curve c;
  const auto every = static_cast<std::uint64_t>(std::max(1.0, std::round(0.01 / sim.time_step())));
  sim.run_until(
      sim.time() + duration,
      [&](Simulation& s) {
        c.values.push_back(s.wall_torque(0));
        return true;
      },
      every);
  return c;
}

Curve pellet_force(const Simulation& prepared, bool reorder) {
  Simulation sim = prepared;
  sim.set_reorder_particles(reorder);
  sim.set_wall_velocity(2, {0, 0, -0.05});
  const double area = std::numbers::pi * 0.018 * 0.018;
  Curve c;
  sim.run_until(
      sim.time() + 1.0,
      [&](Simulation& s) {
        c.values.push_back(s.wall_force(2).z);
        return s.wall_force(2).z / area < 3.0e6;
      },
      20);
  return c;
}

}  // namespace

void print_reordering_roundoff(bool quick) {
  const Simulation drum = make_drum(4.0, 0.3, 2);
  const double duration = quick ? 0.5 : 2.7;
  const Curve plain = drum_torque(drum, false, duration), reordered = drum_torque(drum, true, duration);
  const Curve control = drum_torque(nudged(drum), false, duration);
  std::printf(
      "reorder_particles round-off, s=4 drum (N=%zu), %.1f s at 60 RPM, torque every 0.01 s: largest "
      "difference %.3g of max |torque|; mean torque %.6g vs %.6g N m (relative %.3g)\n",
      drum.particle_count(), duration, relative_difference(plain, reordered), plain.mean(), reordered.mean(),
      std::fabs(reordered.mean() - plain.mean()) / std::fabs(plain.mean()));
  std::printf(
      "  control, particle 0 moved by ~4 ulp instead: largest difference %.3g, mean torque relative %.3g "
      "(granular flow amplifies any round-off change alike)\n",
      relative_difference(plain, control), std::fabs(control.mean() - plain.mean()) / std::fabs(plain.mean()));
  const Simulation bed = make_pellet_bed(0.875046, 0.299582, quick ? 0.3 : 1.0, 2);
  const Curve p = pellet_force(bed, false), q = pellet_force(bed, true), u = pellet_force(nudged(bed), false);
  std::printf(
      "reorder_particles round-off, pellet compression (N=%zu, NORMK 0.875) to 3 MPa: %zu vs %zu samples, "
      "largest piston-force difference %.3g of max force; control (~4 ulp move): %.3g\n",
      bed.particle_count(), p.values.size(), q.values.size(), relative_difference(p, q), relative_difference(p, u));
}

}  // namespace demfit::bench
