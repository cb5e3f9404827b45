// Drum mesh for LIGGGHTS' fix mesh/surface.
#include "drum_mesh.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "demfit/dem_core/vec3.hpp"

namespace demfit::bench {
namespace {
using dem_core::Vec3;

struct StlWriter {
  std::ostream& out;
  std::size_t count = 0;
  /// One facet, vertex order flipped when needed so the right-hand normal is along `inward`.
  void facet(Vec3 a, Vec3 b, Vec3 c, const Vec3& inward) {
    Vec3 n = cross(b - a, c - a);
    if (dot(n, inward) < 0.0) {
      std::swap(b, c);
      n = -n;
    }
    n = (1.0 / norm(n)) * n;
    out << "facet normal " << n.x << ' ' << n.y << ' ' << n.z << "\n outer loop\n";
    for (const Vec3& v : {a, b, c}) out << "  vertex " << v.x << ' ' << v.y << ' ' << v.z << '\n';
    out << " endloop\nendfacet\n";
    ++count;
  }
};

Vec3 on_circle(double r, double angle, double z) { return {r * std::cos(angle), r * std::sin(angle), z}; }

/// Triangles between two concentric rings of p (inner) and q (outer) equally spaced points,
/// both starting at angle `phase`: walk around advancing the ring whose next point comes first.
void ring_band(StlWriter& stl, double r_in, int p, double r_out, int q, double z, double phase, const Vec3& inward) {
  const double tau = 2.0 * std::numbers::pi;
  auto inner = [&](int i) { return p == 1 ? Vec3{0, 0, z} : on_circle(r_in, phase + tau * i / p, z); };
  auto outer = [&](int j) { return on_circle(r_out, phase + tau * j / q, z); };
  int i = p == 1 ? 1 : 0, j = 0;  // a single centre point only fans out
  while (i < p || j < q) {
    const double next_in = static_cast<double>(i + 1) / p, next_out = static_cast<double>(j + 1) / q;
    if (j < q && (i >= p || next_out <= next_in)) {
      stl.facet(inner(p == 1 ? 0 : i % p), outer(j), outer((j + 1) % q), inward);
      ++j;
    } else {
      stl.facet(inner(i % p), outer(j % q), inner((i + 1) % p), inward);
      ++i;
    }
  }
}

}  // namespace

std::size_t write_drum_stl(std::ostream& out, const DrumMeshRequest& r) {
  if (r.segments < 8 || r.shell_rings < 1 || r.cap_rings < 1 || r.segments % r.cap_rings != 0)
    throw std::runtime_error("drum mesh: segments >= 8 and a multiple of cap_rings, shell_rings >= 1");
  out.precision(17);
  out << "solid drum\n";
  StlWriter stl{out};
  const double tau = 2.0 * std::numbers::pi;
  const double vertex_radius = 2.0 * r.radius / (1.0 + std::cos(std::numbers::pi / r.segments));
  for (int ring = 0; ring < r.shell_rings; ++ring) {
    const double z0 = r.depth * ring / r.shell_rings, z1 = r.depth * (ring + 1) / r.shell_rings;
    for (int k = 0; k < r.segments; ++k) {
      const double a0 = r.phase + tau * k / r.segments, a1 = r.phase + tau * (k + 1) / r.segments;
      const Vec3 inward = -on_circle(1.0, 0.5 * (a0 + a1), 0.0);
      stl.facet(on_circle(vertex_radius, a0, z0), on_circle(vertex_radius, a1, z0), on_circle(vertex_radius, a1, z1),
                inward);
      stl.facet(on_circle(vertex_radius, a0, z0), on_circle(vertex_radius, a1, z1), on_circle(vertex_radius, a0, z1),
                inward);
    }
  }
  const int per_ring = r.segments / r.cap_rings;
  for (const auto& [z, inward] : {std::pair{0.0, Vec3{0, 0, 1}}, std::pair{r.depth, Vec3{0, 0, -1}}}) {
    for (int k = 1; k <= r.cap_rings; ++k)
      ring_band(stl, vertex_radius * (k - 1) / r.cap_rings, k == 1 ? 1 : per_ring * (k - 1),
                vertex_radius * k / r.cap_rings, per_ring * k, z, r.phase, inward);
  }
  out << "endsolid drum\n";
  return stl.count;
}

}  // namespace demfit::bench
