// Strict parsing of case files into CaseSpec and back (see case_spec.hpp).
#include "demfit/cases/case_spec.hpp"
#include "demfit/identify/json_document.hpp"

#include <array>
#include <fstream>
#include <optional>
#include <numbers>
#include <stdexcept>

#include "demfit/cases/case_registry.hpp"
#include "demfit/cases/json_fields.hpp"
#include "demfit/cases/parameter_table.hpp"
#include "demfit/cases/section_fields.hpp"
#include "demfit/dem_core/contact_laws.hpp"
#include "drum_case.hpp"
#include "mesh_container_case.hpp"
#include "pellet_case.hpp"

namespace demfit::cases {
namespace {

using nlohmann::json;

// The particle's material (its radius_spread is a parameter-table row, read with its range).
const std::array<SectionField<MaterialSpec>, 4> kParticleFields{{
    {"radius", &MaterialSpec::radius, Sign::positive},
    {"density", &MaterialSpec::density, Sign::positive},
    {"youngs_modulus", &MaterialSpec::youngs_modulus, Sign::positive},
    {"poisson_ratio", &MaterialSpec::poisson_ratio, Sign::any, -0.99, 0.499},
}};

MaterialSpec parse_material(const json& j, MaterialSpec m) {
  const char* p = "particle";
  require_known_keys(j, p, section_keys<MaterialSpec>(kParticleFields, {"radius_spread"}));
  read_section_fields<MaterialSpec>(j, p, kParticleFields, m);
  m.radius_spread = read_parameter(j, p, "radius_spread", m.radius_spread);  // range: parameter table
  return m;
}

constexpr auto kLsDyna = dem_core::ContactLawKind::lsdyna_linear;
constexpr auto kHertz = dem_core::ContactLawKind::hertz_mindlin;

std::vector<std::string> keys_with(std::vector<std::string> keys, std::string_view section,
                                   dem_core::ContactLawKind law) {
  for (std::string& key : parameter_keys(section, law)) keys.push_back(std::move(key));
  return keys;
}

// The Hertz-only keys, refused in an lsdyna_linear file with the fix named.
void refuse_hertz_keys(const json& contact) {
  if (contact.contains("rolling_model") &&
      read_contact_model(contact, "rolling_model", dem_core::kRollingModels, dem_core::RollingModel::constant_torque) !=
          dem_core::RollingModel::constant_torque)
    throw std::runtime_error(
        "'contact.rolling_model' = \"epsd2\" needs law hertz_mindlin: lsdyna_linear has the constant torque "
        "(\"cdt\") only");
  for (const char* key : {"cohesion_energy_density", "cohesion_model"})
    if (contact.contains(key))
      throw std::runtime_error("'contact." + std::string(key) +
                               "' (SJKR cohesion) needs law hertz_mindlin: lsdyna_linear's cohesion is "
                               "contact.surface_energy");
}

// LS-DYNA *CONTROL_DISCRETE_ELEMENT (with the effects) and coupling card 2: every key is a row of
// the parameter table, read with its range ("rolling_model": "cdt" is accepted, the law's only one).
void parse_lsdyna_contact(json contact, const json& wall, CaseSpec& spec) {
  refuse_hertz_keys(contact);
  contact.erase("rolling_model");
  require_known_keys(contact, "contact", parameter_keys("contact", kLsDyna));
  read_parameter_fields(contact, "contact", kLsDyna, spec);
  if (!contact.contains("fricd")) spec.contact.fricd = spec.contact.frics;  // LS-DYNA: FRICD defaults to FRICS
  require_known_keys(wall, "wall_contact", parameter_keys("wall_contact", kLsDyna));
  read_parameter_fields(wall, "wall_contact", kLsDyna, spec);
}

// Hertz–Mindlin contact: restitution, sliding and rolling friction; the
// LS-DYNA springs and dampers do not exist in this law, so their keys are refused.
void parse_hertz_contact(const json& j, CaseSpec& spec) {
  require_known_keys(j, "contact", keys_with({"law", "cohesion_model", "rolling_model"}, "contact", kHertz));
  if (!j.contains("restitution"))
    throw std::runtime_error(
        "'contact.restitution' is missing: law hertz_mindlin needs the coefficient of restitution in " +
        find_parameter("restitution")->valid.to_string());
  read_parameter_fields(j, "contact", kHertz, spec);
  ContactSpec& c = spec.contact;
  c.cohesion_model = read_contact_model(j, "cohesion_model", dem_core::kCohesionModels, c.cohesion_model);
  c.rolling_model = read_contact_model(j, "rolling_model", dem_core::kRollingModels, c.rolling_model);
  spec.contact.fricd = spec.contact.frics;  // one Coulomb coefficient, no velocity dependence (LIGGGHTS' hertz model)
  spec.contact.dc = 0.0;
}

// Hertz wall: its elastic material (default: the particle's) and friction; "fricr" is the
// wall rolling friction (stored in WallContactParameters::fricd, its LS-DYNA place).
void parse_hertz_wall(const json& j, CaseSpec& spec) {
  const char* p = "wall_contact";
  require_known_keys(j, p, keys_with({"youngs_modulus", "poisson_ratio", "friction_as_particles"}, p, kHertz));
  WallContactSpec& w = spec.wall;
  w.youngs_modulus = read_number(j, p, "youngs_modulus", spec.material.youngs_modulus, Sign::positive);
  w.poisson_ratio = read_bounded(j, p, "poisson_ratio", spec.material.poisson_ratio, -0.99, 0.499);
  spec.wall_friction_as_particles = read_bool(j, p, "friction_as_particles", false);
  if (spec.wall_friction_as_particles && (j.contains("frics") || j.contains("fricr")))
    throw std::runtime_error(
        "'wall_contact.frics'/'wall_contact.fricr' cannot be given with 'wall_contact.friction_as_particles' = true: "
        "remove one");
  read_parameter_fields(j, p, kHertz, spec);
  if (!spec.wall_friction_as_particles && spec.wall_friction_ratio != 1.0)
    throw std::runtime_error(
        "'wall_contact.friction_ratio' scales the wall friction tied to the particles': it needs "
        "'wall_contact.friction_as_particles' = true (or give 'wall_contact.frics' instead)");
  w.damp = 0.0;
  w.sfp = 1.0;
}

TimeStepSpec parse_time_step(const json& j, TimeStepSpec t) {
  const char* p = "time_step";
  require_known_keys(j, p, {"value", "factor"});
  t.value = read_number(j, p, "value", t.value, Sign::non_negative);
  t.factor = read_bounded(j, p, "factor", t.factor, 1e-6, 1.0);
  return t;
}

NumericsSpec parse_numerics(const json& j, NumericsSpec n) {
  require_known_keys(j, "numerics", {"reorder_particles", "pair_load_order"});
  n.reorder_particles = read_bool(j, "numerics", "reorder_particles", n.reorder_particles);
  const std::string order = read_string(j, "numerics", "pair_load_order", to_string(n.pair_load_order));
  if (order == to_string(dem_core::PairLoadOrder::own_row_first))
    n.pair_load_order = dem_core::PairLoadOrder::own_row_first;
  else if (order == to_string(dem_core::PairLoadOrder::ascending_first_member))
    n.pair_load_order = dem_core::PairLoadOrder::ascending_first_member;
  else
    throw std::runtime_error(
        "'numerics.pair_load_order' must be \"own_row_first\" or \"ascending_first_member\" (got \"" + order + "\")");
  return n;
}

OutputSpec parse_output(const json& j, OutputSpec o) {
  const char* p = "output";
  require_known_keys(j, p, {"snapshot_times", "progress_interval"});
  if (j.contains("snapshot_times")) {
    const json& times = j.at("snapshot_times");
    if (!times.is_array()) throw std::runtime_error("'output.snapshot_times' must be an array of times [s]");
    o.snapshot_times.clear();
    for (const json& t : times) {
      if (!t.is_number() || t.get<double>() < 0.0) {
        throw std::runtime_error("'output.snapshot_times' entries must be numbers >= 0 [s]");
      }
      o.snapshot_times.push_back(t.get<double>());
    }
  }
  o.progress_interval = read_number(j, p, "progress_interval", o.progress_interval, Sign::positive);
  return o;
}

}  // namespace

double MaterialSpec::bulk_modulus() const { return youngs_modulus / (3.0 * (1.0 - 2.0 * poisson_ratio)); }

std::string to_string(dem_core::ContactLawKind law) { return std::string(dem_core::contact_law_name(law)); }

std::string to_string(dem_core::PairLoadOrder order) {
  switch (order) {
    case dem_core::PairLoadOrder::own_row_first:
      return "own_row_first";
    case dem_core::PairLoadOrder::ascending_first_member:
      return "ascending_first_member";
  }
  return "own_row_first";
}

namespace {

// Kinds whose case files may select the Hertz-Mindlin law (its fill and stiffness set-up exist
// for the drum only).
bool hertz_supported(CaseKind kind) {
  switch (kind) {
    case CaseKind::pellet_compression:
      return false;
    case CaseKind::rotary_drum:
    case CaseKind::mesh_container:
      return true;
  }
  return false;
}

// "lsdyna_linear" or "hertz_mindlin": every row of the law registry, for messages.
std::string law_names() {
  std::string names;
  for (const dem_core::ContactLawRow& row : dem_core::kContactLaws)
    names += (names.empty() ? "\"" : " or \"") + std::string(row.name) + "\"";
  return names;
}

// Hertz–Mindlin contact and wall fields, and what the law excludes.
void parse_hertz_case(const json& document, const json& contact, CaseSpec& spec) {
  if (!hertz_supported(spec.kind))
    throw std::runtime_error(
        "'contact.law' = \"hertz_mindlin\" is supported by rotary_drum and mesh_container cases only: use "
        "lsdyna_linear");
  parse_hertz_contact(contact, spec);
  parse_hertz_wall(child_object(document, "", "wall_contact"), spec);
  if (spec.wall_friction_as_particles) {
    spec.wall.frics = spec.contact.frics * spec.wall_friction_ratio;  // exact for the ratio 1
    spec.wall.fricd = spec.contact.fricr;
  }
  if (spec.material.radius_spread != 0.0)
    throw std::runtime_error(
        "'particle.radius_spread' is an effect of law lsdyna_linear: use drum.size_distribution (or "
        "mesh_container.size_distribution) with hertz_mindlin");
}

}  // namespace

CaseSpec parse_case(const json& document, const std::filesystem::path& base_dir) {
  require_known_keys(document, "",
                     {"case", "description", "particle", "contact", "wall_contact", "time_step", "output", "numerics",
                      "pellet", "drum", "mesh_container"});
  CaseSpec spec;
  if (!document.contains("case")) throw std::runtime_error("'case' is missing: set \"case\": " + case_kind_names());
  const std::string kind = read_string(document, "", "case", "");
  const CaseKindRow* row = find_case_kind(kind);
  if (!row) throw std::runtime_error("'case' must be " + case_kind_names() + " (got \"" + kind + "\")");
  spec.kind = row->kind;
  for (const CaseKindRow& other : case_kind_table())
    if (other.kind != row->kind && document.contains(other.section))
      throw std::runtime_error("'" + std::string(other.section) + "' is not allowed in a " + row->name + " case");
  spec.description = read_string(document, "", "description", "");
  spec.material = parse_material(child_object(document, "", "particle"), spec.material);
  const json& contact = child_object(document, "", "contact");
  const std::string law = read_string(contact, "contact", "law", "lsdyna_linear");
  const std::optional<dem_core::ContactLawKind> kind_of_law = dem_core::contact_law_kind(law);
  if (!kind_of_law) throw std::runtime_error("'contact.law' must be " + law_names() + " (got \"" + law + "\")");
  spec.law = *kind_of_law;
  switch (spec.law) {  // the law's own contact fields (dem_core/contact_laws.hpp: the law registry)
    case dem_core::ContactLawKind::hertz_mindlin:
      parse_hertz_case(document, contact, spec);
      break;
    case dem_core::ContactLawKind::lsdyna_linear: {
      json plain = contact;
      plain.erase("law");
      parse_lsdyna_contact(plain, child_object(document, "", "wall_contact"), spec);
      break;
    }
  }
  spec.time_step = parse_time_step(child_object(document, "", "time_step"), spec.time_step);
  spec.output = parse_output(child_object(document, "", "output"), spec.output);
  spec.numerics = parse_numerics(child_object(document, "", "numerics"), spec.numerics);
  switch (spec.kind) {  // the kind's own section (cases/<kind>/<kind>_section.cpp)
    case CaseKind::pellet_compression:
      spec.pellet = detail::parse_pellet_section(child_object(document, "", "pellet"), spec.pellet);
      break;
    case CaseKind::rotary_drum:
      detail::parse_drum_section(document, spec, base_dir);
      break;
    case CaseKind::mesh_container:
      detail::parse_mesh_container_section(document, spec, base_dir);
      break;
  }
  return spec;
}

json to_json(const CaseSpec& s) {
  json j;
  j["case"] = case_kind_row(s.kind).name;
  j["description"] = s.description;
  j["particle"] = json::object();
  write_section_fields<MaterialSpec>(j["particle"], kParticleFields, s.material);
  j["particle"]["radius_spread"] = s.material.radius_spread;
  const bool distribution = (s.kind == CaseKind::rotary_drum && s.drum.size_distribution.enabled()) ||
                            (s.kind == CaseKind::mesh_container && s.mesh_container.size_distribution.enabled());
  if (distribution) j["particle"].erase("radius");
  // The identified parameters' fields come from the parameter table (write_parameter_fields).
  switch (s.law) {
    case dem_core::ContactLawKind::hertz_mindlin:
      j["particle"].erase("radius_spread");
      j["contact"] = {{"law", to_string(s.law)}};
      write_parameter_fields(j["contact"], "contact", s.law, s);
      j["contact"]["cohesion_model"] = dem_core::model_name(dem_core::kCohesionModels, s.contact.cohesion_model);
      j["contact"]["rolling_model"] = dem_core::model_name(dem_core::kRollingModels, s.contact.rolling_model);
      j["wall_contact"] = {{"youngs_modulus", s.wall.youngs_modulus}, {"poisson_ratio", s.wall.poisson_ratio}};
      if (s.wall_friction_as_particles) {
        j["wall_contact"]["friction_as_particles"] = true;
        if (s.wall_friction_ratio != 1.0) j["wall_contact"]["friction_ratio"] = s.wall_friction_ratio;
      } else {
        write_parameter_fields(j["wall_contact"], "wall_contact", s.law, s);
        j["wall_contact"].erase("friction_ratio");  // 1 without the tie (parse_hertz_wall)
      }
      break;
    case dem_core::ContactLawKind::lsdyna_linear:
      // The text of a case file from before the law could be chosen (no "law" key).
      j["contact"] = json::object();
      write_parameter_fields(j["contact"], "contact", s.law, s);
      j["wall_contact"] = json::object();
      write_parameter_fields(j["wall_contact"], "wall_contact", s.law, s);
      break;
  }
  j["time_step"] = {{"value", s.time_step.value}, {"factor", s.time_step.factor}};
  j["output"] = {{"snapshot_times", s.output.snapshot_times}, {"progress_interval", s.output.progress_interval}};
  j["numerics"] = {{"reorder_particles", s.numerics.reorder_particles},
                   {"pair_load_order", to_string(s.numerics.pair_load_order)}};
  switch (s.kind) {
    case CaseKind::pellet_compression:
      j["pellet"] = detail::pellet_section_json(s.pellet);
      break;
    case CaseKind::rotary_drum:
      j["drum"] = detail::drum_section_json(s.drum);
      break;
    case CaseKind::mesh_container:
      j["mesh_container"] = detail::mesh_container_section_json(s.mesh_container);
      break;
  }
  return j;
}

json to_key_json(const CaseSpec& s) {
  json j = to_json(s);
  // Effects at their off values leave the key (the parameter table's effect rows).
  for (const ParameterRow& row : parameter_table()) {
    if (row.home != ParameterHome::effect || !(row.get(s) == row.off_value)) continue;
    const std::string path = row.case_path;
    const auto dot = path.find('.');
    const std::string section = path.substr(0, dot);
    if (j.contains(section)) j[section].erase(path.substr(dot + 1));
  }
  // So do the Hertz law's default models (sjkr, cdt).
  if (s.law == dem_core::ContactLawKind::hertz_mindlin) {
    const dem_core::ContactParameters defaults;
    if (s.contact.cohesion_model == defaults.cohesion_model) j["contact"].erase("cohesion_model");
    if (s.contact.rolling_model == defaults.rolling_model) j["contact"].erase("rolling_model");
  }
  // Insertion order (the default) leaves the keys, and so the cached fills and results, as before.
  const NumericsSpec defaults;
  if (s.numerics.reorder_particles == defaults.reorder_particles) j["numerics"].erase("reorder_particles");
  if (s.numerics.pair_load_order == defaults.pair_load_order) j["numerics"].erase("pair_load_order");
  if (j["numerics"].empty()) j.erase("numerics");
  // The CSV's content (not only its name) decides the fill.
  if (s.kind == CaseKind::rotary_drum && s.drum.size_distribution.source == SizeDistributionSpec::Source::csv)
    j["drum"]["size_distribution"]["content_hash"] = std::to_string(s.drum.size_distribution.content_hash());
  // So do the STL files' triangles (and a size CSV's content) of a mesh_container case.
  if (s.kind == CaseKind::mesh_container) {
    for (std::size_t p = 0; p < s.mesh_container.meshes.size(); ++p)
      j["mesh_container"]["meshes"][p]["content_hash"] = std::to_string(s.mesh_container.meshes[p].content_hash);
    if (s.mesh_container.size_distribution.source == SizeDistributionSpec::Source::csv)
      j["mesh_container"]["size_distribution"]["content_hash"] =
          std::to_string(s.mesh_container.size_distribution.content_hash());
  }
  // So does the user's drum STL (its triangles' hash).
  if (s.kind == CaseKind::rotary_drum && s.drum.wall_mesh.source == DrumWallMeshSpec::Source::stl)
    j["drum"]["wall_mesh"]["content_hash"] = std::to_string(s.drum.wall_mesh.stl_hash);
  return j;
}

json read_case_json(const std::string& path) {
  // Size, nesting depth and duplicate keys checked while reading (identify/json_document.hpp).
  return identify::read_json_file(path, "case file");
}

const std::vector<std::string>& parameter_names() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> out;
    for (const ParameterRow& row : parameter_table()) out.emplace_back(row.name);
    return out;
  }();
  return names;
}

std::string parameter_path(const std::string& name) {
  const ParameterRow* row = find_parameter(name);
  return row ? row->case_path : "";
}

void apply_setting(json& document, const std::string& assignment) {
  const auto eq = assignment.find('=');
  if (eq == std::string::npos || eq == 0) {
    throw std::runtime_error("--set '" + assignment + "' must have the form name=value");
  }
  const std::string name = assignment.substr(0, eq);
  const std::string text = assignment.substr(eq + 1);
  json value;
  try {
    value = json::parse(text);
  } catch (const json::out_of_range&) {  // 1e999: a number JSON cannot hold
    throw std::runtime_error("--set '" + name + "': " + text + " is out of range; give a finite number");
  } catch (const json::exception&) {
    value = text;  // a bare word: a string (e.g. coarse_graining=cvf)
  }
  std::string path = parameter_path(name);
  if (path.empty()) path = name;
  // Hertz files may name a parameter's field differently (the wall rolling friction is "fricr"
  // there; its LS-DYNA card calls it FRICD).
  const ParameterRow* row = find_parameter(name);
  if (row && row->hertz_path && document.contains("contact") && document["contact"].is_object() &&
      document["contact"].value("law", "") == "hertz_mindlin")
    path = row->hertz_path;
  // A fill amount replaces the file's fill amount (exactly one may be given).
  for (const char* fill : detail::kDrumFillKeys) {
    if (path != std::string("drum.") + fill || !document.contains("drum") || !document["drum"].is_object()) continue;
    for (const char* other : detail::kDrumFillKeys) document["drum"].erase(other);
  }
  json* node = &document;
  std::size_t start = 0;
  while (true) {
    const auto dot = path.find('.', start);
    const std::string key = path.substr(start, dot == std::string::npos ? std::string::npos : dot - start);
    if (key.empty()) throw std::runtime_error("--set '" + name + "': empty path component");
    if (dot == std::string::npos) {
      (*node)[key] = value;
      return;
    }
    json& child = (*node)[key];
    if (child.is_null()) child = json::object();
    if (!child.is_object()) throw std::runtime_error("--set '" + name + "': '" + key + "' is not an object");
    node = &child;
    start = dot + 1;
  }
}

}  // namespace demfit::cases
