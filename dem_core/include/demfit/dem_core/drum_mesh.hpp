#pragma once
// Triangle mesh of a closed rotary drum, for a mesh wall (wall.hpp MeshGeometry) or an STL file
// (LIGGGHTS' fix mesh/surface). Frame: axis = z through the origin, end caps at z = 0 and
// z = depth. The cylindrical shell is a polygon of `segments` sides split into `shell_rings`
// axial rings; each end cap is triangulated as `cap_rings` concentric rings (ring k holds
// k * segments / cap_rings points, the centre one point) that share the shell's rim vertices,
// so the surface is closed. Vertices lie at radius 2R/(1 + cos(pi/segments)): vertices and
// chord midpoints straddle the true radius R equally, largest deviation R (1 - cos(pi/n))/2
// (~1 um at R = 50 mm, n = 360). Each triangle's winding (right-hand rule) gives a normal
// pointing into the drum.
#include <ostream>
#include <string>
#include <vector>

#include "demfit/dem_core/stl_mesh.hpp"

namespace demfit::dem_core {

struct DrumMeshRequest {
  double radius = 0.05;  ///< inner radius R [m]
  double depth = 0.02;   ///< axial length between the caps [m]
  double phase = 0.0;    ///< [rad] rotation of the whole mesh about z (the drum's current angle)
  int segments = 360;    ///< sides of the shell polygon, >= 8
  int shell_rings = 4;   ///< axial rings of the shell, >= 1
  int cap_rings = 20;    ///< concentric rings of each cap, >= 1; segments must be a multiple of it
};

/// Why the request cannot be meshed (empty when it can): names the field and the fix.
std::string drum_mesh_request_problem(const DrumMeshRequest& request);

/// The drum's triangles [m]: 2 segments shell_rings on the shell, then segments cap_rings on each
/// cap (z = 0 first). Throws std::runtime_error (the problem above) for an invalid request.
std::vector<Triangle> drum_mesh_triangles(const DrumMeshRequest& request);

/// ASCII STL ("solid <name>") of the triangles, facet normals from the winding, 17 digits.
void write_ascii_stl(std::ostream& out, const std::vector<Triangle>& triangles, const std::string& name);

}  // namespace demfit::dem_core
