#pragma once
// "drum.wall_mesh": the drum's shell and both end caps as ONE rotating triangle-mesh wall
// (dem_core MeshGeometry) instead of the analytic cylinder and two disks. Either a generated
// drum mesh (dem_core/drum_mesh.hpp; "segments", "shell_rings", "cap_rings") or the user's STL
// ("stl" file, "unit" of its coordinates: "m", "cm" or "mm"), in the case frame: drum axis = z
// through the origin, end caps at z = 0 and z = drum.length. Off (analytic walls) when absent.
// The mesh is used in the rotation stage only: the fill is packed and settled in the analytic
// drum, so the cached fill is the same with or without a mesh (drum_powder.cpp fill_key).
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "demfit/dem_core/stl_mesh.hpp"
#include "demfit/dem_core/triangle_mesh.hpp"

namespace demfit::cases {

struct DrumWallMeshSpec {
  enum class Source { none, generated, stl };
  Source source = Source::none;
  // Generated mesh (dem_core::DrumMeshRequest): shell polygon sides, axial shell rings,
  // concentric cap rings (segments a multiple of cap_rings).
  long long segments = 360;
  long long shell_rings = 4;
  long long cap_rings = 20;
  // STL: the file as written in the case (relative paths resolve against the case file's
  // folder) and the unit of its coordinates; read and checked at parse time.
  std::string stl;
  std::string unit;
  std::vector<dem_core::Triangle> stl_triangles;  // [m], resolved at parse time
  std::uint64_t stl_hash = 0;                      // FNV-1a of the triangles (result cache key)

  bool enabled() const { return source != Source::none; }
};

// Parses drum.wall_mesh of a drum of `diameter` and `length` [m]; errors name the field.
DrumWallMeshSpec parse_drum_wall_mesh(const nlohmann::json& j, double diameter, double length,
                                      const std::filesystem::path& base_dir);
nlohmann::json to_json(const DrumWallMeshSpec& spec);
// The mesh of the drum (diameter, length [m]) at rotation angle 0, in the case frame.
std::shared_ptr<const dem_core::TriangleMesh> drum_wall_mesh(const DrumWallMeshSpec& spec, double diameter,
                                                            double length);

}  // namespace demfit::cases
