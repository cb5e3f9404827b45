// CaseSpec -> dem_core conversions (see dem_setup.hpp).
#include "dem_setup.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

#include "demfit/dem_core/snapshot.hpp"

namespace demfit::cases::detail {

dem_core::SimulationSettings simulation_settings(const CaseSpec& spec) {
  dem_core::SimulationSettings settings;
  settings.law = spec.law;
  settings.contact = spec.contact;
  return settings;
}

dem_core::Material to_material(const MaterialSpec& spec) {
  dem_core::Material m;
  m.bulk_modulus = spec.bulk_modulus();
  m.density = spec.density;
  m.poisson_ratio = spec.poisson_ratio;
  return m;
}

namespace {

bool is_hertz(const CaseSpec& spec) { return spec.law == dem_core::ContactLawKind::hertz_mindlin; }

// Parameters of the LS-DYNA law only: under Hertz–Mindlin they do not exist, so a value other
// than the spec's own is an error (equal values come from default_parameters and are harmless).
bool lsdyna_only(const std::string& name) {
  for (const char* n : {"normk", "sheark", "ndamp", "tdamp", "fricd", "dc", "wall_damp", "wall_sfp",
                        "unloading_stiffness_ratio", "surface_energy", "stiffness_exponent", "radius_spread"})
    if (name == n) return true;
  return false;
}

double current_value(const CaseSpec& spec, const std::string& name) {
  const identify::ParameterSet all = parameters_of(spec);
  const auto it = all.find(name);
  return it == all.end() ? std::numeric_limits<double>::quiet_NaN() : it->second;
}

void set_fill_amount(CaseSpec& spec, const std::string& name, double value) {
  if (spec.kind != CaseKind::rotary_drum)
    throw std::runtime_error("parameter '" + name + "' is a drum fill amount: it does not apply to a pellet_compression case");
  if (name == "particle_count") {
    const long long count = std::llround(value);
    if (!(value >= 1.0) || count < 1) throw std::runtime_error("parameter 'particle_count' = " + std::to_string(value) + " must be >= 1");
    spec.drum.fill_by = FillBy::particle_count;
    spec.drum.particle_count = count;
  } else {
    if (!(value > 0.0)) throw std::runtime_error("parameter 'fill_volume_ml' = " + std::to_string(value) + " must be > 0 [mL]");
    spec.drum.fill_by = FillBy::fill_volume;
    spec.drum.fill_volume_ml = value;
  }
}

}  // namespace

CaseSpec with_parameters(const CaseSpec& base, const identify::ParameterSet& parameters) {
  CaseSpec spec = base;
  for (const auto& [name, value] : parameters) {
    if (is_hertz(base) && lsdyna_only(name)) {
      if (value == current_value(base, name)) continue;
      throw std::runtime_error("parameter '" + name + "' belongs to contact law lsdyna_linear; this case uses hertz_mindlin "
                               "(its parameters: frics fricr restitution wall_frics wall_fricd)");
    }
    if (base.wall_friction_as_particles && (name == "wall_frics" || name == "wall_fricd")) {
      if (value == current_value(base, name)) continue;
      throw std::runtime_error("parameter '" + name + "': the case's wall friction follows the particles "
                               "(wall_contact.friction_as_particles); vary frics/fricr instead");
    }
    if (name == "normk") spec.contact.normk = value;
    else if (name == "sheark") spec.contact.sheark = value;
    else if (name == "ndamp") spec.contact.ndamp = value;
    else if (name == "tdamp") spec.contact.tdamp = value;
    else if (name == "frics") spec.contact.frics = value;
    else if (name == "fricd") spec.contact.fricd = value;
    else if (name == "dc") spec.contact.dc = value;
    else if (name == "fricr") spec.contact.fricr = value;
    else if (name == "wall_frics") spec.wall.frics = value;
    else if (name == "wall_fricd") spec.wall.fricd = value;
    else if (name == "wall_damp") spec.wall.damp = value;
    else if (name == "wall_sfp") spec.wall.sfp = value;
    else if (name == "unloading_stiffness_ratio") spec.contact.unloading_stiffness_ratio = value;
    else if (name == "surface_energy") spec.contact.surface_energy = value;
    else if (name == "stiffness_exponent") spec.contact.stiffness_exponent = value;
    else if (name == "radius_spread") {
      // Same range as the case file (dem_core checks the contact effects itself).
      if (!(value >= 0.0 && value <= 0.3))
        throw std::runtime_error("parameter 'radius_spread' = " + std::to_string(value) + " must lie in [0, 0.3]");
      spec.material.radius_spread = value;
    }
    else if (name == "restitution") {
      if (!is_hertz(base)) {
        if (value == base.contact.restitution) continue;
        throw std::runtime_error("parameter 'restitution' belongs to contact law hertz_mindlin; this case uses lsdyna_linear (use ndamp/tdamp)");
      }
      if (!(value > 0.0 && value <= 1.0)) throw std::runtime_error("parameter 'restitution' = " + std::to_string(value) + " must lie in (0, 1]");
      spec.contact.restitution = value;
    }
    else if (name == "particle_count" || name == "fill_volume_ml") {
      if (value == current_value(base, name)) continue;
      set_fill_amount(spec, name, value);
    }
    else throw std::runtime_error("parameter '" + name + "' is unknown (known: normk sheark ndamp tdamp frics fricd dc fricr wall_frics wall_fricd wall_damp wall_sfp unloading_stiffness_ratio surface_energy stiffness_exponent radius_spread restitution particle_count fill_volume_ml)");
  }
  if (is_hertz(spec)) spec.contact.fricd = spec.contact.frics;  // one Coulomb coefficient
  if (spec.wall_friction_as_particles) {
    spec.wall.frics = spec.contact.frics;
    spec.wall.fricd = spec.contact.fricr;
  }
  return spec;
}

identify::ParameterSet parameters_of(const CaseSpec& spec) {
  identify::ParameterSet out;
  if (is_hertz(spec)) {
    out = {{"frics", spec.contact.frics}, {"fricr", spec.contact.fricr}, {"restitution", spec.contact.restitution},
           {"wall_frics", spec.wall.frics}, {"wall_fricd", spec.wall.fricd}};
  } else {
    out = {{"normk", spec.contact.normk}, {"sheark", spec.contact.sheark}, {"ndamp", spec.contact.ndamp},
           {"tdamp", spec.contact.tdamp}, {"frics", spec.contact.frics}, {"fricd", spec.contact.fricd},
           {"dc", spec.contact.dc}, {"fricr", spec.contact.fricr}, {"wall_frics", spec.wall.frics},
           {"wall_fricd", spec.wall.fricd}, {"wall_damp", spec.wall.damp}, {"wall_sfp", spec.wall.sfp},
           {"unloading_stiffness_ratio", spec.contact.unloading_stiffness_ratio},
           {"surface_energy", spec.contact.surface_energy},
           {"stiffness_exponent", spec.contact.stiffness_exponent},
           {"radius_spread", spec.material.radius_spread}};
  }
  // The fill amount is a parameter only in the form the case gives it.
  if (spec.kind == CaseKind::rotary_drum && spec.drum.fill_by == FillBy::particle_count)
    out["particle_count"] = static_cast<double>(spec.drum.particle_count);
  if (spec.kind == CaseKind::rotary_drum && spec.drum.fill_by == FillBy::fill_volume)
    out["fill_volume_ml"] = spec.drum.fill_volume_ml;
  return out;
}

void check_user_time_step(const CaseSpec& spec, const dem_core::Simulation& simulation) {
  if (spec.time_step.value <= 0.0) return;
  const double limit = simulation.stable_time_step();
  if (spec.time_step.value > limit) {
    char buffer[256];
    std::snprintf(buffer, sizeof buffer,
                  "'time_step.value' = %.3g s exceeds the stable limit %.3g s: lower it or set 0 (automatic)",
                  spec.time_step.value, limit);
    throw std::runtime_error(buffer);
  }
}

void precheck_user_time_step(const CaseSpec& spec, double radius, double density) {
  if (spec.time_step.value <= 0.0) return;
  dem_core::SimulationSettings settings = simulation_settings(spec);
  settings.time_step_factor = spec.time_step.factor;
  dem_core::Simulation probe(settings);
  dem_core::Material material = to_material(spec.material);
  material.density = density;
  probe.add_material(material);
  // The smallest particle of the radius spread (or of the size distribution, whose smallest
  // radius the caller passes) sets the stable step.
  const double smallest = radius * (1.0 - spec.material.radius_spread);
  probe.add_particle({0, 0, 0}, smallest);
  probe.add_wall({dem_core::PlaneGeometry{{0, 0, -smallest}, {0, 0, 1}}, dem_core::FixedMotion{},
                  spec.wall, {}, "probe"});
  check_user_time_step(spec, probe);
}

SnapshotSchedule::SnapshotSchedule(std::vector<double> times, std::string directory, std::string stage)
    : times_(std::move(times)), directory_(std::move(directory)), stage_(std::move(stage)) {
  std::sort(times_.begin(), times_.end());
  if (directory_.empty()) times_.clear();
}

void SnapshotSchedule::maybe_write(const dem_core::Simulation& simulation, double stage_time) {
  while (next_ < times_.size() && stage_time >= times_[next_]) {
    char name[128];
    std::snprintf(name, sizeof name, "/%s_%08.4fs.vtk", stage_.c_str(), times_[next_]);
    dem_core::write_vtk_snapshot(simulation, directory_ + name);
    ++next_;
  }
}

Fill fill_of(const dem_core::Simulation& simulation) {
  Fill fill;
  for (std::size_t i = 0; i < simulation.particle_count(); ++i) {
    const auto p = simulation.positions()[i];
    fill.positions.push_back({p.x, p.y, p.z});
    fill.radii.push_back(simulation.radii()[i]);
  }
  return fill;
}

}  // namespace demfit::cases::detail
