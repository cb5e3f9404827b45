#pragma once
// ASCII STL of a closed drum for LIGGGHTS' fix mesh/surface: the library's drum mesh
// (demfit/dem_core/drum_mesh.hpp: shell polygon and two capped ends, normals into the drum).
#include <cstddef>
#include <ostream>

#include "demfit/dem_core/drum_mesh.hpp"

namespace demfit::bench {

using DrumMeshRequest = dem_core::DrumMeshRequest;

/// Writes the mesh; returns the triangle count.
std::size_t write_drum_stl(std::ostream& out, const DrumMeshRequest& request);

}  // namespace demfit::bench
