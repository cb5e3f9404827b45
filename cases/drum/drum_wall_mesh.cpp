// "drum.wall_mesh" (drum_wall_mesh.hpp): parsing, the mesh of a case's drum.
#include "demfit/cases/drum_wall_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>

#include "demfit/cases/json_fields.hpp"
#include "demfit/dem_core/drum_mesh.hpp"

namespace demfit::cases {
namespace {

using nlohmann::json;
constexpr const char* kPath = "drum.wall_mesh";

std::string field(const char* key) { return std::string("'") + kPath + "." + key + "'"; }

double metres_per_unit(const std::string& unit) {
  if (unit == "m") return 1.0;
  if (unit == "cm") return 1e-2;
  if (unit == "mm") return 1e-3;
  throw std::runtime_error(field("unit") + " must be \"m\", \"cm\" or \"mm\" (got \"" + unit + "\")");
}

// FNV-1a over the coordinates' bytes: a changed file is another result (result cache key).
std::uint64_t triangles_hash(const std::vector<dem_core::Triangle>& triangles) {
  std::uint64_t h = 1469598103934665603ull;
  for (const dem_core::Triangle& t : triangles)
    for (const dem_core::Vec3& v : t)
      for (double c : {v.x, v.y, v.z}) {
        unsigned char bytes[sizeof(double)];
        std::memcpy(bytes, &c, sizeof c);
        for (unsigned char b : bytes) h = (h ^ b) * 1099511628211ull;
      }
  return h;
}

// The user's drum must be the case's drum in the case frame: the fill is settled in the
// analytic drum of drum.diameter x drum.length, axis z, caps at z = 0 and z = length. Tolerance
// 5 % of the radius (a polygon of 8 sides with straddling chords reaches 1.04 R) and 2 % of the length.
void check_stl_fits_drum(const std::vector<dem_core::Triangle>& triangles, double diameter, double length,
                         const std::string& file) {
  const double radius = 0.5 * diameter;
  double r_max = 0.0, z_min = INFINITY, z_max = -INFINITY;
  for (const dem_core::Triangle& t : triangles)
    for (const dem_core::Vec3& v : t) {
      r_max = std::max(r_max, std::hypot(v.x, v.y));
      z_min = std::min(z_min, v.z);
      z_max = std::max(z_max, v.z);
    }
  const auto mm = [](double m) { return std::to_string(m * 1e3) + " mm"; };
  if (std::fabs(r_max - radius) > 0.05 * radius)
    throw std::runtime_error(field("stl") + " '" + file + "': largest distance from the z axis " + mm(r_max) +
                             ", the drum radius is " + mm(radius) +
                             " (within 5 %): check 'unit' and that the drum axis is z through the origin");
  if (std::fabs(z_min) > 0.02 * length || std::fabs(z_max - length) > 0.02 * length)
    throw std::runtime_error(field("stl") + " '" + file + "': spans z = " + mm(z_min) + " to " + mm(z_max) +
                             ", the drum's end caps are at z = 0 and z = drum.length = " + mm(length) +
                             " (within 2 %): move the mesh or check 'unit'");
}

}  // namespace

DrumWallMeshSpec parse_drum_wall_mesh(const json& j, double diameter, double length,
                                      const std::filesystem::path& base_dir) {
  require_known_keys(j, kPath, {"segments", "shell_rings", "cap_rings", "stl", "unit"});
  DrumWallMeshSpec s;
  if (!j.contains("stl")) {
    if (j.contains("unit"))
      throw std::runtime_error(field("unit") + " applies to an STL file only: add " + field("stl") + " or remove it");
    s.source = DrumWallMeshSpec::Source::generated;
    s.segments = read_integer(j, kPath, "segments", s.segments, 8);
    s.shell_rings = read_integer(j, kPath, "shell_rings", s.shell_rings, 1);
    s.cap_rings = read_integer(j, kPath, "cap_rings", s.cap_rings, 1);
    // Bounded as an STL file is (dem_core StlReadOptions::max_triangles): no input allocates gigabytes.
    const long long triangles = 2 * s.segments * (s.shell_rings + s.cap_rings);
    if (s.segments > 1'000'000 || s.shell_rings > 1'000'000 || s.cap_rings > 1'000'000 ||
        triangles > static_cast<long long>(dem_core::StlReadOptions{}.max_triangles))
      throw std::runtime_error("'" + std::string(kPath) + "': 2 segments (shell_rings + cap_rings) = " +
                               std::to_string(triangles) + " triangles, at most " +
                               std::to_string(dem_core::StlReadOptions{}.max_triangles) + ": use fewer");
    if (s.segments % s.cap_rings != 0)
      throw std::runtime_error(field("segments") + " (" + std::to_string(s.segments) +
                               ") must be a multiple of " + field("cap_rings") + " (" +
                               std::to_string(s.cap_rings) + ")");
    return s;
  }
  for (const char* k : {"segments", "shell_rings", "cap_rings"})
    if (j.contains(k))
      throw std::runtime_error(field(k) + " applies to a generated mesh only: remove it or remove " + field("stl"));
  s.source = DrumWallMeshSpec::Source::stl;
  s.stl = read_string(j, kPath, "stl", "");
  if (!j.contains("unit"))
    throw std::runtime_error(field("unit") + " is missing: an STL file has no unit, give \"m\", \"cm\" or \"mm\"");
  s.unit = read_string(j, kPath, "unit", "");
  const double to_m = metres_per_unit(s.unit);
  std::filesystem::path file(s.stl);
  if (file.is_relative()) file = base_dir / file;
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec))
    throw std::runtime_error(field("stl") + ": no file '" + file.string() + "': give the drum's STL file");
  try {
    s.stl_triangles = dem_core::read_stl(file, {to_m});
  } catch (const std::exception& e) {
    throw std::runtime_error(field("stl") + ": " + e.what());
  }
  check_stl_fits_drum(s.stl_triangles, diameter, length, s.stl);
  s.stl_hash = triangles_hash(s.stl_triangles);
  return s;
}

json to_json(const DrumWallMeshSpec& s) {
  if (s.source == DrumWallMeshSpec::Source::stl) return {{"stl", s.stl}, {"unit", s.unit}};
  return {{"segments", s.segments}, {"shell_rings", s.shell_rings}, {"cap_rings", s.cap_rings}};
}

std::shared_ptr<const dem_core::TriangleMesh> drum_wall_mesh(const DrumWallMeshSpec& s, double diameter,
                                                            double length) {
  switch (s.source) {
    case DrumWallMeshSpec::Source::none:
      return nullptr;
    case DrumWallMeshSpec::Source::stl:
      return std::make_shared<const dem_core::TriangleMesh>(s.stl_triangles);
    case DrumWallMeshSpec::Source::generated:
      break;
  }
  const dem_core::DrumMeshRequest request{0.5 * diameter, length, 0.0, static_cast<int>(s.segments),
                                          static_cast<int>(s.shell_rings), static_cast<int>(s.cap_rings)};
  return std::make_shared<const dem_core::TriangleMesh>(dem_core::drum_mesh_triangles(request));
}

}  // namespace demfit::cases
