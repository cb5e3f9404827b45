// Strict parsing of case files into CaseSpec and back (see case_spec.hpp).
#include "demfit/cases/case_spec.hpp"
#include "demfit/identify/json_document.hpp"

#include <fstream>
#include <stdexcept>

#include "demfit/cases/json_fields.hpp"

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
  // Up to 0.3: the drum's lattice packing (gap 0.03) still holds the s = 1 fill (checked).
  m.radius_spread = read_bounded(j, p, "radius_spread", m.radius_spread, 0.0, 0.3);
  return m;
}

ContactSpec parse_contact(const json& j, ContactSpec c) {
  const char* p = "contact";
  require_known_keys(j, p, {"normk", "sheark", "ndamp", "tdamp", "frics", "fricd", "dc", "fricr",
                            "unloading_stiffness_ratio", "surface_energy", "stiffness_exponent"});
  c.normk = read_number(j, p, "normk", c.normk, Sign::positive);
  c.sheark = read_number(j, p, "sheark", c.sheark, Sign::non_negative);
  c.ndamp = read_bounded(j, p, "ndamp", c.ndamp, 0.0, 1.0);
  c.tdamp = read_bounded(j, p, "tdamp", c.tdamp, 0.0, 1.0);
  c.frics = read_number(j, p, "frics", c.frics, Sign::non_negative);
  // LS-DYNA: FRICD defaults to FRICS.
  c.fricd = read_number(j, p, "fricd", j.contains("fricd") ? c.fricd : c.frics, Sign::non_negative);
  c.dc = read_number(j, p, "dc", c.dc, Sign::non_negative);
  c.fricr = read_number(j, p, "fricr", c.fricr, Sign::non_negative);
  c.unloading_stiffness_ratio =
      read_bounded(j, p, "unloading_stiffness_ratio", c.unloading_stiffness_ratio, 1.0, 100.0);
  c.surface_energy = read_number(j, p, "surface_energy", c.surface_energy, Sign::non_negative);
  c.stiffness_exponent = read_bounded(j, p, "stiffness_exponent", c.stiffness_exponent, 1.0, 2.0);
  return c;
}

WallContactSpec parse_wall(const json& j, WallContactSpec w) {
  const char* p = "wall_contact";
  require_known_keys(j, p, {"frics", "fricd", "damp", "sfp"});
  w.frics = read_number(j, p, "frics", w.frics, Sign::non_negative);
  w.fricd = read_number(j, p, "fricd", w.fricd, Sign::non_negative);
  w.damp = read_bounded(j, p, "damp", w.damp, 0.0, 1.0);
  w.sfp = read_number(j, p, "sfp", w.sfp, Sign::positive);
  return w;
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
  require_known_keys(j, p, {"container_diameter", "container_height", "particle_count", "fill_seed",
                            "fill_normk", "settle_time", "piston_speed", "max_pressure",
                            "max_travel", "unload", "curve_points"});
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

DrumSpec parse_drum(const json& j, DrumSpec s) {
  const char* p = "drum";
  require_known_keys(j, p, {"diameter", "length", "rpm", "duration", "fill_fraction",
                            "volume_fraction", "coarse_graining", "scale_factor", "fill_seed",
                            "densify_time", "torque_interval", "surface_window",
                            "surface_snapshots", "surface_points"});
  s.diameter = read_number(j, p, "diameter", s.diameter, Sign::positive);
  s.length = read_number(j, p, "length", s.length, Sign::positive);
  s.rpm = read_number(j, p, "rpm", s.rpm);
  s.duration = read_number(j, p, "duration", s.duration, Sign::positive);
  s.fill_fraction = read_bounded(j, p, "fill_fraction", s.fill_fraction, 0.01, 0.9);
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
  return s;
}

}  // namespace

double MaterialSpec::bulk_modulus() const {
  return youngs_modulus / (3.0 * (1.0 - 2.0 * poisson_ratio));
}

CaseSpec parse_case(const json& document) {
  require_known_keys(document, "", {"case", "description", "particle", "contact", "wall_contact",
                                    "time_step", "output", "pellet", "drum"});
  CaseSpec spec;
  if (!document.contains("case")) {
    throw std::runtime_error("'case' is missing: set \"case\": \"pellet_compression\" or \"rotary_drum\"");
  }
  const std::string kind = read_string(document, "", "case", "");
  if (kind == "pellet_compression") {
    spec.kind = CaseKind::pellet_compression;
    if (document.contains("drum")) throw std::runtime_error("'drum' is not allowed in a pellet_compression case");
  } else if (kind == "rotary_drum") {
    spec.kind = CaseKind::rotary_drum;
    if (document.contains("pellet")) throw std::runtime_error("'pellet' is not allowed in a rotary_drum case");
  } else {
    throw std::runtime_error("'case' must be \"pellet_compression\" or \"rotary_drum\" (got \"" + kind + "\")");
  }
  spec.description = read_string(document, "", "description", "");
  spec.material = parse_material(child_object(document, "", "particle"), spec.material);
  spec.contact = parse_contact(child_object(document, "", "contact"), spec.contact);
  spec.wall = parse_wall(child_object(document, "", "wall_contact"), spec.wall);
  spec.time_step = parse_time_step(child_object(document, "", "time_step"), spec.time_step);
  spec.output = parse_output(child_object(document, "", "output"), spec.output);
  if (spec.kind == CaseKind::pellet_compression) {
    spec.pellet = parse_pellet(child_object(document, "", "pellet"), spec.pellet);
  } else {
    spec.drum = parse_drum(child_object(document, "", "drum"), spec.drum);
  }
  return spec;
}

json to_json(const CaseSpec& s) {
  json j;
  j["case"] = s.kind == CaseKind::pellet_compression ? "pellet_compression" : "rotary_drum";
  j["description"] = s.description;
  j["particle"] = {{"radius", s.material.radius}, {"density", s.material.density},
                   {"youngs_modulus", s.material.youngs_modulus},
                   {"poisson_ratio", s.material.poisson_ratio},
                   {"radius_spread", s.material.radius_spread}};
  const ContactSpec& c = s.contact;
  j["contact"] = {{"normk", c.normk}, {"sheark", c.sheark}, {"ndamp", c.ndamp}, {"tdamp", c.tdamp},
                  {"frics", c.frics}, {"fricd", c.fricd}, {"dc", c.dc}, {"fricr", c.fricr},
                  {"unloading_stiffness_ratio", c.unloading_stiffness_ratio},
                  {"surface_energy", c.surface_energy}, {"stiffness_exponent", c.stiffness_exponent}};
  j["wall_contact"] = {{"frics", s.wall.frics}, {"fricd", s.wall.fricd}, {"damp", s.wall.damp},
                       {"sfp", s.wall.sfp}};
  j["time_step"] = {{"value", s.time_step.value}, {"factor", s.time_step.factor}};
  j["output"] = {{"snapshot_times", s.output.snapshot_times},
                 {"progress_interval", s.output.progress_interval}};
  if (s.kind == CaseKind::pellet_compression) {
    const PelletSpec& p = s.pellet;
    j["pellet"] = {{"container_diameter", p.container_diameter}, {"container_height", p.container_height},
                   {"particle_count", p.particle_count}, {"fill_seed", p.fill_seed},
                   {"fill_normk", p.fill_normk}, {"settle_time", p.settle_time},
                   {"piston_speed", p.piston_speed}, {"max_pressure", p.max_pressure},
                   {"max_travel", p.max_travel}, {"unload", p.unload}, {"curve_points", p.curve_points}};
  } else {
    const DrumSpec& d = s.drum;
    j["drum"] = {{"diameter", d.diameter}, {"length", d.length}, {"rpm", d.rpm},
                 {"duration", d.duration}, {"fill_fraction", d.fill_fraction},
                 {"volume_fraction", d.volume_fraction},
                 {"coarse_graining", to_string(d.coarse_graining)}, {"scale_factor", d.scale_factor},
                 {"fill_seed", d.fill_seed}, {"densify_time", d.densify_time},
                 {"torque_interval", d.torque_interval}, {"surface_window", d.surface_window},
                 {"surface_snapshots", d.surface_snapshots}, {"surface_points", d.surface_points}};
  }
  return j;
}

json to_key_json(const CaseSpec& s) {
  json j = to_json(s);
  if (s.material.radius_spread == 0.0) j["particle"].erase("radius_spread");
  if (s.contact.unloading_stiffness_ratio == 1.0) j["contact"].erase("unloading_stiffness_ratio");
  if (s.contact.surface_energy == 0.0) j["contact"].erase("surface_energy");
  if (s.contact.stiffness_exponent == 1.0) j["contact"].erase("stiffness_exponent");
  return j;
}

json read_case_json(const std::string& path) {
  // Size, nesting depth and duplicate keys checked while reading (identify/json_document.hpp).
  return identify::read_json_file(path, "case file");
}

const std::vector<std::string>& parameter_names() {
  static const std::vector<std::string> names{"normk", "sheark", "ndamp", "tdamp", "frics", "fricd",
                                              "dc", "fricr", "wall_frics", "wall_fricd",
                                              "wall_damp", "wall_sfp",
                                              // effects library (issue #6), off by default
                                              "unloading_stiffness_ratio", "surface_energy",
                                              "stiffness_exponent", "radius_spread"};
  return names;
}

std::string parameter_path(const std::string& name) {
  for (const std::string& n : parameter_names()) {
    if (n != name) continue;
    if (name.rfind("wall_", 0) == 0) return "wall_contact." + name.substr(5);
    if (name == "radius_spread") return "particle.radius_spread";
    return "contact." + name;
  }
  return "";
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
