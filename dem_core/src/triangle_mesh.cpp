// Triangle mesh of a mesh wall: welding, contact grid, sphere contacts and the one-contact rule
// where triangles meet (triangle_mesh.hpp).
#include "demfit/dem_core/triangle_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>
#include <string>
#include <tuple>

namespace demfit::dem_core {
namespace {

enum class Feature : std::uint8_t { face, edge, vertex };

/// A triangle's closest point to a sphere centre and the feature it lies on.
struct Candidate {
  Vec3 point{};
  Vec3 normal{};  // towards the surface
  double distance = 0.0;
  std::uint32_t triangle = 0;
  Feature feature = Feature::face;
  std::uint32_t first = 0, second = 0;  // edge: vertex ids, first < second; vertex: first
};

/// Closest point on the segment between vertices lo < hi, always computed from the lower index
/// so that both triangles of a shared edge find the same point.
Vec3 edge_point(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Vec3 e = b - a;
  const double t = std::clamp(dot(p - a, e) / dot(e, e), 0.0, 1.0);
  return a + t * e;
}

}  // namespace

TriangleMesh::TriangleMesh(const std::vector<Triangle>& triangles) {
  if (triangles.empty()) throw std::runtime_error("triangle mesh: no triangles; a mesh wall needs at least one");
  std::map<std::tuple<double, double, double>, std::uint32_t> ids;  // exact welding
  double area = 0.0;
  for (std::size_t k = 0; k < triangles.size(); ++k) {
    std::array<std::uint32_t, 3> c{};
    for (int v = 0; v < 3; ++v) {
      const Vec3& x = triangles[k][static_cast<std::size_t>(v)];
      if (!is_finite(x))
        throw std::runtime_error("triangle mesh: triangle " + std::to_string(k) + " has a non-finite vertex coordinate");
      const auto [it, added] = ids.try_emplace({x.x, x.y, x.z}, static_cast<std::uint32_t>(vertex_.size()));
      if (added) vertex_.push_back(x);
      c[static_cast<std::size_t>(v)] = it->second;
    }
    const Vec3 w = cross(vertex_[c[1]] - vertex_[c[0]], vertex_[c[2]] - vertex_[c[0]]);
    const double twice_area = norm(w);
    if (twice_area == 0.0 || !std::isfinite(twice_area))
      throw std::runtime_error("triangle mesh: triangle " + std::to_string(k) + " has zero area; remove it");
    // Divided, not multiplied by 1/|w|: an axis-aligned face gets an exact unit normal.
    normal_.push_back({w.x / twice_area, w.y / twice_area, w.z / twice_area});
    corner_.push_back(c);
    area += 0.5 * twice_area;
  }
  lower_ = upper_ = vertex_[0];
  for (const Vec3& v : vertex_) {
    lower_ = {std::min(lower_.x, v.x), std::min(lower_.y, v.y), std::min(lower_.z, v.z)};
    upper_ = {std::max(upper_.x, v.x), std::max(upper_.y, v.y), std::max(upper_.z, v.z)};
  }
  // Cells about twice a typical triangle's size, at most ~4 cells per triangle.
  const Vec3 extent = upper_ - lower_;
  const double n = static_cast<double>(triangles.size());
  cell_ = std::max(2.0 * std::sqrt(area / n), 1e-9 * std::max({extent.x, extent.y, extent.z}));
  const double max_cells = 4.0 * n + 64.0;
  for (;;) {
    const double e[3] = {extent.x, extent.y, extent.z};
    double cells = 1.0;
    for (int d = 0; d < 3; ++d) {
      dims_[static_cast<std::size_t>(d)] = std::max<std::int64_t>(1, static_cast<std::int64_t>(std::ceil(e[d] / cell_)));
      cells *= static_cast<double>(dims_[static_cast<std::size_t>(d)]);
    }
    if (cells <= max_cells) break;
    cell_ *= 1.26;
  }
  auto cell_range = [&](const Triangle& t, std::array<std::int64_t, 3>& lo, std::array<std::int64_t, 3>& hi) {
    const double l[3] = {lower_.x, lower_.y, lower_.z};
    for (std::size_t d = 0; d < 3; ++d) {
      double mn = (&t[0].x)[d], mx = mn;
      for (const Vec3& v : t) mn = std::min(mn, (&v.x)[d]), mx = std::max(mx, (&v.x)[d]);
      lo[d] = std::clamp<std::int64_t>(static_cast<std::int64_t>(std::floor((mn - l[d]) / cell_)), 0, dims_[d] - 1);
      hi[d] = std::clamp<std::int64_t>(static_cast<std::int64_t>(std::floor((mx - l[d]) / cell_)), 0, dims_[d] - 1);
    }
  };
  const auto cells = static_cast<std::size_t>(dims_[0] * dims_[1] * dims_[2]);
  cell_start_.assign(cells + 1, 0);
  for (int pass = 0; pass < 2; ++pass) {  // count, then fill (CSR)
    std::vector<std::uint32_t> fill(cell_start_.begin(), cell_start_.end() - 1);
    if (pass == 1) cell_triangle_.resize(cell_start_.back());
    for (std::size_t k = 0; k < triangles.size(); ++k) {
      std::array<std::int64_t, 3> lo{}, hi{};
      cell_range({vertex_[corner_[k][0]], vertex_[corner_[k][1]], vertex_[corner_[k][2]]}, lo, hi);
      for (std::int64_t x = lo[0]; x <= hi[0]; ++x)
        for (std::int64_t y = lo[1]; y <= hi[1]; ++y)
          for (std::int64_t z = lo[2]; z <= hi[2]; ++z) {
            const auto cell = static_cast<std::size_t>((x * dims_[1] + y) * dims_[2] + z);
            if (pass == 0) ++cell_start_[cell + 1];
            else cell_triangle_[fill[cell]++] = static_cast<std::uint32_t>(k);
          }
    }
    if (pass == 0)
      for (std::size_t c = 0; c < cells; ++c) cell_start_[c + 1] += cell_start_[c];
  }
}

void TriangleMesh::triangles_near(const Vec3& c, double reach, std::vector<std::uint32_t>& found) const {
  found.clear();
  const double cc[3] = {c.x, c.y, c.z}, l[3] = {lower_.x, lower_.y, lower_.z}, u[3] = {upper_.x, upper_.y, upper_.z};
  std::array<std::int64_t, 3> lo{}, hi{};
  for (std::size_t d = 0; d < 3; ++d) {
    if (!(cc[d] + reach >= l[d] && cc[d] - reach <= u[d])) return;  // outside the box (or NaN)
    lo[d] = std::clamp<std::int64_t>(static_cast<std::int64_t>(std::floor((cc[d] - reach - l[d]) / cell_)), 0, dims_[d] - 1);
    hi[d] = std::clamp<std::int64_t>(static_cast<std::int64_t>(std::floor((cc[d] + reach - l[d]) / cell_)), 0, dims_[d] - 1);
  }
  // Each triangle once, in the order first met (cells ascending): a per-thread stamp per triangle.
  thread_local std::vector<std::uint32_t> stamp;
  thread_local std::uint32_t query = 0;
  if (stamp.size() < corner_.size()) stamp.assign(corner_.size(), 0), query = 0;
  if (++query == 0) std::fill(stamp.begin(), stamp.end(), 0), query = 1;  // wrapped around
  const double reach2 = reach * reach;
  for (std::int64_t x = lo[0]; x <= hi[0]; ++x)
    for (std::int64_t y = lo[1]; y <= hi[1]; ++y)
      for (std::int64_t z = lo[2]; z <= hi[2]; ++z) {
        const auto cell = static_cast<std::size_t>((x * dims_[1] + y) * dims_[2] + z);
        for (std::uint32_t k = cell_start_[cell]; k < cell_start_[cell + 1]; ++k) {
          const std::uint32_t t = cell_triangle_[k];
          if (stamp[t] == query) continue;
          stamp[t] = query;
          // The plane's distance bounds the triangle's from below: most far triangles stop here.
          const Vec3& a = vertex_[corner_[t][0]];
          const double d = dot(c - a, normal_[t]);
          if (d * d >= reach2) continue;
          // And by its bounding box grown by reach (cells are coarser than a sphere).
          const Vec3& b = vertex_[corner_[t][1]];
          const Vec3& e = vertex_[corner_[t][2]];
          auto outside = [&](double p, double q0, double q1, double q2) {
            return p + reach < std::min({q0, q1, q2}) || p - reach > std::max({q0, q1, q2});
          };
          if (outside(c.x, a.x, b.x, e.x) || outside(c.y, a.y, b.y, e.y) || outside(c.z, a.z, b.z, e.z)) continue;
          found.push_back(t);
        }
      }
}

namespace {

/// Closest point of triangle (a, b, c) with vertex ids (ia, ib, ic) to p, by Voronoi region
/// (Ericson 5.1.5); a face point uses the plane distance along the unit normal n.
Candidate closest_point(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c, std::uint32_t ia,
                        std::uint32_t ib, std::uint32_t ic, const Vec3& n) {
  Candidate r;
  auto vertex = [&](const Vec3& v, std::uint32_t id) {
    r.feature = Feature::vertex, r.point = v, r.first = id;
    return r;
  };
  auto edge = [&](const Vec3& u, std::uint32_t iu, const Vec3& v, std::uint32_t iv) {
    r.feature = Feature::edge, r.first = std::min(iu, iv), r.second = std::max(iu, iv);
    r.point = iu < iv ? edge_point(p, u, v) : edge_point(p, v, u);
    return r;
  };
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = dot(ab, ap), d2 = dot(ac, ap);
  if (d1 <= 0.0 && d2 <= 0.0) return vertex(a, ia);
  const Vec3 bp = p - b;
  const double d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0.0 && d4 <= d3) return vertex(b, ib);
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) return edge(a, ia, b, ib);
  const Vec3 cp = p - c;
  const double d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0.0 && d5 <= d6) return vertex(c, ic);
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) return edge(a, ia, c, ic);
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0) return edge(b, ib, c, ic);
  const double d = dot(p - a, n);  // as PlaneGeometry: dot(c - point, normal)
  r.feature = Feature::face;
  r.point = p - d * n;
  r.distance = std::abs(d);
  r.normal = d >= 0.0 ? -n : n;
  return r;
}

bool holds(const std::array<std::uint32_t, 3>& corners, std::uint32_t id) {
  return corners[0] == id || corners[1] == id || corners[2] == id;
}

}  // namespace

int TriangleMesh::contacts(const Vec3& center, double radius, MeshContact* out, int capacity) const {
  thread_local std::vector<std::uint32_t> near;
  triangles_near(center, radius, near);
  return contacts(center, radius, near, out, capacity);
}

int TriangleMesh::contacts(const Vec3& center, double radius, std::span<const std::uint32_t> candidates,
                           MeshContact* out, int capacity) const {
  thread_local std::vector<Candidate> found;
  found.clear();
  for (const std::uint32_t t : candidates) {
    const auto& k = corner_[t];
    // A triangle is no closer than its plane: a plane at r or beyond rules it out (one dot product).
    const double plane_distance = dot(center - vertex_[k[0]], normal_[t]);
    if (plane_distance * plane_distance >= radius * radius) continue;
    Candidate c = closest_point(center, vertex_[k[0]], vertex_[k[1]], vertex_[k[2]], k[0], k[1], k[2], normal_[t]);
    if (c.feature != Feature::face) {
      const Vec3 to_surface = c.point - center;
      const double d2 = norm2(to_surface);
      if (d2 >= radius * radius || d2 == 0.0) continue;
      c.distance = std::sqrt(d2);
      c.normal = (1.0 / c.distance) * to_surface;
    } else if (c.distance >= radius) {
      continue;
    }
    c.triangle = t;
    found.push_back(c);
  }
  const double same2 = (1e-6 * radius) * (1e-6 * radius);
  // Rule 2: an edge or vertex point that a triangle around it does not agree on is not a contact.
  auto dropped = [&](const Candidate& c) {
    if (c.feature == Feature::face) return false;
    for (const Candidate& o : found) {
      const auto& k = corner_[o.triangle];
      const bool around = holds(k, c.first) && (c.feature == Feature::vertex || holds(k, c.second));
      if (around && norm2(o.point - c.point) > same2 && o.distance <= c.distance) return true;
    }
    return false;
  };
  thread_local std::vector<Candidate> kept;  // few: a sphere rarely touches more than three features
  kept.clear();
  for (const Candidate& c : found)
    if (!dropped(c)) kept.push_back(c);
  std::sort(kept.begin(), kept.end(), [](const Candidate& x, const Candidate& y) {
    return x.distance != y.distance ? x.distance < y.distance : x.triangle < y.triangle;
  });
  int count = 0;
  // Rule 3: coincident points, and points whose normals differ by less than 10 degrees, once.
  constexpr double same_direction = 0.98480775301220802;  // cos(10 deg)
  for (std::size_t i = 0; i < kept.size() && count < capacity; ++i) {
    bool repeated = false;
    for (std::size_t j = 0; j < i && !repeated; ++j)
      repeated = norm2(kept[j].point - kept[i].point) <= same2 || dot(kept[j].normal, kept[i].normal) > same_direction;
    if (repeated) continue;
    out[count++] = {kept[i].normal, radius - kept[i].distance, kept[i].triangle};
  }
  return count;
}

void TriangleMesh::triangles_within(const Vec3& center, double reach, std::vector<std::uint32_t>& found) const {
  thread_local std::vector<std::uint32_t> near;
  triangles_near(center, reach, near);
  for (const std::uint32_t t : near) {
    const auto& k = corner_[t];
    const Candidate c = closest_point(center, vertex_[k[0]], vertex_[k[1]], vertex_[k[2]], k[0], k[1], k[2], normal_[t]);
    if (norm2(c.point - center) < reach * reach) found.push_back(t);
  }
}

bool TriangleMesh::any_within(const Vec3& center, double distance) const {
  thread_local std::vector<std::uint32_t> near;
  triangles_near(center, distance, near);
  for (const std::uint32_t t : near) {
    const auto& k = corner_[t];
    const Candidate c = closest_point(center, vertex_[k[0]], vertex_[k[1]], vertex_[k[2]], k[0], k[1], k[2], normal_[t]);
    if (norm2(c.point - center) < distance * distance) return true;
  }
  return false;
}

}  // namespace demfit::dem_core
