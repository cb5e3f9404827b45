#pragma once
// A rigid triangle surface for mesh walls (stl_mesh.hpp reads one), in its own frame, with a
// uniform grid of cells over its bounding box so that a sphere tests only the triangles
// registered in the cells its bounding box covers: cost follows the triangles near a particle,
// not the triangle count.
//
// Contact of a sphere (centre c, radius r) with the surface. Each triangle closer than r gives
// its closest point q (Ericson, Real-Time Collision Detection, 5.1.5: the Voronoi region of the
// face interior, of an edge or of a vertex); contact is two-sided (the surface is a thin shell:
// orientation and closedness do not matter), overlap r - |c - q|, normal (q - c)/|c - q|. For a
// face interior the distance is the signed plane distance dot(c - a, n) of an analytic plane
// (same operations as PlaneGeometry), so a flat face gives the plane's forces to the bit.
//
// Where triangles meet, a sphere must feel one contact, not one per triangle. Rule:
//  1. A face-interior point always counts.
//  2. An edge or vertex point q_i is dropped when a triangle CONTAINING that edge or vertex has
//     its own closest point elsewhere (farther than the coincidence tolerance) and not farther
//     from c. Reason: q_i is then not the closest point of the surface near the feature (the
//     sphere lies over a neighbouring face or edge, which carries the contact), e.g. the shared
//     edge of a flat floor when the centre lies over one of its triangles, or a box corner when
//     the centre lies beside a box edge. q_i survives exactly when it is the closest point of
//     every triangle around its feature: a convex edge or corner, or a border edge.
//  3. Points closer together than 1e-6 r are one contact (the shared edge reported by both its
//     triangles, a corner by all of its triangles, a face/edge pair within round-off of the
//     edge), and so are points whose normals differ by less than 10 degrees: inside a shallow
//     concave crease (a drum shell polygon of 360 sides creases by 1 degree) a sphere near the
//     crease overlaps both faces' planes by almost the same depth, and counting both would
//     double the force in a band along every crease of a surface meant to be smooth. The
//     deepest is kept (ties: lower triangle index), so the contact passes from one face to the
//     next when their depths are equal: the overlap stays continuous. Creases sharper than 10
//     degrees (a box's inside corner: 90) give one contact per face.
// A triangle holding the feature point q_i is at most |c - q_i| < r from c, so it is among the
// tested triangles: the rule needs no adjacency table. Distinct contacts (a sphere in an inside
// corner touches two or three faces) all count, deepest first.
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "demfit/dem_core/stl_mesh.hpp"
#include "demfit/dem_core/vec3.hpp"

namespace demfit::dem_core {

/// One contact point of a sphere with a mesh (mesh frame).
struct MeshContact {
  Vec3 normal{};         ///< unit vector from the sphere centre towards the surface
  double overlap = 0.0;  ///< r - distance [m], > 0
  std::uint32_t triangle = 0;
};

class TriangleMesh {
 public:
  /// Vertices with identical coordinates are one vertex. Throws std::runtime_error (naming the
  /// triangle) on an empty list, non-finite coordinates or a zero-area triangle.
  explicit TriangleMesh(const std::vector<Triangle>& triangles);

  [[nodiscard]] std::size_t triangle_count() const { return corner_.size(); }
  [[nodiscard]] std::size_t vertex_count() const { return vertex_.size(); }
  [[nodiscard]] std::size_t cell_count() const { return cell_start_.empty() ? 0 : cell_start_.size() - 1; }
  [[nodiscard]] const std::vector<Vec3>& vertices() const { return vertex_; }
  [[nodiscard]] Vec3 lower() const { return lower_; }
  [[nodiscard]] Vec3 upper() const { return upper_; }

  /// Contacts of the sphere (centre [m] in the mesh frame, radius [m]) after the rule above,
  /// deepest first, at most `capacity` (the shallowest are dropped); returns how many.
  int contacts(const Vec3& center, double radius, MeshContact* out, int capacity) const;
  /// The same contacts, testing only `candidates` instead of the cells: the result is identical
  /// whenever `candidates` holds every triangle closer than `radius` to `center` (the rule above
  /// reads only triangles closer than r, and the contacts are ordered by depth, then index).
  int contacts(const Vec3& center, double radius, std::span<const std::uint32_t> candidates, MeshContact* out,
               int capacity) const;
  /// Triangles closer than `reach` [m] to `center` (mesh frame), each once, appended to `found`
  /// in a fixed order: a particle's candidate list for contacts(..., candidates, ...). It stays
  /// complete while the sphere moves less than reach - r relative to the mesh.
  void triangles_within(const Vec3& center, double reach, std::vector<std::uint32_t>& found) const;
  /// True when some triangle lies closer than `distance` [m] to `center`.
  [[nodiscard]] bool any_within(const Vec3& center, double distance) const;

 private:
  /// Triangles registered in the cells covered by the box [c - reach, c + reach] whose plane
  /// lies closer than `reach` to c, each once, in a fixed order, into `found` (cleared first).
  void triangles_near(const Vec3& c, double reach, std::vector<std::uint32_t>& found) const;

  std::vector<Vec3> vertex_;
  std::vector<std::array<std::uint32_t, 3>> corner_;  ///< vertex indices of each triangle
  std::vector<Vec3> normal_;                          ///< unit normal of the winding
  Vec3 lower_{}, upper_{};                            ///< bounding box
  double cell_ = 0.0;                                 ///< cell edge [m]
  std::array<std::int64_t, 3> dims_{1, 1, 1};
  std::vector<std::uint32_t> cell_start_, cell_triangle_;  ///< CSR: triangles of each cell
};

}  // namespace demfit::dem_core
