// The parameter table (see parameter_table.hpp). Physics of each row: dem_core/parameters.hpp
// (LS-DYNA semantics, docs/spec.md 1), dem_core/contact_effects.hpp (effects), docs/cases.md.
#include "demfit/cases/parameter_table.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>

namespace demfit::cases {
namespace {

using identify::ParameterRange;
using Law = ParameterLaws;
using Home = ParameterHome;

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNone = std::numeric_limits<double>::quiet_NaN();  // no default: the case gives it

constexpr ParameterRange closed(double lo, double hi) { return {lo, hi, false, false}; }
constexpr ParameterRange positive() { return {0.0, kInf, true, true}; }
constexpr ParameterRange non_negative() { return {0.0, kInf, false, true}; }
// Damping ratios: [0, 1) (critical damping and above have no restitution formula; dem_core).
constexpr ParameterRange damping() { return {0.0, 1.0, false, true}; }

// LS-DYNA defaults, as dem_core holds them.
const dem_core::ContactParameters kPair{};
const dem_core::WallContactParameters kWall{};

// Fill amounts exist only in the form the case gives them: NaN otherwise.
double fill_count(const CaseSpec& s) {
  return s.kind == CaseKind::rotary_drum && s.drum.fill_by == FillBy::particle_count
             ? static_cast<double>(s.drum.particle_count)
             : kNone;
}
double fill_volume(const CaseSpec& s) {
  return s.kind == CaseKind::rotary_drum && s.drum.fill_by == FillBy::fill_volume ? s.drum.fill_volume_ml : kNone;
}

#define DEMFIT_FIELD(member) [](const CaseSpec& s) { return s.member; }, [](CaseSpec& s, double v) { s.member = v; }

// *CONTROL_DISCRETE_ELEMENT: particle pairs (frics, fricr also in Hertz-Mindlin).
std::vector<ParameterRow> pair_rows() {
  return {
      {"normk", "-", "particle spring k_i = NORMK K R_i (K bulk modulus); a pair is two springs in series", positive(),
       kPair.normk, false, 0.0, Home::pair_contact, "*CONTROL_DISCRETE_ELEMENT NORMK", Law::lsdyna_linear, false,
       "contact.normk", nullptr, DEMFIT_FIELD(contact.normk)},
      {"sheark", "-", "tangential spring k_t = SHEARK k_n", non_negative(), kPair.sheark, false, 0.0,
       Home::pair_contact, "*CONTROL_DISCRETE_ELEMENT SHEARK", Law::lsdyna_linear, false, "contact.sheark", nullptr,
       DEMFIT_FIELD(contact.sheark)},
      {"ndamp", "-", "normal damping, fraction of critical", damping(), kPair.ndamp, false, 0.0, Home::pair_contact,
       "*CONTROL_DISCRETE_ELEMENT NDAMP", Law::lsdyna_linear, false, "contact.ndamp", nullptr,
       DEMFIT_FIELD(contact.ndamp)},
      {"tdamp", "-", "tangential damping, fraction of critical", damping(), kPair.tdamp, false, 0.0, Home::pair_contact,
       "*CONTROL_DISCRETE_ELEMENT TDAMP", Law::lsdyna_linear, false, "contact.tdamp", nullptr,
       DEMFIT_FIELD(contact.tdamp)},
      {"frics", "-", "static (sliding) friction between particles; 0 switches particle rotation off", non_negative(),
       kPair.frics, false, 0.0, Home::pair_contact, "*CONTROL_DISCRETE_ELEMENT FRICS", Law::both, false,
       "contact.frics", nullptr, DEMFIT_FIELD(contact.frics)},
      {"fricd", "-", "dynamic friction, mu = FRICD + (FRICS - FRICD) exp(-DC abs(v_t)); default FRICS", non_negative(),
       kNone, false, 0.0, Home::pair_contact, "*CONTROL_DISCRETE_ELEMENT FRICD", Law::lsdyna_linear, false,
       "contact.fricd", nullptr, DEMFIT_FIELD(contact.fricd)},
      {"dc", "s/m", "decay of friction with sliding speed (FRICS -> FRICD)", non_negative(), kPair.dc, false, 0.0,
       Home::pair_contact, "*CONTROL_DISCRETE_ELEMENT DC", Law::lsdyna_linear, false, "contact.dc", nullptr,
       DEMFIT_FIELD(contact.dc)},
      {"fricr", "-", "rolling friction between particles, constant-torque model (acts only with FRICS > 0)",
       non_negative(), kPair.fricr, true, 0.0, Home::pair_contact, "*CONTROL_DISCRETE_ELEMENT FRICR", Law::both, false,
       "contact.fricr", nullptr, DEMFIT_FIELD(contact.fricr)},
  };
}

// *DEFINE_DE_TO_SURFACE_COUPLING card 2 (and SFP): particle-wall contact.
std::vector<ParameterRow> wall_rows() {
  return {
      {"wall_frics", "-", "particle-wall sliding friction", non_negative(), kWall.frics, true, 0.0, Home::wall_contact,
       "*DEFINE_DE_TO_SURFACE_COUPLING FRICS", Law::both, false, "wall_contact.frics", nullptr,
       DEMFIT_FIELD(wall.frics)},
      {"wall_fricd", "-", "particle-wall ROLLING friction (FRICD of the coupling card)", non_negative(), kWall.fricd,
       false, 0.0, Home::wall_contact, "*DEFINE_DE_TO_SURFACE_COUPLING FRICD", Law::both, false, "wall_contact.fricd",
       "wall_contact.fricr", DEMFIT_FIELD(wall.fricd)},
      {"wall_damp", "-", "particle-wall damping, fraction of critical (normal and tangential)", damping(), kWall.damp,
       false, 0.0, Home::wall_contact, "*DEFINE_DE_TO_SURFACE_COUPLING DAMP", Law::lsdyna_linear, false,
       "wall_contact.damp", nullptr, DEMFIT_FIELD(wall.damp)},
      {"wall_sfp", "-", "scale factor on the wall normal spring, k_n,w = SFP NORMK K R", positive(), kWall.sfp, false,
       0.0, Home::wall_contact, "*DEFINE_DE_TO_SURFACE_COUPLING SFP (written as a comment)", Law::lsdyna_linear, false,
       "wall_contact.sfp", nullptr, DEMFIT_FIELD(wall.sfp)},
  };
}

// Effects library: pairs and walls; off at the off value (the plain LS-DYNA law).
std::vector<ParameterRow> effect_rows() {
  return {
      {"unloading_stiffness_ratio", "-", "plasticity (Walton-Braun): unloading stiffness k2 = ratio k1",
       closed(1.0, 100.0), kPair.unloading_stiffness_ratio, true, 1.0, Home::effect, "", Law::lsdyna_linear, false,
       "contact.unloading_stiffness_ratio", nullptr, DEMFIT_FIELD(contact.unloading_stiffness_ratio)},
      {"surface_energy", "J/m^2", "cohesion: pull-off force F_c = 1.5 pi gamma R* while overlapping", non_negative(),
       kPair.surface_energy, true, 0.0, Home::effect, "", Law::lsdyna_linear, false, "contact.surface_energy", nullptr,
       DEMFIT_FIELD(contact.surface_energy)},
      {"stiffness_exponent", "-", "nonlinear normal spring F = k_n d_ref (delta/d_ref)^n, d_ref = 0.01 R*",
       closed(1.0, 2.0), kPair.stiffness_exponent, true, 1.0, Home::effect, "", Law::lsdyna_linear, false,
       "contact.stiffness_exponent", nullptr, DEMFIT_FIELD(contact.stiffness_exponent)},
      // Up to 0.3: the drum's lattice packing (gap 0.03) still holds the s = 1 fill.
      {"radius_spread", "-",
       "polydispersity: radii uniform in [R(1 - s), R(1 + s)] at the same solid volume (changes the fill)",
       closed(0.0, 0.3), 0.0, true, 0.0, Home::effect, "", Law::lsdyna_linear, false, "particle.radius_spread", nullptr,
       DEMFIT_FIELD(material.radius_spread)},
      // Hertz-Mindlin SJKR cohesion (dem_core/hertz_cohesion.hpp); the area model is the case's
      // contact.cohesion_model. Values past the time step's limit are refused when the run starts.
      {"cohesion_energy_density", "J/m^3",
       "cohesion: attractive normal force k_c A while overlapping (A: contact.cohesion_model sjkr or sjkr2)",
       non_negative(), kPair.cohesion_energy_density, true, 0.0, Home::effect, "", Law::hertz_mindlin, false,
       "contact.cohesion_energy_density", nullptr, DEMFIT_FIELD(contact.cohesion_energy_density)},
      // Hertz drums whose wall friction follows the particles' (wall_contact.friction_as_particles):
      // the tie released to wall FRICS = ratio x FRICS; refused without the tie (give wall_frics).
      {"wall_friction_ratio", "-",
       "tied wall sliding friction: wall FRICS = ratio x particle FRICS (with wall_contact.friction_as_particles)",
       non_negative(), 1.0, true, 1.0, Home::effect, "", Law::hertz_mindlin, false, "wall_contact.friction_ratio",
       nullptr, DEMFIT_FIELD(wall_friction_ratio)},
  };
}

std::vector<ParameterRow> law_and_fill_rows() {
  return {
      // Hertz-Mindlin: shared by pairs and walls; required in a hertz_mindlin file.
      {"restitution", "-", "coefficient of restitution of pairs and walls (Hertz-Mindlin damping)", closed(1e-3, 1.0),
       kNone, false, 0.0, Home::pair_contact, "", Law::hertz_mindlin, false, "contact.restitution", nullptr,
       DEMFIT_FIELD(contact.restitution)},
      // Drum fill amount: a parameter only in the form the case gives it.
      {"particle_count", "-", "drum fill: count N0 of original (s = 1) particles (changes the fill)", closed(1.0, kInf),
       kNone, false, 0.0, Home::fill, "", Law::both, true, "drum.particle_count", nullptr, fill_count,
       [](CaseSpec& s, double v) {
         s.drum.fill_by = FillBy::particle_count;
         s.drum.particle_count = std::llround(v);
       }},
      {"fill_volume_ml", "mL", "drum fill: bulk volume of the fill (changes the fill)", positive(), kNone, false, 0.0,
       Home::fill, "", Law::both, true, "drum.fill_volume_ml", nullptr, fill_volume,
       [](CaseSpec& s, double v) {
         s.drum.fill_by = FillBy::fill_volume;
         s.drum.fill_volume_ml = v;
       }},
  };
}

#undef DEMFIT_FIELD

std::vector<ParameterRow> build_rows() {
  std::vector<ParameterRow> rows;
  for (auto part : {pair_rows, wall_rows, effect_rows, law_and_fill_rows})
    for (const ParameterRow& row : part()) rows.push_back(row);
  return rows;
}

}  // namespace

bool ParameterRow::applies_to(dem_core::ContactLawKind law) const {
  return (static_cast<unsigned>(laws) & law_bit(law)) != 0;
}

const std::vector<ParameterRow>& parameter_table() {
  static const std::vector<ParameterRow> rows = build_rows();
  return rows;
}

const ParameterRow* find_parameter(std::string_view name) {
  for (const ParameterRow& row : parameter_table())
    if (name == row.name) return &row;
  return nullptr;
}

const ParameterRow* find_parameter_by_path(std::string_view path) {
  for (const ParameterRow& row : parameter_table())
    if (path == row.case_path || (row.hertz_path && path == row.hertz_path)) return &row;
  return nullptr;
}

std::string parameter_names_text() {
  std::string text;
  for (const ParameterRow& row : parameter_table()) {
    if (!text.empty()) text += ' ';  // appended: GCC 12 warns (-Wrestrict) on "literal" + string
    text += row.name;
  }
  return text;
}

identify::ParameterDescriptor descriptor_of(const ParameterRow& row) {
  identify::ParameterDescriptor d;
  d.name = row.name;
  d.unit = row.unit;
  d.valid = row.valid;
  d.default_value = row.default_value;
  if (row.is_effect) d.off_value = row.off_value;
  d.lsdyna_field = row.lsdyna;
  return d;
}

std::vector<identify::ParameterDescriptor> parameter_descriptors() {
  std::vector<identify::ParameterDescriptor> out;
  for (const ParameterRow& row : parameter_table()) out.push_back(descriptor_of(row));
  return out;
}

}  // namespace demfit::cases
