// The "mesh_container" section of a case file (docs/mesh-container.md): STL parts with their unit
// and motion, the fill box and particles, the run's duration and output interval, and the outputs
// the user selects. STL files are read here, so a missing or malformed file is an error before
// any output exists.
#include <algorithm>
#include <cstring>
#include <cmath>
#include <limits>
#include <set>
#include <stdexcept>

#include "demfit/cases/json_fields.hpp"
#include "mesh_container_case.hpp"

namespace demfit::cases::detail {
namespace {

using nlohmann::json;

constexpr long long kMaxParticles = 200000;  // a pour the kernel runs in minutes, not days
constexpr long long kMaxBins = 1000;

struct UnitRow {
  const char* name;
  double metres;
};
constexpr UnitRow kStlUnits[] = {{"m", 1.0}, {"cm", 1e-2}, {"mm", 1e-3}, {"um", 1e-6}, {"in", 0.0254}};
constexpr const char* kUnitList = "\"m\", \"cm\", \"mm\", \"um\" or \"in\"";

// `count` finite numbers in a JSON array (a point or a direction) [SI].
template <std::size_t N>
std::array<double, N> read_numbers(const json& j, const std::string& path, const char* key, const char* example) {
  const std::string name = join_path(path, key);
  if (!j.contains(key))
    throw std::runtime_error("'" + name + "' is missing: give " + std::to_string(N) + " numbers, e.g. " + example);
  const json& a = j.at(key);
  if (!a.is_array() || a.size() != N)
    throw std::runtime_error("'" + name + "' must be an array of " + std::to_string(N) + " numbers, e.g. " + example);
  std::array<double, N> out{};
  for (std::size_t k = 0; k < N; ++k) {
    if (!a[k].is_number() || !std::isfinite(a[k].get<double>()))
      throw std::runtime_error("'" + name + "' must hold finite numbers, e.g. " + example);
    out[k] = a[k].get<double>();
  }
  return out;
}

double required_number(const json& j, const std::string& path, const char* key, Sign sign, const char* what) {
  if (!j.contains(key)) throw std::runtime_error("'" + join_path(path, key) + "' is missing: give " + what);
  return read_number(j, path, key, 0.0, sign);
}

// FNV-1a over the triangles' coordinates (bit patterns): the geometry, not the file's name.
std::uint64_t triangles_hash(const std::vector<dem_core::Triangle>& triangles) {
  std::uint64_t h = 1469598103934665603ull;
  for (const dem_core::Triangle& t : triangles)
    for (const dem_core::Vec3& v : t)
      for (double c : {v.x, v.y, v.z}) {
        std::uint64_t bits = 0;
        static_assert(sizeof bits == sizeof c);
        std::memcpy(&bits, &c, sizeof c);
        for (int b = 0; b < 8; ++b) h = (h ^ ((bits >> (8 * b)) & 0xffu)) * 1099511628211ull;
      }
  return h;
}

void parse_motion(const json& m, const std::string& path, MeshPartSpec& part) {
  require_known_keys(m, path, {"type", "axis_point", "axis_direction", "rpm", "velocity", "start_time"});
  const std::string type = read_string(m, path, "type", "");
  part.start_time = read_number(m, path, "start_time", 0.0, Sign::non_negative);
  if (type == "rotation") {
    part.motion = MeshMotion::rotation;
    if (!m.contains("axis_direction"))
      throw std::runtime_error("'" + path +
                               ".axis_direction' is missing: a rotating part needs its axis, e.g. [0, 0, 1] "
                               "(with axis_point [m] and rpm)");
    part.axis_direction = read_numbers<3>(m, path, "axis_direction", "[0, 0, 1]");
    part.axis_point = read_numbers<3>(m, path, "axis_point", "[0, 0, 0] (a point of the axis, metres)");
    part.rpm = required_number(m, path, "rpm", Sign::any, "the rotation speed in rev/min (positive: right-handed)");
    if (std::hypot(part.axis_direction[0], part.axis_direction[1], part.axis_direction[2]) == 0.0)
      throw std::runtime_error("'" + path + ".axis_direction' is the zero vector: give the axis, e.g. [0, 0, 1]");
    if (m.contains("velocity"))
      throw std::runtime_error("'" + path +
                               ".velocity' belongs to a translation: remove it or set type \"translation\"");
  } else if (type == "translation") {
    part.motion = MeshMotion::translation;
    part.velocity = read_numbers<3>(m, path, "velocity", "[0, 0, -0.01] (m/s)");
    for (const char* k : {"axis_point", "axis_direction", "rpm"})
      if (m.contains(k))
        throw std::runtime_error("'" + path + "." + k + "' belongs to a rotation: remove it or set type \"rotation\"");
  } else {
    throw std::runtime_error("'" + path + ".type' must be \"rotation\" or \"translation\" (got \"" + type +
                             "\"); leave \"motion\" out for a fixed part");
  }
}

MeshPartSpec parse_part(const json& j, const std::string& path, const std::filesystem::path& base_dir) {
  require_known_keys(j, path, {"name", "stl", "unit", "motion"});
  MeshPartSpec part;
  if (!j.contains("stl"))
    throw std::runtime_error("'" + path + ".stl' is missing: give the STL file (relative to the case file)");
  part.stl = read_string(j, path, "stl", "");
  part.name = read_string(j, path, "name", std::filesystem::path(part.stl).stem().string());
  if (!j.contains("unit"))
    throw std::runtime_error("'" + path + ".unit' is missing: STL files carry no unit; state the file's length unit, " +
                             kUnitList);
  part.unit = read_string(j, path, "unit", "");
  const double metres = metres_per_stl_unit(part.unit);
  if (metres == 0.0)
    throw std::runtime_error("'" + path + ".unit' must be " + kUnitList + " (got \"" + part.unit + "\")");
  if (j.contains("motion")) parse_motion(child_object(j, path, "motion"), path + ".motion", part);
  std::filesystem::path file(part.stl);
  if (file.is_relative()) file = base_dir / file;
  std::error_code error;
  if (!std::filesystem::is_regular_file(file, error))
    throw std::runtime_error("'" + path + ".stl' = \"" + part.stl + "\": no such file (looked for " + file.string() +
                             "): give the path relative to the case file");
  try {
    auto triangles = dem_core::read_stl(file, {metres, 5'000'000});
    part.content_hash = triangles_hash(triangles);
    part.triangles = std::make_shared<const std::vector<dem_core::Triangle>>(std::move(triangles));
  } catch (const std::exception& e) { throw std::runtime_error("'" + path + ".stl': " + e.what()); }
  if (part.triangles->empty())
    throw std::runtime_error("'" + path + ".stl' holds no triangle: export the surface again");
  return part;
}

// Lower and upper corner [m] of every part's triangles (at their place at time 0).
std::array<std::array<double, 3>, 2> mesh_bounds(const std::vector<MeshPartSpec>& parts) {
  constexpr double inf = std::numeric_limits<double>::infinity();
  std::array<std::array<double, 3>, 2> b{{{inf, inf, inf}, {-inf, -inf, -inf}}};
  for (const MeshPartSpec& p : parts)
    for (const dem_core::Triangle& t : *p.triangles)
      for (const dem_core::Vec3& v : t) {
        const double c[3] = {v.x, v.y, v.z};
        for (int k = 0; k < 3; ++k) {
          b[0][k] = std::min(b[0][k], c[k]);
          b[1][k] = std::max(b[1][k], c[k]);
        }
      }
  return b;
}

// The fill box lies over the geometry: inside the meshes' x and y range, its bottom not below
// their lowest point (particles poured from above the meshes are the usual case, so its top may
// be higher than theirs).
void check_fill_box(const MeshContainerSpec& s) {
  const char* p = "mesh_container.fill_box";
  const auto bounds = mesh_bounds(s.meshes);
  const char* axis = "xyz";
  for (int k = 0; k < 3; ++k)
    if (!(s.fill_lower[k] < s.fill_upper[k]))
      throw std::runtime_error(std::string("'") + p + "': lower " + axis[k] + " must be below upper " + axis[k] +
                               ": give lower and upper corners [m]");
  const double slack = 1e-9;
  for (int k = 0; k < 2; ++k)
    if (s.fill_lower[k] < bounds[0][k] - slack || s.fill_upper[k] > bounds[1][k] + slack)
      throw std::runtime_error(std::string("'") + p + "' " + axis[k] + " range [" + std::to_string(s.fill_lower[k]) +
                               ", " + std::to_string(s.fill_upper[k]) + "] m lies outside the meshes' " + axis[k] +
                               " range [" + std::to_string(bounds[0][k]) + ", " + std::to_string(bounds[1][k]) +
                               "] m: place the box over the geometry (STL coordinates times their unit)");
  if (s.fill_lower[2] < bounds[0][2] - slack)
    throw std::runtime_error(std::string("'") + p + "' bottom z = " + std::to_string(s.fill_lower[2]) +
                             " m lies below the meshes' lowest point z = " + std::to_string(bounds[0][2]) +
                             " m: raise the box into or above the geometry");
}

void parse_fill_box(const json& j, MeshContainerSpec& s) {
  const char* p = "mesh_container.fill_box";
  if (!j.is_object() || j.empty())
    throw std::runtime_error(std::string("'") + p +
                             "' is missing: give {\"lower\": [x, y, z], \"upper\": [x, y, z]} in metres");
  require_known_keys(j, p, {"lower", "upper"});
  s.fill_lower = read_numbers<3>(j, p, "lower", "[-0.01, -0.01, 0.02] (m)");
  s.fill_upper = read_numbers<3>(j, p, "upper", "[0.01, 0.01, 0.05] (m)");
}

HeapAngleSpec parse_heap(const json& j) {
  const std::string p = "mesh_container.outputs.heap_angle";
  require_known_keys(j, p, {"center", "base_z", "r_min", "r_max", "bins", "rest_speed"});
  HeapAngleSpec h;
  h.enabled = true;
  h.center = read_numbers<2>(j, p, "center", "[0, 0] (heap axis x, y in metres)");
  h.base_z = required_number(j, p, "base_z", Sign::any, "the pedestal top height z [m]");
  for (const char* k : {"r_min", "r_max"})
    if (j.contains(k) && j.at(k).is_number() && j.at(k).get<double>() < 0.0)
      throw std::runtime_error(
          "'" + p + "." + k + "' = " + j.at(k).dump() +
          " is a negative radius: give the radial window as distances from the heap axis >= 0 [m]");
  h.r_min = required_number(j, p, "r_min", Sign::non_negative, "the inner radius of the fit window [m]");
  h.r_max = required_number(j, p, "r_max", Sign::positive, "the outer radius of the fit window [m]");
  if (!(h.r_max > h.r_min))
    throw std::runtime_error("'" + p + ".r_max' must exceed r_min: give the window [r_min, r_max] in metres");
  h.bins = read_integer(j, p, "bins", h.bins, 2);
  if (h.bins > kMaxBins) throw std::runtime_error("'" + p + ".bins' must be at most " + std::to_string(kMaxBins));
  h.rest_speed = read_number(j, p, "rest_speed", h.rest_speed, Sign::positive);
  return h;
}

void parse_outputs(const json& j, MeshContainerSpec& s) {
  const char* p = "mesh_container.outputs";
  require_known_keys(j, p, {"heap_angle", "discharge_mass", "moving_part_torque"});
  if (j.empty())
    throw std::runtime_error(std::string("'") + p +
                             "' selects no output: give one or more of heap_angle, discharge_mass, moving_part_torque");
  if (j.contains("heap_angle")) s.heap_angle = parse_heap(child_object(j, p, "heap_angle"));
  if (j.contains("discharge_mass")) {
    const std::string q = "mesh_container.outputs.discharge_mass";
    const json& d = child_object(j, p, "discharge_mass");
    require_known_keys(d, q, {"plane_z", "orifice_diameter"});
    s.discharge_mass.enabled = true;
    s.discharge_mass.plane_z =
        required_number(d, q, "plane_z", Sign::any, "the height z [m] of the counting plane below the orifice");
    s.discharge_mass.orifice_diameter = read_number(d, q, "orifice_diameter", 0.0, Sign::non_negative);
  }
  if (j.contains("moving_part_torque")) {
    const std::string q = "mesh_container.outputs.moving_part_torque";
    const json& t = child_object(j, p, "moving_part_torque");
    require_known_keys(t, q, {"mesh"});
    s.moving_part_torque.enabled = true;
    s.moving_part_torque.mesh = read_string(t, q, "mesh", "");
    const auto part = std::find_if(s.meshes.begin(), s.meshes.end(),
                                   [&](const MeshPartSpec& m) { return m.name == s.moving_part_torque.mesh; });
    if (part == s.meshes.end())
      throw std::runtime_error("'" + q + ".mesh' = \"" + s.moving_part_torque.mesh +
                               "\" names no part: give the name of a rotating part of mesh_container.meshes");
    if (part->motion != MeshMotion::rotation)
      throw std::runtime_error("'" + q + ".mesh' = \"" + part->name +
                               "\" does not rotate: the torque is about a rotation axis; give the part a \"motion\" of "
                               "type \"rotation\"");
  }
}

MeshContainerSpec parse_section(const json& j, MeshContainerSpec s, const std::filesystem::path& base_dir) {
  const char* p = "mesh_container";
  require_known_keys(j, p,
                     {"meshes", "fill_box", "particle_count", "fill_seed", "size_distribution", "duration",
                      "output_interval", "outputs"});
  if (!j.contains("meshes") || !j.at("meshes").is_array() || j.at("meshes").empty())
    throw std::runtime_error(
        "'mesh_container.meshes' must be a non-empty array of {\"stl\": file, \"unit\": \"mm\", ...}");
  std::set<std::string> names;
  for (std::size_t i = 0; i < j.at("meshes").size(); ++i) {
    const std::string path = "mesh_container.meshes[" + std::to_string(i) + "]";
    s.meshes.push_back(parse_part(j.at("meshes")[i], path, base_dir));
    if (!names.insert(s.meshes.back().name).second)
      throw std::runtime_error("'" + path + ".name' = \"" + s.meshes.back().name +
                               "\" is used twice: give every part its own name");
  }
  parse_fill_box(child_object(j, p, "fill_box"), s);
  check_fill_box(s);
  s.particle_count = read_integer(j, p, "particle_count", s.particle_count, 1);
  if (s.particle_count > kMaxParticles)
    throw std::runtime_error("'mesh_container.particle_count' must be at most " + std::to_string(kMaxParticles));
  s.fill_seed = read_integer(j, p, "fill_seed", s.fill_seed, 0);
  s.duration = read_number(j, p, "duration", s.duration, Sign::positive);
  s.output_interval = read_number(j, p, "output_interval", s.output_interval, Sign::positive);
  if (s.output_interval > s.duration)
    throw std::runtime_error(
        "'mesh_container.output_interval' must not exceed 'mesh_container.duration': give e.g. 0.01 s");
  if (s.duration / s.output_interval > 1e6)
    throw std::runtime_error("'mesh_container.output_interval' gives more than 1e6 samples: raise it");
  if (j.contains("size_distribution"))
    s.size_distribution =
        parse_size_distribution(child_object(j, p, "size_distribution"), "mesh_container.size_distribution", base_dir);
  if (!j.contains("outputs"))
    throw std::runtime_error(
        "'mesh_container.outputs' is missing: select one or more of heap_angle, discharge_mass, moving_part_torque");
  parse_outputs(child_object(j, p, "outputs"), s);
  return s;
}

json numbers(const auto& a) { return json(std::vector<double>(a.begin(), a.end())); }

}  // namespace

double metres_per_stl_unit(std::string_view unit) {
  for (const UnitRow& row : kStlUnits)
    if (unit == row.name) return row.metres;
  return 0.0;
}

void parse_mesh_container_section(const json& document, CaseSpec& spec, const std::filesystem::path& base_dir) {
  if (!document.contains("mesh_container"))
    throw std::runtime_error(
        "'mesh_container' is missing: a mesh_container case needs its section (docs/mesh-container.md)");
  spec.mesh_container = parse_section(child_object(document, "", "mesh_container"), spec.mesh_container, base_dir);
  if (!spec.mesh_container.size_distribution.enabled()) return;
  if (child_object(document, "", "particle").contains("radius"))
    throw std::runtime_error(
        "'particle.radius' cannot be given with 'mesh_container.size_distribution': the distribution sets the sizes");
  if (spec.material.radius_spread != 0.0)
    throw std::runtime_error("'particle.radius_spread' cannot be combined with 'mesh_container.size_distribution'");
  spec.material.radius = 0.5 * spec.mesh_container.size_distribution.min_diameter();  // smallest size (time step)
}

json mesh_container_section_json(const MeshContainerSpec& s) {
  json meshes = json::array();
  for (const MeshPartSpec& m : s.meshes) {
    json part = {{"name", m.name}, {"stl", m.stl}, {"unit", m.unit}};
    switch (m.motion) {
      case MeshMotion::fixed:
        break;
      case MeshMotion::rotation:
        part["motion"] = {{"type", "rotation"},
                          {"axis_point", numbers(m.axis_point)},
                          {"axis_direction", numbers(m.axis_direction)},
                          {"rpm", m.rpm},
                          {"start_time", m.start_time}};
        break;
      case MeshMotion::translation:
        part["motion"] = {{"type", "translation"}, {"velocity", numbers(m.velocity)}, {"start_time", m.start_time}};
        break;
    }
    meshes.push_back(part);
  }
  json j = {{"meshes", meshes},
            {"fill_box", {{"lower", numbers(s.fill_lower)}, {"upper", numbers(s.fill_upper)}}},
            {"particle_count", s.particle_count},
            {"fill_seed", s.fill_seed},
            {"duration", s.duration},
            {"output_interval", s.output_interval}};
  if (s.size_distribution.enabled()) j["size_distribution"] = to_json(s.size_distribution);
  json outputs = json::object();
  if (s.heap_angle.enabled) {
    const HeapAngleSpec& h = s.heap_angle;
    outputs["heap_angle"] = {
        {"center", numbers(h.center)}, {"base_z", h.base_z}, {"r_min", h.r_min}, {"r_max", h.r_max}, {"bins", h.bins},
        {"rest_speed", h.rest_speed}};
  }
  if (s.discharge_mass.enabled)
    outputs["discharge_mass"] = {{"plane_z", s.discharge_mass.plane_z},
                                 {"orifice_diameter", s.discharge_mass.orifice_diameter}};
  if (s.moving_part_torque.enabled) outputs["moving_part_torque"] = {{"mesh", s.moving_part_torque.mesh}};
  j["outputs"] = outputs;
  return j;
}

}  // namespace demfit::cases::detail
