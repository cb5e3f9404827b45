// Mesh walls: placement, validation and the sphere contacts in world coordinates
// (wall.hpp MeshGeometry, triangle_mesh.hpp for the contact rule).
#include "wall_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "validation.hpp"

namespace demfit::dem_core {
namespace {
constexpr int kMostMeshContacts = 8;

Vec3 unit(const Vec3& v) {
  const double n = norm(v);
  return {v.x / n, v.y / n, v.z / n};  // divided: exact for axis-aligned axes
}
}  // namespace

void orthonormalize(MeshGeometry& g) {
  g.axis_x = unit(g.axis_x);
  g.axis_y = unit(g.axis_y - dot(g.axis_y, g.axis_x) * g.axis_x);
  g.axis_z = cross(g.axis_x, g.axis_y);
}

void validate_mesh_geometry(MeshGeometry& g) {
  if (!g.mesh) throw std::runtime_error("mesh.mesh: no triangle mesh given; build one from read_stl(...) triangles");
  require_finite("mesh.origin [m]", g.origin);
  const Vec3 x = require_direction("mesh.axis_x", g.axis_x);
  const Vec3 y = require_direction("mesh.axis_y", g.axis_y);
  const Vec3 z = require_direction("mesh.axis_z", g.axis_z);
  if (std::abs(dot(x, y)) > 1e-9 || std::abs(dot(x, z)) > 1e-9 || std::abs(dot(y, z)) > 1e-9)
    throw std::runtime_error("mesh.axis_x/axis_y/axis_z: must be mutually perpendicular (a rigid placement)");
  if (dot(cross(x, y), z) < 0.0)
    throw std::runtime_error("mesh.axis_z: must equal axis_x x axis_y (right-handed); a mirrored mesh is not rigid motion");
  if (g.max_contacts < 1 || g.max_contacts > kMostMeshContacts)
    fail("mesh.max_contacts", g.max_contacts, "must lie in 1..8 (3 covers a sphere in an inside box corner)");
  orthonormalize(g);
}

int mesh_wall_contacts(const MeshGeometry& g, const Vec3& center, double radius, WallProximity* out, int capacity) {
  MeshContact found[kMostMeshContacts];
  const int n = g.mesh->contacts(mesh_frame_point(g, center), radius, found, std::min(capacity, kMostMeshContacts));
  for (int k = 0; k < n; ++k) out[k] = {true, world_direction(g, found[k].normal), found[k].overlap};
  return n;
}

int mesh_wall_contacts(const MeshGeometry& g, const Vec3& center, double radius,
                       std::span<const std::uint32_t> candidates, WallProximity* out, int capacity) {
  MeshContact found[kMostMeshContacts];
  const int n = g.mesh->contacts(mesh_frame_point(g, center), radius, candidates, found,
                                 std::min(capacity, kMostMeshContacts));
  for (int k = 0; k < n; ++k) out[k] = {true, world_direction(g, found[k].normal), found[k].overlap};
  return n;
}

void mesh_wall_candidates(const MeshGeometry& g, const Vec3& center, double reach, std::vector<std::uint32_t>& found) {
  g.mesh->triangles_within(mesh_frame_point(g, center), reach, found);
}

double wall_sweep_radius(const Wall& wall) {
  const auto* g = std::get_if<MeshGeometry>(&wall.geometry);
  const auto* m = std::get_if<RotatingMotion>(&wall.motion);
  if (g == nullptr || m == nullptr || m->angular_velocity == 0.0) return 0.0;
  // The axis in the mesh frame; the farthest vertex bounds every surface point (distance from a
  // line is convex). O(vertices) per step: ~10 us for 10^4 vertices.
  const Vec3 point = mesh_frame_point(*g, m->axis_point);
  const Vec3 direction{dot(m->axis_direction, g->axis_x), dot(m->axis_direction, g->axis_y),
                       dot(m->axis_direction, g->axis_z)};
  double reach2 = 0.0;
  for (const Vec3& v : g->mesh->vertices()) reach2 = std::max(reach2, norm2(cross(v - point, direction)));
  return std::sqrt(reach2);
}

int wall_contact_slots(const WallGeometry& geometry) {
  const auto* g = std::get_if<MeshGeometry>(&geometry);
  return g == nullptr ? 1 : g->max_contacts;
}

}  // namespace demfit::dem_core
