// Simulation: building, settings, time stepping (velocity Verlet) and diagnostics.
// Force evaluation lives in simulation_forces.cpp.
#include "demfit/dem_core/simulation.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <variant>

#include "demfit/dem_core/time_step.hpp"
#include "validation.hpp"

namespace demfit::dem_core {
namespace {

/// The effects library extends the LS-DYNA linear law only (contact_effects.hpp); SJKR cohesion
/// and the epsd2 rolling spring the Hertz–Mindlin law only (contact_law_hertz.hpp).
void require_effects_law(ContactLawKind law, const ContactParameters& c) {
  switch (law) {
    case ContactLawKind::lsdyna_linear:
      if (c.rolling_model != RollingModel::constant_torque)
        throw std::runtime_error(
            "contact.rolling_model = epsd2 applies to the hertz_mindlin law only: use cdt (constant torque) "
            "with lsdyna_linear or switch to law hertz_mindlin");
      if (c.cohesion_energy_density != 0.0 || c.cohesion_model != CohesionModel::sjkr)
        throw std::runtime_error(
            "contact.cohesion_energy_density / cohesion_model apply to the hertz_mindlin law only: use "
            "surface_energy (the linear law's cohesion) or switch to law hertz_mindlin");
      return;
    case ContactLawKind::hertz_mindlin:
      if (c.effects_enabled())
        throw std::runtime_error(
            "contact.unloading_stiffness_ratio / surface_energy / stiffness_exponent apply to the "
            "lsdyna_linear law only: set them to 1 / 0 / 1 or use law lsdyna_linear");
      return;
  }
}

}  // namespace

Simulation::Simulation(SimulationSettings settings) : settings_(std::move(settings)) {
  validate(settings_.contact);
  require_effects_law(settings_.law, settings_.contact);
  require_finite("gravity [m/s^2]", settings_.gravity);
  if (settings_.threads < 1) fail("threads", settings_.threads, "must be >= 1");
  require_non_negative("time_step [s]", settings_.time_step);
  require_positive("time_step_factor", settings_.time_step_factor);
  require_finite("skin [m]", settings_.skin);
  // Histories of the law the simulation starts with (no conversion at the first step).
  with_contact_law(settings_.law, settings_.contact, [&]<class Law>(std::type_identity<Law>) {
    contact_state_.emplace<ContactLawState<Law>>().evaluated_with = settings_.contact;
  });
}

std::size_t Simulation::add_material(const Material& material) {
  validate(material);
  materials_.push_back(material);
  return materials_.size() - 1;
}

std::size_t Simulation::add_particle(const Vec3& position, double radius, std::size_t material, const Vec3& velocity,
                                     const Vec3& angular_velocity) {
  require_finite("particle position [m]", position);
  require_positive("particle radius [m]", radius);
  require_finite("particle velocity [m/s]", velocity);
  require_finite("particle angular_velocity [rad/s]", angular_velocity);
  if (material >= materials_.size()) {
    std::ostringstream out;
    out << "particle material index " << material << " does not exist (" << materials_.size()
        << " materials registered); call add_material first";
    throw std::runtime_error(out.str());
  }
  const Material& m = materials_[material];
  const double mass = m.density * 4.0 / 3.0 * std::numbers::pi * radius * radius * radius;
  ParticleState& p = particles_;
  p.position.push_back(position);
  p.velocity.push_back(velocity);
  p.angular_velocity.push_back(settings_.contact.rotation_enabled() ? angular_velocity : Vec3{});
  p.force.push_back({});
  p.torque.push_back({});
  p.radius.push_back(radius);
  p.mass.push_back(mass);
  p.inverse_mass.push_back(1.0 / mass);
  p.inverse_inertia.push_back(1.0 / (0.4 * mass * radius * radius));
  p.material.push_back(material);
  p.id.push_back(next_id_++);
  p.normal_compliance.push_back(0.0);
  p.shear_compliance.push_back(0.0);
  update_compliances(p.size() - 1);
  invalidate_forces();
  step_cache_valid_ = false;
  wall_laws_valid_ = false;
  return p.size() - 1;
}

void Simulation::remove_particles(const std::vector<bool>& flags) {
  if (flags.size() != particles_.size())
    fail("remove_particles flags size", static_cast<double>(flags.size()), "must equal particle_count()");
  ParticleState& p = particles_;
  const std::size_t count = p.size();
  std::size_t kept = 0;
  p.for_each_array([&](auto& values) {
    kept = 0;
    for (std::size_t i = 0; i < count; ++i)
      if (!flags[i]) values[kept++] = values[i];
    values.resize(kept);
  });
  // Contact histories are dropped (documented in the header).
  neighbors_ = NeighborList{};
  std::visit([](auto& state) { state.pair_history.clear(); }, contact_state_);
  drop_wall_slots();
  invalidate_forces();
  step_cache_valid_ = false;
  wall_laws_valid_ = false;
}

std::size_t Simulation::add_wall(const WallSpec& spec) {
  walls_.push_back(make_wall(spec));
  rebuild_requested_ = true;  // wall candidate lists must be rebuilt
  // The (particle, wall) layout changes: wall histories restart.
  drop_wall_slots();
  invalidate_forces();
  step_cache_valid_ = false;
  wall_laws_valid_ = false;
  return walls_.size() - 1;
}

void Simulation::drop_wall_slots() {
  wall_slots_.clear();
  std::visit([](auto& state) { state.wall_history.clear(); }, contact_state_);
}

void Simulation::update_compliances(std::size_t first) {
  ParticleState& p = particles_;
  const ContactParameters& c = settings_.contact;
  with_contact_law(settings_.law, c, [&]<class Law>(std::type_identity<Law>) {
    for (std::size_t i = first; i < p.size(); ++i) {
      const ParticleCompliance compliance = Law::particle_compliance(materials_[p.material[i]], p.radius[i], c);
      p.normal_compliance[i] = compliance.normal;
      p.shear_compliance[i] = compliance.shear;
    }
  });
}

void Simulation::set_gravity(const Vec3& gravity) {
  require_finite("gravity [m/s^2]", gravity);
  settings_.gravity = gravity;
}

void Simulation::set_contact_parameters(const ContactParameters& parameters) {
  validate(parameters);
  require_effects_law(settings_.law, parameters);
  const bool had_rotation = settings_.contact.rotation_enabled();
  settings_.contact = parameters;
  if (had_rotation && !parameters.rotation_enabled())
    std::fill(particles_.angular_velocity.begin(), particles_.angular_velocity.end(), Vec3{});
  update_compliances();
  step_cache_valid_ = false;
  wall_laws_valid_ = false;
}

void Simulation::set_wall_contact_parameters(std::size_t index, const WallContactParameters& parameters) {
  validate(parameters);
  (void)wall(index);
  walls_[index].contact = parameters;
  step_cache_valid_ = false;
  wall_laws_valid_ = false;
}

void Simulation::set_time_step(double time_step) {
  require_non_negative("time_step [s]", time_step);
  settings_.time_step = time_step;
  step_cache_valid_ = false;
  wall_laws_valid_ = false;
}

void Simulation::set_threads(int threads) {
  if (threads < 1) fail("threads", threads, "must be >= 1");
  settings_.threads = threads;
}

void Simulation::set_pair_load_order(PairLoadOrder order) {
  if (order != settings_.pair_load_order) rebuild_requested_ = true;
  settings_.pair_load_order = order;
}

void Simulation::set_reorder_particles(bool reorder) {
  if (reorder && !settings_.reorder_particles) rebuild_requested_ = true;
  settings_.reorder_particles = reorder;
}

const Wall& Simulation::wall(std::size_t index) const {
  if (index >= walls_.size())
    fail("wall index", static_cast<double>(index), "does not exist; use an index returned by add_wall");
  reduce_diagnostics();
  return walls_[index];
}

void Simulation::set_wall_motion(std::size_t index, const WallMotion& motion) {
  (void)wall(index);
  WallSpec probe{walls_[index].geometry, motion, walls_[index].contact, walls_[index].torque_axis, walls_[index].name};
  walls_[index].motion = make_wall(probe).motion;  // validated and normalised
  rebuild_requested_ = true;
}

void Simulation::set_wall_velocity(std::size_t index, const Vec3& velocity) {
  require_finite("wall velocity [m/s]", velocity);
  (void)wall(index);
  walls_[index].motion = TranslatingMotion{velocity};
  rebuild_requested_ = true;
}

void Simulation::set_wall_angular_velocity(std::size_t index, double angular_velocity) {
  require_finite("wall angular_velocity [rad/s]", angular_velocity);
  (void)wall(index);  // index check with a one-line message
  auto* rotating = std::get_if<RotatingMotion>(&walls_[index].motion);
  if (rotating == nullptr)
    throw std::runtime_error("set_wall_angular_velocity: wall " + std::to_string(index) +
                             " does not rotate; give it a RotatingMotion with set_wall_motion");
  rotating->angular_velocity = angular_velocity;
  rebuild_requested_ = true;
}

void Simulation::set_particle_velocity(std::size_t index, const Vec3& velocity, const Vec3& angular_velocity) {
  if (index >= particles_.size()) fail("particle index", static_cast<double>(index), "does not exist");
  require_finite("particle velocity [m/s]", velocity);
  require_finite("particle angular_velocity [rad/s]", angular_velocity);
  particles_.velocity[index] = velocity;
  particles_.angular_velocity[index] = settings_.contact.rotation_enabled() ? angular_velocity : Vec3{};
}

void Simulation::zero_velocities() {
  std::fill(particles_.velocity.begin(), particles_.velocity.end(), Vec3{});
  std::fill(particles_.angular_velocity.begin(), particles_.angular_velocity.end(), Vec3{});
}

double Simulation::resolved_step() const {
  if (step_cache_valid_) return cached_step_;
  const double dt = time_step();
  cached_step_ = dt;
  step_cache_valid_ = true;
  return dt;
}

TimeStepEstimate Simulation::step_estimate() const {
  double max_sfp = 0.0, max_damp = 0.0, max_hertz = 0.0;
  for (const Wall& w : walls_) {
    max_sfp = std::max(max_sfp, w.contact.sfp);
    max_damp = std::max(max_damp, w.contact.damp);
    max_hertz = std::max(max_hertz, w.contact.hertz_normal_compliance());
  }
  return estimate_time_step(settings_.law, particles_, materials_, settings_.contact, max_sfp, max_damp,
                            settings_.time_step_factor, max_hertz);
}

double Simulation::stable_time_step() const { return step_estimate().stable_limit; }

double Simulation::time_step() const {
  const TimeStepEstimate e = step_estimate();
  if (settings_.time_step > 0.0) {
    if (settings_.time_step > e.stable_limit) {
      std::ostringstream out;
      out.precision(4);
      out << "time_step = " << settings_.time_step << " s exceeds the stable limit " << e.stable_limit
          << " s of the stiffest contact; set time_step <= " << e.stable_limit << " s or 0 for automatic ("
          << e.automatic << " s)";
      throw std::runtime_error(out.str());
    }
    return settings_.time_step;
  }
  return e.automatic;
}

void Simulation::step() {
  const double dt = resolved_step();
  if (!forces_valid_) compute_forces(0.0, 0.0, -1.0);  // initial loads; zero history increment
  const double moved = kick_and_drift(dt);
  for (Wall& w : walls_) advance_wall(w, dt);
  time_ += dt;
  compute_forces(dt, 0.5 * dt, moved);  // ends with the second half kick
  ++step_count_;
}

double Simulation::kick_and_drift(double dt) {
  // Velocity Verlet: half kick and drift, fused with the displacement check of the neighbour list
  // (one parallel region; max is order-independent, so the result is deterministic).
  ParticleState& p = particles_;
  const bool rotation = settings_.contact.rotation_enabled();
  const auto n = static_cast<std::int64_t>(p.size());
  const double half = 0.5 * dt;
  const std::span<const Vec3> reference = neighbors_.reference_positions();
  const bool known = reference.size() == p.size();
  double worst = 0.0;
#pragma omp parallel for schedule(static) reduction(max \
                                                    : worst) num_threads(settings_.threads) if (settings_.threads > 1)
  for (std::int64_t k = 0; k < n; ++k) {
    const auto i = static_cast<std::size_t>(k);
    p.velocity[i] += (half * p.inverse_mass[i]) * p.force[i];
    if (rotation) p.angular_velocity[i] += (half * p.inverse_inertia[i]) * p.torque[i];
    p.position[i] += dt * p.velocity[i];
    if (known) worst = std::max(worst, norm2(p.position[i] - reference[i]));
  }
  return known ? std::sqrt(worst) : -1.0;
}

void Simulation::run_steps(std::uint64_t steps) {
  for (std::uint64_t s = 0; s < steps; ++s) step();
}

void Simulation::run_until(double t_end, const StepCallback& callback, std::uint64_t every) {
  require_finite("run_until t_end [s]", t_end);
  if (every == 0) every = 1;
  std::uint64_t local = 0;
  while (!reached(t_end)) {
    step();
    ++local;
    if (callback && local % every == 0 && !callback(*this)) return;
  }
}

bool Simulation::reached(double t_end) const {
  // The first step that reaches t_end within a hundredth of a step ends a run (round-off).
  return time_ >= t_end - 0.01 * resolved_step();
}

double Simulation::kinetic_energy() const {
  const ParticleState& p = particles_;
  double e = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i)
    e += 0.5 * p.mass[i] * norm2(p.velocity[i]) + 0.5 * norm2(p.angular_velocity[i]) / p.inverse_inertia[i];
  return e;
}

double Simulation::gravitational_potential_energy() const {
  double e = 0.0;
  for (std::size_t i = 0; i < particles_.size(); ++i)
    e -= particles_.mass[i] * dot(settings_.gravity, particles_.position[i]);
  return e;
}

std::size_t Simulation::wall_contact_count() const {
  reduce_diagnostics();
  std::size_t c = 0;
  for (const Wall& w : walls_) c += w.contact_count;
  return c;
}

double Simulation::elastic_energy() const {
  reduce_pair_diagnostics();
  return elastic_energy_;
}

std::size_t Simulation::contact_count() const {
  reduce_pair_diagnostics();
  return contact_count_;
}

double Simulation::skin() const {
  if (settings_.skin > 0.0) return settings_.skin;
  if (particles_.size() == 0) return 0.0;
  return 0.3 * *std::max_element(particles_.radius.begin(), particles_.radius.end());
}

}  // namespace demfit::dem_core
