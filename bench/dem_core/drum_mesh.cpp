// Drum mesh for LIGGGHTS' fix mesh/surface (the library's dem_core::drum_mesh_triangles).
#include "drum_mesh.hpp"

namespace demfit::bench {

std::size_t write_drum_stl(std::ostream& out, const DrumMeshRequest& request) {
  const auto triangles = dem_core::drum_mesh_triangles(request);
  dem_core::write_ascii_stl(out, triangles, "drum");
  return triangles.size();
}

}  // namespace demfit::bench
