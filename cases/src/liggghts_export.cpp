// LIGGGHTS snippet of a Hertz–Mindlin answer (liggghts_export.hpp). Command syntax: LIGGGHTS 3.8
// documentation pages fix_property.html (property/global peratomtype / peratomtypepair n, values
// row by row), pair_gran.html (model, tangential, cohesion, rolling_friction in that order),
// gran_cohesion_sjkr(2).html, gran_rolling_friction_cdt.html / _epsd2.html, fix_wall_gran.html.
#include "demfit/cases/liggghts_export.hpp"

#include <algorithm>
#include <cstdio>
#include <set>
#include <sstream>
#include <stdexcept>

#include "demfit/cases/parameter_table.hpp"
#include "dem_setup.hpp"

namespace demfit::cases {
namespace {

// A type-pair property: its LIGGGHTS name and the case fields (parameter-table rows) of its
// particle-particle (1-1) and particle-wall (1-2) entries.
struct PairProperty {
  const char* liggghts;
  const char* particle_field;
  const char* wall_field;
};
constexpr PairProperty kRestitution{"coefficientRestitution", "contact.restitution", "contact.restitution"};
constexpr PairProperty kFriction{"coefficientFriction", "contact.frics", "wall_contact.frics"};
constexpr PairProperty kRollingFriction{"coefficientRollingFriction", "contact.fricr", "wall_contact.fricr"};
constexpr PairProperty kCohesion{"cohesionEnergyDensity", "contact.cohesion_energy_density",
                                 "contact.cohesion_energy_density"};
constexpr const char* kFrictionRatioField = "wall_contact.friction_ratio";

// LIGGGHTS needs a finite wall modulus; a rigid demfit wall (E_w = 0) becomes this multiple of the
// particles' E, which lowers the effective modulus E* of a wall contact by 1/1000 (0.1 %).
constexpr double kRigidWallFactor = 1000.0;

const ParameterRow& row_at(const char* field) {
  const ParameterRow* row = find_parameter_by_path(field);
  if (!row) throw std::logic_error(std::string("LIGGGHTS export: no parameter-table row for ") + field);
  return *row;
}

std::string number(double value) {
  char text[40];
  std::snprintf(text, sizeof text, "%.10g", value);
  return text;
}

std::string comment(const std::string& text) {
  std::string line = "# ";
  for (char c : text) line += (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) ? ' ' : c;
  return line + "\n";
}

// "frics = 0.5 [-] identified, 95 % interval [0.45, 0.56] (posterior)" or "... case value".
std::string value_note(const ParameterRow& row, double value, const IdentifiedVariables& identified) {
  std::string note = std::string(row.name) + " = " + number(value) + " [" + row.unit + "]";
  const auto found = identified.find(row.name);
  if (found == identified.end()) return note + " (case value)";
  const identify::ReportedInterval& interval = found->second;
  if (!interval.available) return note + " (identified; no interval: study not finished)";
  return note + " (identified, 95 % interval " + identify::interval_text(interval) +
         (interval.identifiable ? ")" : ", NOT identifiable from the study's targets)");
}

// One peratomtypepair fix for atom types 1 (particles) and 2 (walls): 1-1, 1-2, 2-1, 2-2. The wall
// type's own 2-2 entry is never used (walls do not touch walls); it repeats 1-2.
void write_pair_property(std::ostringstream& out, const PairProperty& property, const CaseSpec& spec,
                         const IdentifiedVariables& identified, std::set<std::string>& written) {
  const ParameterRow& particle = row_at(property.particle_field);
  const ParameterRow& wall = row_at(property.wall_field);
  const double pair_value = particle.get(spec), wall_value = wall.get(spec);
  out << comment(std::string(property.liggghts) + " [" + particle.unit +
                 "]: particle-particle " + value_note(particle, pair_value, identified));
  if (&wall == &particle) {
    out << comment("  particle-wall: the same value (one " + std::string(particle.name) + " for pairs and walls)");
  } else if (spec.wall_friction_as_particles) {
    // The tie of with_parameters: wall FRICS = ratio x FRICS, wall rolling friction = FRICR.
    std::string tie = "  particle-wall " + number(wall_value) + ": tied to the particles' value";
    if (&particle == &row_at(kFriction.particle_field)) {
      const ParameterRow& ratio = row_at(kFrictionRatioField);
      tie += " as " + value_note(ratio, ratio.get(spec), identified) + " x " + particle.name;
      written.insert(ratio.name);
    }
    out << comment(tie + " (wall_contact.friction_as_particles)");
  } else {
    out << comment("  particle-wall " + value_note(wall, wall_value, identified));
  }
  written.insert(particle.name);
  written.insert(wall.name);
  out << "fix demfit_" << property.liggghts << " all property/global " << property.liggghts << " peratomtypepair 2 "
      << number(pair_value) << ' ' << number(wall_value) << ' ' << number(wall_value) << ' ' << number(wall_value)
      << "\n";
}

// youngsModulus and poissonsRatio per atom type: the particle material and the wall material.
void write_elastic_properties(std::ostringstream& out, const CaseSpec& spec) {
  const double particle_modulus = spec.material.youngs_modulus;
  const bool rigid_wall = !(spec.wall.youngs_modulus > 0.0);
  const double wall_modulus = rigid_wall ? kRigidWallFactor * particle_modulus : spec.wall.youngs_modulus;
  out << comment("youngsModulus [Pa]: particles particle.youngs_modulus = " + number(particle_modulus) +
                 ", walls wall_contact.youngs_modulus = " + number(spec.wall.youngs_modulus) + " (case values)");
  if (rigid_wall)
    out << comment("  the case's walls are rigid (0); LIGGGHTS needs a finite modulus: 1000 x the particles' E, "
                   "which lowers E* of a wall contact by 0.1 %");
  out << "fix demfit_youngsModulus all property/global youngsModulus peratomtype " << number(particle_modulus) << ' '
      << number(wall_modulus) << "\n";
  out << comment("poissonsRatio [-]: particles particle.poisson_ratio = " + number(spec.material.poisson_ratio) +
                 ", walls wall_contact.poisson_ratio = " + number(spec.wall.poisson_ratio) + " (case values)");
  out << "fix demfit_poissonsRatio all property/global poissonsRatio peratomtype " << number(spec.material.poisson_ratio)
      << ' ' << number(spec.wall.poisson_ratio) << "\n";
}

// "model hertz tangential history [cohesion sjkr] rolling_friction cdt" (pair_gran.html order).
std::string contact_models(const CaseSpec& spec) {
  std::string models = "model hertz tangential history";
  if (spec.contact.cohesion_energy_density > 0.0)
    models += std::string(" cohesion ") + dem_core::model_name(dem_core::kCohesionModels, spec.contact.cohesion_model);
  return models + " rolling_friction " + dem_core::model_name(dem_core::kRollingModels, spec.contact.rolling_model);
}

void write_header(std::ostringstream& out, const CaseSpec& spec, const std::string& title) {
  out << comment("demfit export for LIGGGHTS 3.8: " + title)
      << comment("Hertz-Mindlin contact identified by demfit. SI units: moduli in Pa, cohesion energy density in")
      << comment("J/m^3, restitution and friction coefficients dimensionless.")
      << comment("Include after create_box / read_data of a box with 2 atom types: 1 = particles, 2 = walls;")
      << comment("give your walls type 2 and use the wall model of this file, e.g.")
      << comment("  fix walls all wall/gran ${demfit_wall_model} mesh n_meshes 1 meshes cad");
  std::string particles = "particles of the case: density " + number(spec.material.density) + " kg/m^3";
  const auto none = SizeDistributionSpec::Source::none;
  if (spec.kind == CaseKind::rotary_drum && spec.drum.size_distribution.source != none)
    particles += ", the case's size distribution (drum.size_distribution)";
  else if (spec.kind == CaseKind::mesh_container && spec.mesh_container.size_distribution.source != none)
    particles += ", the case's size distribution (mesh_container.size_distribution)";
  else
    particles += ", radius " + number(spec.material.radius) + " m";
  if (spec.kind == CaseKind::rotary_drum && spec.drum.scale_factor != 1.0)
    particles += "; simulated coarse-grained (" + to_string(spec.drum.coarse_graining) + ", scale factor " +
                 number(spec.drum.scale_factor) + "): the values were identified at that particle size";
  out << comment(particles);
  if (spec.time_step.value > 0.0) out << comment("time step of the case: " + number(spec.time_step.value) + " s");
}

// The study's variables this snippet does not carry (a drum fill amount, or another effect).
void write_uncarried(std::ostringstream& out, const identify::ParameterSet& answer, const IdentifiedVariables& identified,
                     const std::set<std::string>& written) {
  for (const auto& [name, interval] : identified) {
    if (written.count(name)) continue;
    const ParameterRow* row = find_parameter(name);
    const auto value = answer.find(name);
    const std::string text = row && value != answer.end() ? value_note(*row, value->second, identified) : name;
    out << comment(text + ": not a LIGGGHTS contact property" +
                   (row && row->home == ParameterHome::fill ? " (a fill amount: set it in your insertion)" : ""));
  }
}

// The LIGGGHTS command lines of a snippet (no comments): what two experiments must share.
std::vector<std::string> commands_of(const std::string& snippet) {
  std::vector<std::string> commands;
  std::istringstream in(snippet);
  for (std::string line; std::getline(in, line);)
    if (!line.empty() && line[0] != '#') commands.push_back(line);
  return commands;
}

}  // namespace

std::string liggghts_snippet(const CaseSpec& base, const identify::ParameterSet& answer,
                             const IdentifiedVariables& identified, const std::string& title) {
  if (base.law != dem_core::ContactLawKind::hertz_mindlin)
    throw std::runtime_error(
        "--liggghts: the study's case uses contact law " + to_string(base.law) +
        ", whose NORMK/SHEARK springs scale with each particle's radius (k = NORMK K R) with damping as a fraction "
        "of critical; LIGGGHTS 3.8 has no such contact (hooke/stiffness takes one fixed spring per atom-type pair, "
        "hertz is nonlinear): export it with --lsdyna, or identify a case with contact.law = hertz_mindlin");
  const CaseSpec spec = detail::with_parameters(base, answer);
  std::ostringstream out;
  std::set<std::string> written;
  write_header(out, spec, title);
  write_elastic_properties(out, spec);
  write_pair_property(out, kRestitution, spec, identified, written);
  write_pair_property(out, kFriction, spec, identified, written);
  if (!(spec.contact.frics > 0.0))
    out << comment("frics = 0: demfit keeps the particles from rotating at all; LIGGGHTS has no such switch");
  write_pair_property(out, kRollingFriction, spec, identified, written);
  if (spec.contact.cohesion_energy_density > 0.0) write_pair_property(out, kCohesion, spec, identified, written);
  write_uncarried(out, answer, identified, written);
  const std::string models = contact_models(spec);
  out << "pair_style gran " << models << "\npair_coeff * *\n"
      << comment("the same contact models for fix wall/gran: ${demfit_wall_model}")
      << "variable demfit_wall_model string \"" << models << "\"\n";
  return out.str();
}

std::string liggghts_snippet(const std::vector<std::pair<std::string, CaseSpec>>& experiments,
                             const identify::ParameterSet& answer, const IdentifiedVariables& identified,
                             const std::string& title) {
  if (experiments.empty()) throw std::runtime_error("--liggghts: the study has no experiments");
  const std::string first = liggghts_snippet(experiments.front().second, answer, identified, title);
  const std::vector<std::string> first_commands = commands_of(first);
  std::string names = experiments.front().first;
  for (std::size_t i = 1; i < experiments.size(); ++i) {
    const auto& [name, spec] = experiments[i];
    const std::vector<std::string> commands = commands_of(liggghts_snippet(spec, answer, identified, title));
    for (std::size_t k = 0; k < std::max(commands.size(), first_commands.size()); ++k) {
      const std::string a = k < first_commands.size() ? first_commands[k] : "(none)";
      const std::string b = k < commands.size() ? commands[k] : "(none)";
      if (a != b)
        throw std::runtime_error("--liggghts: experiments '" + experiments.front().first + "' and '" + name +
                                 "' simulate different contact values ('" + a + "' against '" + b +
                                 "'); one LIGGGHTS material needs the same contact in every experiment");
    }
    names += ", " + name;
  }
  // After the title line: the experiments the one material stands for.
  const std::size_t title_end = first.find('\n') + 1;
  return first.substr(0, title_end) +
         comment("one material for the study's experiments " + names + " (their LIGGGHTS commands are the same)") +
         first.substr(title_end);
}

}  // namespace demfit::cases
