// Settling (densification) under gravity until the kinetic energy is small.
#include <algorithm>
#include <cmath>
#include <functional>

#include "demfit/dem_core/packing.hpp"
#include "demfit/dem_core/simulation.hpp"
#include "validation.hpp"

namespace demfit::dem_core {
namespace {

/// Run in check_interval chunks until KE < tolerance * sum(m |g| R) after min_time, or max_time.
bool settle_phase(Simulation& s, double min_time, double max_time, double tolerance, double interval,
                  const std::function<void(double)>& checked) {
  double scale = 0.0;
  const double g = norm(s.settings().gravity);
  for (std::size_t i = 0; i < s.particle_count(); ++i) scale += s.masses()[i] * g * s.radii()[i];
  if (scale == 0.0) {  // no gravity: compare with the elastic energy scale instead
    for (std::size_t i = 0; i < s.particle_count(); ++i) scale += s.masses()[i] * 1e-6;
  }
  // The phase ends where run_until stops stepping (Simulation::reached): comparing elapsed times
  // exactly could leave a round-off remainder that no step covers, and loop forever (found on a
  // polydisperse drum fill whose refriction phase ended 1e-17 s short).
  const double end = s.time() + max_time;
  const double check = std::max(interval, s.time_step());
  const double start = s.time();
  while (!s.reached(end)) {
    s.run_until(std::min(s.time() + check, end));
    if (checked) checked(s.time());
    if (s.time() - start >= min_time && s.kinetic_energy() < tolerance * scale) return true;
  }
  return false;
}

}  // namespace

SettleReport settle(Simulation& s, const SettleOptions& o) {
  require_positive("settle.max_time [s]", o.max_time);
  require_positive("settle.kinetic_energy_tolerance", o.kinetic_energy_tolerance);
  require_non_negative("settle.min_time [s]", o.min_time);
  require_positive("settle.check_interval [s]", o.check_interval);
  require_non_negative("settle.refriction_time [s]", o.refriction_time);
  const double start = s.time();
  const std::uint64_t first_step = s.step_count();
  SettleReport report;
  std::function<void(double)> checked;
  if (o.progress) checked = [&](double now) { o.progress(std::min(now - start, o.max_time), o.max_time); };
  if (o.frictionless) {
    const ContactParameters saved = s.settings().contact;
    std::vector<WallContactParameters> saved_walls;
    ContactParameters smooth = saved;
    smooth.frics = 0.0;
    smooth.fricd = 0.0;
    smooth.fricr = 0.0;
    s.set_contact_parameters(smooth);
    for (std::size_t w = 0; w < s.wall_count(); ++w) {
      saved_walls.push_back(s.wall(w).contact);
      WallContactParameters p = saved_walls.back();
      p.frics = 0.0;
      p.fricd = 0.0;
      s.set_wall_contact_parameters(w, p);
    }
    settle_phase(s, o.min_time, o.max_time, o.kinetic_energy_tolerance, o.check_interval, checked);
    s.set_contact_parameters(saved);
    for (std::size_t w = 0; w < s.wall_count(); ++w) s.set_wall_contact_parameters(w, saved_walls[w]);
    const double left = std::max(o.max_time - (s.time() - start), o.refriction_time);
    report.converged = settle_phase(s, o.refriction_time, left, o.kinetic_energy_tolerance, o.check_interval, checked);
  } else {
    report.converged = settle_phase(s, o.min_time, o.max_time, o.kinetic_energy_tolerance, o.check_interval, checked);
  }
  report.simulated_time = s.time() - start;
  report.steps = s.step_count() - first_step;
  report.kinetic_energy = s.kinetic_energy();
  return report;
}

}  // namespace demfit::dem_core
