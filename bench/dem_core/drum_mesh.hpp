#pragma once
// ASCII STL of a closed drum: cylindrical shell (polygon of `segments` sides, split into axial
// rings) and two flat end caps triangulated as concentric rings that share the shell's rim
// vertices. Vertices lie at radius 2R/(1 + cos(pi/segments)), so vertices and chord midpoints
// straddle the true radius R equally (largest deviation R (1 - cos(pi/n))/2, ~1 um at R = 50 mm,
// n = 360). Facet normals point into the drum.
#include <cstddef>
#include <ostream>

namespace demfit::bench {

struct DrumMeshRequest {
  double radius = 0.05;  ///< [m]
  double depth = 0.02;   ///< [m], caps at z = 0 and z = depth, axis = z through the origin
  double phase = 0.0;    ///< [rad] rotation of the whole mesh about z (the drum's current angle)
  int segments = 360;
  int shell_rings = 4;
  int cap_rings = 20;  ///< segments must be a multiple of cap_rings
};

/// Writes the mesh; returns the triangle count.
std::size_t write_drum_stl(std::ostream& out, const DrumMeshRequest& request);

}  // namespace demfit::bench
