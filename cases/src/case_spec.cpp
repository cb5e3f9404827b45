// Strict parsing of case files into CaseSpec and back (see case_spec.hpp).
#include "demfit/cases/case_spec.hpp"
#include "demfit/identify/json_document.hpp"

#include <fstream>
#include <numbers>
#include <stdexcept>

#include "demfit/cases/case_registry.hpp"
#include "demfit/cases/json_fields.hpp"
#include "demfit/cases/parameter_table.hpp"

namespace demfit::cases {
namespace {

using nlohmann::json;

MaterialSpec parse_material(const json& j, MaterialSpec m) {
  const char* p = "particle";
  require_known_keys(j, p, {"radius", "density", "youngs_modulus", "poisson_ratio", "radius_spread"});
  m.radius = read_number(j, p, "radius", m.radius, Sign::positive);
  m.density = read_number(j, p, "density", m.density, Sign::positive);
  m.youngs_modulus = read_number(j, p, "youngs_modulus", m.youngs_modulus, Sign::positive);
  m.poisson_ratio = read_bounded(j, p, "poisson_ratio", m.poisson_ratio, -0.99, 0.499);
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

// LS-DYNA *CONTROL_DISCRETE_ELEMENT (with the effects) and coupling card 2: every key is a row of
// the parameter table, read with its range.
void parse_lsdyna_contact(const json& contact, const json& wall, CaseSpec& spec) {
  require_known_keys(contact, "contact", parameter_keys("contact", kLsDyna));
  read_parameter_fields(contact, "contact", kLsDyna, spec);
  if (!contact.contains("fricd")) spec.contact.fricd = spec.contact.frics;  // LS-DYNA: FRICD defaults to FRICS
  require_known_keys(wall, "wall_contact", parameter_keys("wall_contact", kLsDyna));
  read_parameter_fields(wall, "wall_contact", kLsDyna, spec);
}

// Hertz–Mindlin contact (issue 12 item 3): restitution, sliding and rolling friction; the
// LS-DYNA springs and dampers do not exist in this law, so their keys are refused.
void parse_hertz_contact(const json& j, CaseSpec& spec) {
  require_known_keys(j, "contact", keys_with({"law"}, "contact", kHertz));
  if (!j.contains("restitution"))
    throw std::runtime_error(
        "'contact.restitution' is missing: law hertz_mindlin needs the coefficient of restitution in " +
        find_parameter("restitution")->valid.to_string());
  read_parameter_fields(j, "contact", kHertz, spec);
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

PelletSpec parse_pellet(const json& j, PelletSpec s) {
  const char* p = "pellet";
  require_known_keys(j, p,
                     {"container_diameter", "container_height", "particle_count", "fill_seed", "fill_normk",
                      "settle_time", "piston_speed", "max_pressure", "max_travel", "unload", "curve_points"});
  s.container_diameter = read_number(j, p, "container_diameter", s.container_diameter, Sign::positive);
  s.container_height = read_number(j, p, "container_height", s.container_height, Sign::positive);
  s.particle_count = read_integer(j, p, "particle_count", s.particle_count, 1);
  s.fill_seed = read_integer(j, p, "fill_seed", s.fill_seed, 0);
  s.fill_normk = read_number(j, p, "fill_normk", s.fill_normk, Sign::positive);
  s.settle_time = read_number(j, p, "settle_time", s.settle_time, Sign::positive);
  s.piston_speed = read_number(j, p, "piston_speed", s.piston_speed, Sign::positive);
  s.max_pressure = read_number(j, p, "max_pressure", s.max_pressure, Sign::positive);
  s.max_travel = read_number(j, p, "max_travel", s.max_travel, Sign::positive);
  s.unload = read_bool(j, p, "unload", s.unload);
  s.curve_points = read_integer(j, p, "curve_points", s.curve_points, 2);
  return s;
}

DrumImageSpec parse_drum_image(const json& j) {
  const char* p = "drum.image";
  require_known_keys(j, p, {"pixels", "margin", "points"});
  DrumImageSpec image;
  image.enabled = true;
  image.pixels = read_integer(j, p, "pixels", image.pixels, 32);
  image.margin = read_bounded(j, p, "margin", image.margin, 0.0, 0.95);
  image.points = read_integer(j, p, "points", image.points, 2);
  return image;
}

// Exactly one fill amount (fill_fraction when none is given; see FillBy).
void parse_fill_amount(const json& j, DrumSpec& s) {
  const char* p = "drum";
  int given = 0;
  for (const char* k : {"fill_fraction", "fill_volume_ml", "particle_count", "fill_mass"})
    given += j.contains(k) ? 1 : 0;
  if (given > 1)
    throw std::runtime_error("'drum': give exactly one of fill_fraction, fill_volume_ml, particle_count or fill_mass");
  s.fill_fraction = read_bounded(j, p, "fill_fraction", s.fill_fraction, 0.01, 0.9);
  if (j.contains("fill_volume_ml")) {
    s.fill_by = FillBy::fill_volume;
    s.fill_volume_ml = read_parameter(j, p, "fill_volume_ml", 0.0);
  } else if (j.contains("particle_count")) {
    s.fill_by = FillBy::particle_count;
    s.particle_count =
        read_integer(j, p, "particle_count", 0, static_cast<long long>(find_parameter("particle_count")->valid.lower));
  } else if (j.contains("fill_mass")) {
    s.fill_by = FillBy::fill_mass;
    s.fill_mass = read_number(j, p, "fill_mass", 0.0, Sign::positive);
  } else if (j.contains("fill_fraction")) {
    s.fill_by = FillBy::fill_fraction;
  }
}

DrumSpec parse_drum(const json& j, DrumSpec s, const std::filesystem::path& base_dir) {
  const char* p = "drum";
  require_known_keys(
      j, p,
      {"diameter", "length", "rpm", "duration", "fill_fraction", "volume_fraction", "coarse_graining", "scale_factor",
       "fill_seed", "densify_time", "torque_interval", "surface_window", "surface_snapshots", "surface_points",
       "fill_volume_ml", "particle_count", "fill_mass", "size_distribution", "image"});
  s.diameter = read_number(j, p, "diameter", s.diameter, Sign::positive);
  s.length = read_number(j, p, "length", s.length, Sign::positive);
  s.rpm = read_number(j, p, "rpm", s.rpm);
  s.duration = read_number(j, p, "duration", s.duration, Sign::positive);
  parse_fill_amount(j, s);
  s.volume_fraction = read_bounded(j, p, "volume_fraction", s.volume_fraction, 0.05, 1.0);
  const std::string cg = read_string(j, p, "coarse_graining", to_string(s.coarse_graining));
  try {
    s.coarse_graining = parse_coarse_graining(cg);
  } catch (const std::exception&) {
    throw std::runtime_error("'drum.coarse_graining' must be \"scg\" or \"cvf\" (got \"" + cg + "\")");
  }
  s.scale_factor = read_bounded(j, p, "scale_factor", s.scale_factor, 1.0, 16.0);
  s.fill_seed = read_integer(j, p, "fill_seed", s.fill_seed, 0);
  s.densify_time = read_number(j, p, "densify_time", s.densify_time, Sign::positive);
  s.torque_interval = read_number(j, p, "torque_interval", s.torque_interval, Sign::positive);
  s.surface_window = read_number(j, p, "surface_window", s.surface_window, Sign::non_negative);
  s.surface_snapshots = read_integer(j, p, "surface_snapshots", s.surface_snapshots, 1);
  s.surface_points = read_integer(j, p, "surface_points", s.surface_points, 2);
  if (s.surface_window > s.duration) {
    throw std::runtime_error("'drum.surface_window' must not exceed 'drum.duration'");
  }
  if (j.contains("size_distribution"))
    s.size_distribution =
        parse_size_distribution(child_object(j, p, "size_distribution"), "drum.size_distribution", base_dir);
  if (j.contains("image")) s.image = parse_drum_image(child_object(j, p, "image"));
  if (s.fill_by == FillBy::fill_volume) {
    const double drum_ml = std::numbers::pi * 0.25 * s.diameter * s.diameter * s.length * 1e6;
    if (s.fill_volume_ml > 0.9 * drum_ml)
      throw std::runtime_error("'drum.fill_volume_ml' = " + std::to_string(s.fill_volume_ml) +
                               " exceeds 90 % of the drum volume (" + std::to_string(drum_ml) + " mL): lower it");
  }
  return s;
}

}  // namespace

double MaterialSpec::bulk_modulus() const { return youngs_modulus / (3.0 * (1.0 - 2.0 * poisson_ratio)); }

std::string to_string(dem_core::ContactLawKind law) {
  return law == dem_core::ContactLawKind::hertz_mindlin ? "hertz_mindlin" : "lsdyna_linear";
}

namespace {

json pellet_json(const PelletSpec& p) {
  return {{"container_diameter", p.container_diameter},
          {"container_height", p.container_height},
          {"particle_count", p.particle_count},
          {"fill_seed", p.fill_seed},
          {"fill_normk", p.fill_normk},
          {"settle_time", p.settle_time},
          {"piston_speed", p.piston_speed},
          {"max_pressure", p.max_pressure},
          {"max_travel", p.max_travel},
          {"unload", p.unload},
          {"curve_points", p.curve_points}};
}

json drum_json(const DrumSpec& d) {
  json j = {{"diameter", d.diameter},
            {"length", d.length},
            {"rpm", d.rpm},
            {"duration", d.duration},
            {"fill_fraction", d.fill_fraction},
            {"volume_fraction", d.volume_fraction},
            {"coarse_graining", to_string(d.coarse_graining)},
            {"scale_factor", d.scale_factor},
            {"fill_seed", d.fill_seed},
            {"densify_time", d.densify_time},
            {"torque_interval", d.torque_interval},
            {"surface_window", d.surface_window},
            {"surface_snapshots", d.surface_snapshots},
            {"surface_points", d.surface_points}};
  // General-drum options appear only when used, so a paper drum keeps its old text.
  if (d.fill_by != FillBy::fill_fraction) j.erase("fill_fraction");
  if (d.fill_by == FillBy::fill_volume) j["fill_volume_ml"] = d.fill_volume_ml;
  if (d.fill_by == FillBy::particle_count) j["particle_count"] = d.particle_count;
  if (d.fill_by == FillBy::fill_mass) j["fill_mass"] = d.fill_mass;
  if (d.size_distribution.enabled()) j["size_distribution"] = to_json(d.size_distribution);
  if (d.image.enabled)
    j["image"] = {{"pixels", d.image.pixels}, {"margin", d.image.margin}, {"points", d.image.points}};
  return j;
}

// Kinds whose case files may select the Hertz-Mindlin law (its fill and stiffness set-up exist
// for the drum only).
bool hertz_supported(CaseKind kind) {
  switch (kind) {
    case CaseKind::pellet_compression:
      return false;
    case CaseKind::rotary_drum:
      return true;
  }
  return false;
}

}  // namespace

CaseSpec parse_case(const json& document, const std::filesystem::path& base_dir) {
  require_known_keys(
      document, "",
      {"case", "description", "particle", "contact", "wall_contact", "time_step", "output", "pellet", "drum"});
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
  if (law == "hertz_mindlin") {
    if (!hertz_supported(spec.kind))
      throw std::runtime_error(
          "'contact.law' = \"hertz_mindlin\" is supported by rotary_drum cases only: use lsdyna_linear");
    spec.law = dem_core::ContactLawKind::hertz_mindlin;
    parse_hertz_contact(contact, spec);
    parse_hertz_wall(child_object(document, "", "wall_contact"), spec);
    if (spec.wall_friction_as_particles) {
      spec.wall.frics = spec.contact.frics;
      spec.wall.fricd = spec.contact.fricr;
    }
    if (spec.material.radius_spread != 0.0)
      throw std::runtime_error(
          "'particle.radius_spread' is an effect of law lsdyna_linear: use drum.size_distribution with hertz_mindlin");
  } else if (law == "lsdyna_linear") {
    json plain = contact;
    plain.erase("law");
    parse_lsdyna_contact(plain, child_object(document, "", "wall_contact"), spec);
  } else {
    throw std::runtime_error("'contact.law' must be \"lsdyna_linear\" or \"hertz_mindlin\" (got \"" + law + "\")");
  }
  spec.time_step = parse_time_step(child_object(document, "", "time_step"), spec.time_step);
  spec.output = parse_output(child_object(document, "", "output"), spec.output);
  switch (spec.kind) {
    case CaseKind::pellet_compression:
      spec.pellet = parse_pellet(child_object(document, "", "pellet"), spec.pellet);
      break;
    case CaseKind::rotary_drum:
      spec.drum = parse_drum(child_object(document, "", "drum"), spec.drum, base_dir);
      if (spec.drum.size_distribution.enabled()) {
        if (child_object(document, "", "particle").contains("radius"))
          throw std::runtime_error(
              "'particle.radius' cannot be given with 'drum.size_distribution': the distribution sets the sizes");
        if (spec.material.radius_spread != 0.0)
          throw std::runtime_error("'particle.radius_spread' cannot be combined with 'drum.size_distribution'");
        spec.material.radius = 0.5 * spec.drum.size_distribution.min_diameter();  // smallest size (time-step checks)
      }
      break;
  }
  return spec;
}

json to_json(const CaseSpec& s) {
  json j;
  j["case"] = case_kind_row(s.kind).name;
  j["description"] = s.description;
  j["particle"] = {{"radius", s.material.radius},
                   {"density", s.material.density},
                   {"youngs_modulus", s.material.youngs_modulus},
                   {"poisson_ratio", s.material.poisson_ratio},
                   {"radius_spread", s.material.radius_spread}};
  const bool distribution = s.kind == CaseKind::rotary_drum && s.drum.size_distribution.enabled();
  if (distribution) j["particle"].erase("radius");
  // The identified parameters' fields come from the parameter table (write_parameter_fields).
  if (s.law == dem_core::ContactLawKind::hertz_mindlin) {
    j["particle"].erase("radius_spread");
    j["contact"] = {{"law", to_string(s.law)}};
    write_parameter_fields(j["contact"], "contact", s.law, s);
    j["wall_contact"] = {{"youngs_modulus", s.wall.youngs_modulus}, {"poisson_ratio", s.wall.poisson_ratio}};
    if (s.wall_friction_as_particles)
      j["wall_contact"]["friction_as_particles"] = true;
    else
      write_parameter_fields(j["wall_contact"], "wall_contact", s.law, s);
  } else {
    // lsdyna_linear: the text of a case file from before the law could be chosen.
    j["contact"] = json::object();
    write_parameter_fields(j["contact"], "contact", s.law, s);
    j["wall_contact"] = json::object();
    write_parameter_fields(j["wall_contact"], "wall_contact", s.law, s);
  }
  j["time_step"] = {{"value", s.time_step.value}, {"factor", s.time_step.factor}};
  j["output"] = {{"snapshot_times", s.output.snapshot_times}, {"progress_interval", s.output.progress_interval}};
  switch (s.kind) {
    case CaseKind::pellet_compression:
      j["pellet"] = pellet_json(s.pellet);
      break;
    case CaseKind::rotary_drum:
      j["drum"] = drum_json(s.drum);
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
  // The CSV's content (not only its name) decides the fill.
  if (s.kind == CaseKind::rotary_drum && s.drum.size_distribution.source == SizeDistributionSpec::Source::csv)
    j["drum"]["size_distribution"]["content_hash"] = std::to_string(s.drum.size_distribution.content_hash());
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
  } catch (const json::parse_error&) {
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
  for (const char* fill : {"drum.fill_fraction", "drum.fill_volume_ml", "drum.particle_count", "drum.fill_mass"}) {
    if (path != fill || !document.contains("drum") || !document["drum"].is_object()) continue;
    for (const char* other : {"fill_fraction", "fill_volume_ml", "particle_count", "fill_mass"})
      document["drum"].erase(other);
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
