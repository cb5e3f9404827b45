// CaseSpec -> dem_core conversions (see dem_setup.hpp).
#include "dem_setup.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

#include "demfit/cases/case_registry.hpp"
#include "demfit/cases/parameter_table.hpp"
#include "demfit/dem_core/snapshot.hpp"

namespace demfit::cases::detail {

dem_core::SimulationSettings simulation_settings(const CaseSpec& spec) {
  dem_core::SimulationSettings settings;
  settings.law = spec.law;
  settings.contact = spec.contact;
  settings.reorder_particles = spec.numerics.reorder_particles;
  settings.pair_load_order = spec.numerics.pair_load_order;
  return settings;
}

nlohmann::json fill_key_of(const CaseSpec& spec, const char* section, std::initializer_list<const char*> run_only) {
  const nlohmann::json full = to_key_json(spec);
  nlohmann::json kind_section = full[section];
  for (const char* k : run_only) kind_section.erase(k);
  nlohmann::json key = {{"fill_format", 1},
                        {"particle", full["particle"]},
                        {"contact", full["contact"]},
                        {"wall_contact", full["wall_contact"]},
                        {"time_step_factor", kFillTimeStepFactor},
                        {section, kind_section}};
  if (full.contains("numerics")) key["numerics"] = full["numerics"];  // a reordered settle is another fill
  return key;
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

std::string law_parameters_text(dem_core::ContactLawKind law) {
  std::string text;
  for (const ParameterRow& row : parameter_table())
    if (row.applies_to(law) && row.home != ParameterHome::fill) {
      if (!text.empty()) text += ' ';  // appended: GCC 12 warns (-Wrestrict) on "literal" + string
      text += row.name;
    }
  return text;
}

// Whether `value` for `row` changes `base`: a value equal to the case's own (e.g. from
// default_parameters or a study's fixed values) is skipped, even where the row does not apply.
bool is_change(const ParameterRow& row, const CaseSpec& base, double value) { return !(value == row.get(base)); }

// Throws when `row` cannot be set on `base` (wrong law, pellet case, wall friction tied to the
// particles' values).
void check_applicable(const ParameterRow& row, const CaseSpec& base) {
  const std::string name = row.name;
  if (!row.applies_to(base.law))
    throw std::runtime_error("parameter '" + name + "' belongs to contact law " + laws_text(row.laws) +
                             "; this case uses " + to_string(base.law) +
                             " (its parameters: " + law_parameters_text(base.law) + ")");
  if (row.drum_only && base.kind != CaseKind::rotary_drum)
    throw std::runtime_error("parameter '" + name +
                             "' is a drum fill amount: it does not apply to a " +
                             case_kind_row(base.kind).name + " case");
  if (base.wall_friction_as_particles && row.home == ParameterHome::wall_contact)
    throw std::runtime_error("parameter '" + name +
                             "': the case's wall friction follows the particles "
                             "(wall_contact.friction_as_particles); vary frics/fricr (or wall_friction_ratio) instead");
  if (!base.wall_friction_as_particles && name == "wall_friction_ratio")
    throw std::runtime_error(
        "parameter 'wall_friction_ratio' scales a wall friction tied to the particles' "
        "(wall_contact.friction_as_particles); this case gives its own: vary wall_frics instead");
}

}  // namespace

CaseSpec with_parameters(const CaseSpec& base, const identify::ParameterSet& parameters) {
  CaseSpec spec = base;
  for (const auto& [name, value] : parameters) {
    const ParameterRow* row = find_parameter(name);
    if (!row) throw std::runtime_error("parameter '" + name + "' is unknown (known: " + parameter_names_text() + ")");
    if (!is_change(*row, base, value)) continue;
    check_applicable(*row, base);
    check_parameter_value(*row, value);
    row->set(spec, value);
  }
  if (is_hertz(spec)) spec.contact.fricd = spec.contact.frics;  // one Coulomb coefficient
  if (spec.wall_friction_as_particles) {
    spec.wall.frics = spec.contact.frics * spec.wall_friction_ratio;  // exact for the ratio 1
    spec.wall.fricd = spec.contact.fricr;
  }
  return spec;
}

identify::ParameterSet parameters_of(const CaseSpec& spec) {
  identify::ParameterSet out;
  for (const ParameterRow& row : parameter_table()) {
    if (!row.applies_to(spec.law) || (row.drum_only && spec.kind != CaseKind::rotary_drum)) continue;
    const double value = row.get(spec);
    // The fill amount is a parameter only in the form the case gives it (NaN otherwise).
    if (!std::isnan(value)) out[row.name] = value;
  }
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

namespace {

// A probe simulation with one particle of the smallest radius of the spec's spread around the
// nominal `radius` [m], density [kg/m^3], and one wall with the spec's wall parameters (the stable
// step depends on particle size, material and contact parameters, not on positions); returns
// what `use` makes of it.
template <class Use>
auto with_time_step_probe(const CaseSpec& spec, double radius, double density, Use use) {
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
  probe.add_wall(
      {dem_core::PlaneGeometry{{0, 0, -smallest}, {0, 0, 1}}, dem_core::FixedMotion{}, spec.wall, {}, "probe"});
  return use(probe);
}

}  // namespace

void precheck_user_time_step(const CaseSpec& spec, double radius, double density) {
  if (spec.time_step.value <= 0.0) return;
  with_time_step_probe(spec, radius, density, [&](const dem_core::Simulation& probe) {
    check_user_time_step(spec, probe);
    return 0;
  });
}

double planned_time_step(const CaseSpec& spec, double radius, double density) {
  if (spec.time_step.value > 0.0) return spec.time_step.value;
  return with_time_step_probe(spec, radius, density,
                              [](const dem_core::Simulation& probe) { return probe.time_step(); });
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
  for (std::size_t i : simulation.particles().indices_by_id()) {
    const auto p = simulation.positions()[i];
    fill.positions.push_back({p.x, p.y, p.z});
    fill.radii.push_back(simulation.radii()[i]);
  }
  return fill;
}

}  // namespace demfit::cases::detail
