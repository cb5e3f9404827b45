// Triangle mesh of a closed drum (drum_mesh.hpp).
#include "demfit/dem_core/drum_mesh.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <utility>

namespace demfit::dem_core {
namespace {

/// Appends triangles with the winding flipped when needed so the right-hand normal is along `inward`.
struct InwardTriangles {
  std::vector<Triangle>& out;
  void add(const Vec3& a, Vec3 b, Vec3 c, const Vec3& inward) {
    if (dot(cross(b - a, c - a), inward) < 0.0) std::swap(b, c);
    out.push_back({a, b, c});
  }
};

Vec3 on_circle(double r, double angle, double z) { return {r * std::cos(angle), r * std::sin(angle), z}; }

/// Triangles between two concentric rings of p (inner) and q (outer) equally spaced points,
/// both starting at angle `phase`: walk around advancing the ring whose next point comes first.
void ring_band(InwardTriangles& mesh, double r_in, int p, double r_out, int q, double z, double phase,
               const Vec3& inward) {
  const double tau = 2.0 * std::numbers::pi;
  auto inner = [&](int i) { return p == 1 ? Vec3{0, 0, z} : on_circle(r_in, phase + tau * i / p, z); };
  auto outer = [&](int j) { return on_circle(r_out, phase + tau * j / q, z); };
  int i = p == 1 ? 1 : 0, j = 0;  // a single centre point only fans out
  while (i < p || j < q) {
    const double next_in = static_cast<double>(i + 1) / p, next_out = static_cast<double>(j + 1) / q;
    if (j < q && (i >= p || next_out <= next_in)) {
      mesh.add(inner(p == 1 ? 0 : i % p), outer(j), outer((j + 1) % q), inward);
      ++j;
    } else {
      mesh.add(inner(i % p), outer(j % q), inner((i + 1) % p), inward);
      ++i;
    }
  }
}

}  // namespace

std::string drum_mesh_request_problem(const DrumMeshRequest& r) {
  if (!(std::isfinite(r.radius) && r.radius > 0.0)) return "radius must be a positive finite length [m]";
  if (!(std::isfinite(r.depth) && r.depth > 0.0)) return "depth must be a positive finite length [m]";
  if (!std::isfinite(r.phase)) return "phase must be finite [rad]";
  if (r.segments < 8) return "segments must be at least 8 (sides of the shell polygon)";
  if (r.shell_rings < 1) return "shell_rings must be at least 1";
  if (r.cap_rings < 1) return "cap_rings must be at least 1";
  if (r.segments % r.cap_rings != 0) return "segments must be a multiple of cap_rings";
  return {};
}

std::vector<Triangle> drum_mesh_triangles(const DrumMeshRequest& r) {
  if (const std::string problem = drum_mesh_request_problem(r); !problem.empty())
    throw std::runtime_error("drum mesh: " + problem);
  std::vector<Triangle> triangles;
  InwardTriangles mesh{triangles};
  const double tau = 2.0 * std::numbers::pi;
  const double vertex_radius = 2.0 * r.radius / (1.0 + std::cos(std::numbers::pi / r.segments));
  for (int ring = 0; ring < r.shell_rings; ++ring) {
    const double z0 = r.depth * ring / r.shell_rings, z1 = r.depth * (ring + 1) / r.shell_rings;
    for (int k = 0; k < r.segments; ++k) {
      const double a0 = r.phase + tau * k / r.segments, a1 = r.phase + tau * (k + 1) / r.segments;
      const Vec3 inward = -on_circle(1.0, 0.5 * (a0 + a1), 0.0);
      mesh.add(on_circle(vertex_radius, a0, z0), on_circle(vertex_radius, a1, z0), on_circle(vertex_radius, a1, z1),
               inward);
      mesh.add(on_circle(vertex_radius, a0, z0), on_circle(vertex_radius, a1, z1), on_circle(vertex_radius, a0, z1),
               inward);
    }
  }
  const int per_ring = r.segments / r.cap_rings;
  for (const auto& [z, inward] : {std::pair{0.0, Vec3{0, 0, 1}}, std::pair{r.depth, Vec3{0, 0, -1}}}) {
    for (int k = 1; k <= r.cap_rings; ++k)
      ring_band(mesh, vertex_radius * (k - 1) / r.cap_rings, k == 1 ? 1 : per_ring * (k - 1),
                vertex_radius * k / r.cap_rings, per_ring * k, z, r.phase, inward);
  }
  return triangles;
}

void write_ascii_stl(std::ostream& out, const std::vector<Triangle>& triangles, const std::string& name) {
  const auto precision = out.precision(17);
  out << "solid " << name << '\n';
  for (const Triangle& t : triangles) {
    Vec3 n = cross(t[1] - t[0], t[2] - t[0]);
    n = (1.0 / norm(n)) * n;
    out << "facet normal " << n.x << ' ' << n.y << ' ' << n.z << "\n outer loop\n";
    for (const Vec3& v : t) out << "  vertex " << v.x << ' ' << v.y << ' ' << v.z << '\n';
    out << " endloop\nendfacet\n";
  }
  out << "endsolid " << name << '\n';
  out.precision(precision);
}

}  // namespace demfit::dem_core
