// The case-kind registry (see case_registry.hpp).
#include "demfit/cases/case_registry.hpp"

#include <stdexcept>

namespace demfit::cases {

const std::vector<CaseKindRow>& case_kind_table() {
  static const std::vector<CaseKindRow> table{
      {CaseKind::pellet_compression,
       "pellet_compression",
       "pellet",
       "pellets poured into a cylinder and compressed by a piston (docs/spec.md 2.1)",
       {{{"pressure_volume", "volume_cm3", "pressure_MPa"}},
        {{"bottom_force_volume", "volume_cm3", "bottom_force_N"}},
        {{"pressure_volume_cycle", "volume_cm3", "pressure_MPa"}, CurveCondition::pellet_unload},
        // docs/spec.md 2.1's quasi-static check (identify::kQuasiStaticCurve), once the bed carries load.
        {{"quasi_static_check", "volume_cm3", "kinetic_over_elastic_energy_per_limit"}}}},
      {CaseKind::rotary_drum,
       "rotary_drum",
       "drum",
       "powder turning in a closed drum (docs/spec.md 2.2; the GranuDrum, data/granudrum_mcc)",
       {{{"torque", "time_s", "torque_Nm"}},
        {{"free_surface", "x_mm", "height_mm"}},
        {{"free_surface_image", "x_mm", "z_mm"}, CurveCondition::drum_image}}},
      {CaseKind::mesh_container,
       "mesh_container",
       "mesh_container",
       "particles poured into STL geometry with fixed and moving parts (docs/mesh-container.md)",
       {{{"heap_angle", "time_s", "heap_angle_deg"}, CurveCondition::mesh_heap_angle},
        {{"discharge_mass", "time_s", "discharged_mass_kg"}, CurveCondition::mesh_discharge_mass},
        {{"moving_part_torque", "time_s", "torque_Nm"}, CurveCondition::mesh_part_torque}}},
  };
  return table;
}

const CaseKindRow& case_kind_row(CaseKind kind) {
  for (const CaseKindRow& row : case_kind_table())
    if (row.kind == kind) return row;
  throw std::logic_error("case registry: a CaseKind without a row");
}

const CaseKindRow* find_case_kind(std::string_view name) {
  for (const CaseKindRow& row : case_kind_table())
    if (name == row.name) return &row;
  return nullptr;
}

std::string case_kind_names() {
  std::string names;
  const auto& table = case_kind_table();
  for (std::size_t i = 0; i < table.size(); ++i)
    names += std::string(i == 0 ? "" : i + 1 == table.size() ? " or " : ", ") + "\"" + table[i].name + "\"";
  return names;
}

namespace {

// Whether the case-file option a curve depends on is on in `spec` (exhaustive: -Werror=switch).
bool option_on(const CaseSpec& spec, CurveCondition produced) {
  switch (produced) {
    case CurveCondition::always:
      return true;
    case CurveCondition::pellet_unload:
      return spec.pellet.unload;
    case CurveCondition::drum_image:
      return spec.drum.image.enabled;
    case CurveCondition::mesh_heap_angle:
      return spec.mesh_container.heap_angle.enabled;
    case CurveCondition::mesh_discharge_mass:
      return spec.mesh_container.discharge_mass.enabled;
    case CurveCondition::mesh_part_torque:
      return spec.mesh_container.moving_part_torque.enabled;
  }
  throw std::logic_error("case registry: a CurveCondition without its option");
}

}  // namespace

std::vector<identify::CurveDescriptor> produced_curves(const CaseSpec& spec) {
  std::vector<identify::CurveDescriptor> out;
  for (const CaseCurve& c : case_kind_row(spec.kind).curves) {
    if (!option_on(spec, c.produced)) continue;
    out.push_back(c.curve);
    // The occupancy picture spans the drum's inner diameter (drum_case.cpp), like the photo's frame.
    if (c.produced == CurveCondition::drum_image) out.back().picture_span = spec.drum.diameter;
  }
  return out;
}

const identify::CurveDescriptor& case_curve(CaseKind kind, std::string_view name) {
  for (const CaseCurve& c : case_kind_row(kind).curves)
    if (c.curve.name == name) return c.curve;
  throw std::logic_error("case registry: kind " + std::string(case_kind_row(kind).name) + " has no curve " +
                         std::string(name));
}

identify::Curve empty_curve(CaseKind kind, std::string_view name) {
  const identify::CurveDescriptor& d = case_curve(kind, name);
  return {d.x_label, d.y_label, {}, {}};
}

}  // namespace demfit::cases
