#pragma once
// Internal helpers of mesh walls (wall.cpp, wall_mesh.cpp): the placement of the mesh frame.
#include "demfit/dem_core/wall.hpp"

namespace demfit::dem_core {

/// World point [m] -> mesh-frame point (exact for the identity placement).
inline Vec3 mesh_frame_point(const MeshGeometry& g, const Vec3& world) {
  const Vec3 d = world - g.origin;
  return {dot(d, g.axis_x), dot(d, g.axis_y), dot(d, g.axis_z)};
}

/// Mesh-frame direction -> world direction (exact for the identity placement).
inline Vec3 world_direction(const MeshGeometry& g, const Vec3& v) {
  return v.x * g.axis_x + v.y * g.axis_y + v.z * g.axis_z;
}

/// Gram–Schmidt on axis_x, axis_y; axis_z = axis_x x axis_y (right-handed).
void orthonormalize(MeshGeometry& g);

/// Throws std::runtime_error naming the field: missing mesh, non-finite placement, axes not
/// perpendicular or left-handed, max_contacts outside 1..8. Orthonormalises the axes.
void validate_mesh_geometry(MeshGeometry& g);

}  // namespace demfit::dem_core
