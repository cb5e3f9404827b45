#pragma once
// Triangle surfaces for the mesh-wall tests: an axis-aligned box (12 triangles, outward winding)
// and a flat square floor of two triangles (shared diagonal edge).
#include <memory>
#include <vector>

#include "demfit/dem_core/triangle_mesh.hpp"
#include "demfit/dem_core/wall.hpp"

namespace demfit::dem_core::test {

inline std::vector<Triangle> box_triangles(const Vec3& lo, const Vec3& hi) {
  auto p = [&](int x, int y, int z) { return Vec3{x ? hi.x : lo.x, y ? hi.y : lo.y, z ? hi.z : lo.z}; };
  // Each face as a quad (a, b, c, d) counter-clockwise seen from outside: (a, b, c) and (a, c, d).
  const int quads[6][4][3] = {{{0, 0, 0}, {0, 1, 0}, {1, 1, 0}, {1, 0, 0}},   // z = lo
                              {{0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}},   // z = hi
                              {{0, 0, 0}, {1, 0, 0}, {1, 0, 1}, {0, 0, 1}},   // y = lo
                              {{0, 1, 0}, {0, 1, 1}, {1, 1, 1}, {1, 1, 0}},   // y = hi
                              {{0, 0, 0}, {0, 0, 1}, {0, 1, 1}, {0, 1, 0}},   // x = lo
                              {{1, 0, 0}, {1, 1, 0}, {1, 1, 1}, {1, 0, 1}}};  // x = hi
  std::vector<Triangle> t;
  for (const auto& q : quads) {
    const Vec3 a = p(q[0][0], q[0][1], q[0][2]), b = p(q[1][0], q[1][1], q[1][2]);
    const Vec3 c = p(q[2][0], q[2][1], q[2][2]), d = p(q[3][0], q[3][1], q[3][2]);
    t.push_back({a, b, c});
    t.push_back({a, c, d});
  }
  return t;
}

/// Square [-h, h]^2 at z = 0, split along the diagonal from (-h, -h) to (h, h).
inline std::vector<Triangle> two_triangle_floor(double h) {
  return {{Vec3{-h, -h, 0}, Vec3{h, -h, 0}, Vec3{h, h, 0}}, {Vec3{-h, -h, 0}, Vec3{h, h, 0}, Vec3{-h, h, 0}}};
}

inline WallSpec mesh_wall(const std::vector<Triangle>& triangles, const WallContactParameters& contact) {
  WallSpec spec{MeshGeometry{std::make_shared<const TriangleMesh>(triangles)}};
  spec.contact = contact;
  return spec;
}

}  // namespace demfit::dem_core::test
