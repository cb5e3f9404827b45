// Packing generation on a jittered cubic lattice inside a region (seeded, platform-independent),
// and region volumes used to report achieved volume fractions.
#include "demfit/dem_core/packing.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <sstream>
#include <stdexcept>

#include "demfit/dem_core/simulation.hpp"
#include "validation.hpp"

namespace demfit::dem_core {
namespace {

/// Uniform double in [0, 1) from the top 53 bits (our own mapping: std distributions differ
/// between standard libraries, which would break cross-platform reproducibility).
double uniform01(std::mt19937_64& rng) { return static_cast<double>(rng() >> 11) * 0x1.0p-53; }

/// Area of the part of a circle (radius r) below the chord at height h from the centre.
double segment_area(double r, double h) {
  h = std::clamp(h, -r, r);
  return r * r * (std::numbers::pi - std::acos(h / r)) + h * std::sqrt(std::max(0.0, r * r - h * h));
}

struct Frame {  // orthonormal (e1, e2, up)
  Vec3 e1, e2, up;
};

Frame frame_for(const Vec3& up) {
  const Vec3 u = normalized(up);
  const Vec3 helper = std::fabs(u.x) < 0.9 ? Vec3{1, 0, 0} : Vec3{0, 1, 0};
  const Vec3 e1 = normalized(cross(helper, u));
  return {e1, cross(u, e1), u};
}

/// Centre and radius of a sphere enclosing the region.
std::pair<Vec3, double> bounding_sphere(const Region& region) {
  return std::visit(
      [](const auto& g) -> std::pair<Vec3, double> {
        using G = std::decay_t<decltype(g)>;
        if constexpr (std::is_same_v<G, BoxRegion>)
          return {0.5 * (g.lower + g.upper), 0.5 * norm(g.upper - g.lower)};
        else
          return {g.base_center + (0.5 * g.length) * normalized(g.axis),
                  std::sqrt(g.radius * g.radius + 0.25 * g.length * g.length)};
      },
      region);
}

bool inside_cylinder(const Vec3& base, const Vec3& axis, double radius, double length, const Vec3& c, double r) {
  const Vec3 a = normalized(axis);
  const Vec3 rel = c - base;
  const double s = dot(rel, a);
  if (s < r || s > length - r) return false;
  const double inner = radius - r;
  return inner > 0.0 && norm2(rel - s * a) <= inner * inner;
}

void validate_region(const Region& region) {
  std::visit(
      [](const auto& g) {
        using G = std::decay_t<decltype(g)>;
        if constexpr (std::is_same_v<G, BoxRegion>) {
          require_finite("box.lower [m]", g.lower);
          require_finite("box.upper [m]", g.upper);
          if (!(g.upper.x > g.lower.x && g.upper.y > g.lower.y && g.upper.z > g.lower.z))
            throw std::runtime_error("box.upper must exceed box.lower in x, y and z");
        } else {
          require_finite("region base_center [m]", g.base_center);
          require_direction("region axis", g.axis);
          require_positive("region radius [m]", g.radius);
          require_positive("region length [m]", g.length);
          if constexpr (std::is_same_v<G, DrumSegmentRegion>) {
            require_direction("drum segment up", g.up);
            require_finite("drum segment fill_height [m]", g.fill_height);
            if (std::fabs(dot(normalized(g.up), normalized(g.axis))) > 1e-9)
              throw std::runtime_error("drum segment up must be perpendicular to its axis");
          }
        }
      },
      region);
}

}  // namespace

double region_volume(const Region& region) {
  return std::visit(
      [](const auto& g) -> double {
        using G = std::decay_t<decltype(g)>;
        if constexpr (std::is_same_v<G, BoxRegion>) {
          const Vec3 d = g.upper - g.lower;
          return d.x * d.y * d.z;
        } else if constexpr (std::is_same_v<G, CylinderRegion>) {
          return std::numbers::pi * g.radius * g.radius * g.length;
        } else {
          return segment_area(g.radius, g.fill_height) * g.length;
        }
      },
      region);
}

bool region_contains(const Region& region, const Vec3& c, double r) {
  return std::visit(
      [&](const auto& g) -> bool {
        using G = std::decay_t<decltype(g)>;
        if constexpr (std::is_same_v<G, BoxRegion>) {
          return c.x - r >= g.lower.x && c.x + r <= g.upper.x && c.y - r >= g.lower.y && c.y + r <= g.upper.y &&
                 c.z - r >= g.lower.z && c.z + r <= g.upper.z;
        } else if constexpr (std::is_same_v<G, CylinderRegion>) {
          return inside_cylinder(g.base_center, g.axis, g.radius, g.length, c, r);
        } else {
          return inside_cylinder(g.base_center, g.axis, g.radius, g.length, c, r) &&
                 dot(c - g.base_center, normalized(g.up)) <= g.fill_height - r;
        }
      },
      region);
}

double drum_fill_height(double radius, double fraction) {
  require_positive("drum radius [m]", radius);
  if (!(fraction >= 0.0 && fraction <= 1.0)) fail("drum fill fraction", fraction, "must lie in [0, 1]");
  const double target = fraction * std::numbers::pi * radius * radius;
  double lo = -radius, hi = radius;
  for (int it = 0; it < 200; ++it) {
    const double mid = 0.5 * (lo + hi);
    (segment_area(radius, mid) < target ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

namespace {

// Feasibility before any lattice is built (impossible fills once spun silently). The
// lattice of spacing 2 r_max (1 + gap) holds at most the simple-cubic fraction pi/6 of the region
// (face-centred cubic: pi/(3 sqrt 2)), so a larger solid volume can never be placed; a sphere wider than the region
// fits nowhere; and a lattice of more than kMaxLatticeSites sites would take minutes and gigabytes.
void check_packing_feasible(const PackingRequest& q) {
  const double kLatticeFraction =
      q.lattice == PackingRequest::Lattice::cubic ? std::numbers::pi / 6.0 : std::numbers::pi / (3.0 * std::sqrt(2.0));
  constexpr double kMaxLatticeSites = 2.0e8;
  const bool explicit_radii = !q.radii.empty();
  const double r_largest = explicit_radii ? *std::max_element(q.radii.begin(), q.radii.end()) : 0.0;
  const double r_hi = explicit_radii          ? r_largest
                      : q.radius_spread > 0.0 ? q.radius_max * (1.0 + q.radius_spread)
                                              : q.radius_max;
  const double volume = region_volume(q.region);
  const double extent = bounding_sphere(q.region).second;
  if (r_hi >= extent) fail("packing.radius_max [m]", r_hi, "is larger than the region; no sphere fits");
  // Smallest possible sphere: the check refuses only what surely cannot be placed.
  const double r_lo = explicit_radii          ? r_largest
                      : q.radius_spread > 0.0 ? q.radius_min * (1.0 - q.radius_spread)
                                              : q.radius_min;
  const double sphere = 4.0 / 3.0 * std::numbers::pi * r_lo * r_lo * r_lo;
  double requested = q.count > 0 ? static_cast<double>(q.count) * sphere : q.solid_volume;
  if (explicit_radii) {
    requested = 0.0;
    for (double r : q.radii) requested += 4.0 / 3.0 * std::numbers::pi * r * r * r;
  }
  if (requested > kLatticeFraction * volume) {
    std::ostringstream msg;
    msg << "packing: "
        << (explicit_radii ? "radii"
            : q.count > 0  ? "count"
                           : "solid_volume")
        << " needs a solid volume of " << requested << " m^3, more than the " << kLatticeFraction << " x " << volume
        << " m^3 of the region that a packing can reach; fewer or smaller particles, or a larger container";
    throw std::runtime_error(msg.str());
  }
  const double cells = 2.0 * std::ceil(extent / (2.0 * r_hi * (1.0 + q.gap))) + 1.0;
  if (cells * cells * cells > kMaxLatticeSites) {
    std::ostringstream msg;
    msg << "packing.radius_max [m]: " << r_hi << " is too small for a region of extent " << extent << " m ("
        << cells * cells * cells << " lattice sites, limit " << kMaxLatticeSites
        << "); use larger particles or coarse graining";
    throw std::runtime_error(msg.str());
  }
}

void validate_request(const PackingRequest& q) {
  validate_region(q.region);
  require_non_negative("packing.gap", q.gap);
  if (!q.radii.empty()) {
    for (double r : q.radii) require_positive("packing.radii [m]", r);
    return;
  }
  require_positive("packing.radius_min [m]", q.radius_min);
  require_positive("packing.radius_max [m]", q.radius_max);
  if (q.radius_min > q.radius_max) fail("packing.radius_min [m]", q.radius_min, "must be <= radius_max");
  require_non_negative("packing.radius_spread", q.radius_spread);
  if (q.radius_spread > 0.9) fail("packing.radius_spread", q.radius_spread, "must lie in [0, 0.9]");
  if (q.radius_spread > 0.0 && q.radius_min != q.radius_max)
    fail("packing.radius_spread", q.radius_spread, "needs radius_min == radius_max (the nominal radius)");
  require_non_negative("packing.solid_volume [m^3]", q.solid_volume);
  if (q.count == 0 && q.solid_volume <= 0.0)
    throw std::runtime_error("packing: set count > 0 or solid_volume > 0 (m^3)");
}

/// Sub-lattice offsets (in units of the cubic cell) of the lattice's basis.
std::vector<Vec3> lattice_basis(PackingRequest::Lattice lattice) {
  if (lattice == PackingRequest::Lattice::cubic) return {{0, 0, 0}};
  return {{0, 0, 0}, {0.5, 0.5, 0}, {0.5, 0, 0.5}, {0, 0.5, 0.5}};
}

}  // namespace

Packing generate_packing(const PackingRequest& q) {
  validate_request(q);
  check_packing_feasible(q);
  const Frame f = frame_for(require_direction("packing.up", q.up));
  const bool explicit_radii = !q.radii.empty();
  // Radius bounds: [radius_min, radius_max], or R(1 -+ s) with a spread (identical when s = 0);
  // explicit radii: every site sized for the largest one.
  const double r_largest = explicit_radii ? *std::max_element(q.radii.begin(), q.radii.end()) : 0.0;
  const double r_lo = explicit_radii          ? r_largest
                      : q.radius_spread > 0.0 ? q.radius_min * (1.0 - q.radius_spread)
                                              : q.radius_min;
  const double r_hi = explicit_radii          ? r_largest
                      : q.radius_spread > 0.0 ? q.radius_max * (1.0 + q.radius_spread)
                                              : q.radius_max;
  const std::size_t count = explicit_radii ? q.radii.size() : q.count;
  const double neighbour_distance = 2.0 * r_hi * (1.0 + q.gap);
  const std::vector<Vec3> basis = lattice_basis(q.lattice);
  // Cubic cell edge: the nearest-neighbour distance (cubic) or sqrt(2) times it (fcc).
  const double spacing = basis.size() == 1 ? neighbour_distance : std::sqrt(2.0) * neighbour_distance;
  const double jitter = 0.4999 * (neighbour_distance - 2.0 * r_hi);
  const auto [center, extent] = bounding_sphere(q.region);
  const auto cells = static_cast<std::int64_t>(std::ceil(extent / spacing));
  std::mt19937_64 rng(q.seed);
  struct Site {
    std::int64_t layer;
    double key;
    Vec3 x;
    double r;
  };
  std::vector<Site> sites;
  for (std::int64_t k = -cells; k <= cells; ++k)
    for (std::int64_t j = -cells; j <= cells; ++j)
      for (std::int64_t i = -cells; i <= cells; ++i)
        for (std::size_t b = 0; b < basis.size(); ++b) {
          // Always draw the same numbers per site so the sequence does not depend on acceptance.
          const double r = r_lo + (r_hi - r_lo) * uniform01(rng);
          const double a = (2.0 * uniform01(rng) - 1.0) * jitter;
          const double bb = (2.0 * uniform01(rng) - 1.0) * jitter;
          const double c = (2.0 * uniform01(rng) - 1.0) * jitter;
          const double key = uniform01(rng);
          const Vec3 cell{static_cast<double>(i) + basis[b].x, static_cast<double>(j) + basis[b].y,
                          static_cast<double>(k) + basis[b].z};
          const Vec3 x =
              center + (cell.x * spacing + a) * f.e1 + (cell.y * spacing + bb) * f.e2 + (cell.z * spacing + c) * f.up;
          // Layers along up: a cubic cell holds two fcc layers (basis z = 0 and 1/2).
          const std::int64_t layer = basis.size() == 1 ? k : 2 * k + (basis[b].z > 0.0 ? 1 : 0);
          if (region_contains(q.region, x, r)) sites.push_back({layer, key, x, r});
        }
  // Lowest layers first; random order inside a layer so a partly filled top layer is random.
  std::stable_sort(sites.begin(), sites.end(),
                   [](const Site& s, const Site& t) { return s.layer != t.layer ? s.layer < t.layer : s.key < t.key; });
  Packing out;
  out.capacity = sites.size();
  for (const Site& s : sites) {
    if (count > 0 ? out.centers.size() >= count : out.solid_volume >= q.solid_volume) break;
    const double r = explicit_radii ? q.radii[out.centers.size()] : s.r;
    out.centers.push_back(s.x);
    out.radii.push_back(r);
    out.solid_volume += 4.0 / 3.0 * std::numbers::pi * r * r * r;
  }
  const bool short_count = count > 0 && out.centers.size() < count;
  const bool short_volume = count == 0 && out.solid_volume < q.solid_volume;
  if (short_count || short_volume) {
    std::ostringstream msg;
    msg << "packing: " << (short_count ? "count" : "solid_volume") << " cannot be reached, only " << out.capacity
        << " spheres fit in the region at gap " << q.gap << "; enlarge the region or reduce the gap";
    throw std::runtime_error(msg.str());
  }
  out.volume_fraction = out.solid_volume / region_volume(q.region);
  return out;
}

double mean_volume_factor(double radius_spread) {
  // E[(1 + s u)^3] for u uniform in [-1, 1]: 1 + 3 s^2 E[u^2] = 1 + s^2 (odd moments vanish).
  return 1.0 + radius_spread * radius_spread;
}

void add_packing(Simulation& simulation, const Packing& packing, std::size_t material) {
  for (std::size_t i = 0; i < packing.centers.size(); ++i)
    simulation.add_particle(packing.centers[i], packing.radii[i], material);
}

double bed_height(const Simulation& s, const Vec3& up, double top_fraction) {
  if (s.particle_count() == 0) throw std::runtime_error("bed_height: no particles");
  const Vec3 u = normalized(up);
  std::vector<double> tops(s.particle_count());
  for (std::size_t i = 0; i < tops.size(); ++i) tops[i] = dot(s.positions()[i], u) + s.radii()[i];
  const auto m =
      std::max<std::size_t>(1, static_cast<std::size_t>(std::lround(top_fraction * static_cast<double>(tops.size()))));
  std::nth_element(tops.begin(), tops.begin() + static_cast<std::ptrdiff_t>(m - 1), tops.end(), std::greater<>());
  std::sort(tops.begin(), tops.begin() + static_cast<std::ptrdiff_t>(m), std::greater<>());
  double sum = 0.0;
  for (std::size_t k = 0; k < m; ++k) sum += tops[k];
  return sum / static_cast<double>(m);
}

double solid_volume(const Simulation& s) {
  double v = 0.0;
  for (double r : s.radii()) v += 4.0 / 3.0 * std::numbers::pi * r * r * r;
  return v;
}

double region_volume_below(const Region& region, const Vec3& up, double height) {
  const Vec3 u = normalized(up);
  return std::visit(
      [&](const auto& g) -> double {
        using G = std::decay_t<decltype(g)>;
        if constexpr (std::is_same_v<G, BoxRegion>) {
          const double lo = std::min(dot(g.lower, u), dot(g.upper, u));
          const double hi = std::max(dot(g.lower, u), dot(g.upper, u));
          const double aligned = std::max({std::fabs(u.x), std::fabs(u.y), std::fabs(u.z)});
          if (aligned < 1.0 - 1e-12)
            throw std::runtime_error("region_volume_below: box needs up along a coordinate axis");
          return region_volume(region) * std::clamp((height - lo) / (hi - lo), 0.0, 1.0);
        } else if constexpr (std::is_same_v<G, CylinderRegion>) {
          const double along = dot(normalized(g.axis), u);
          if (std::fabs(along) < 1.0 - 1e-9)
            throw std::runtime_error("region_volume_below: cylinder axis must be parallel to up");
          const double b0 = dot(g.base_center, u);
          const double lo = std::min(b0, b0 + along * g.length);
          return std::numbers::pi * g.radius * g.radius * std::clamp(height - lo, 0.0, g.length);
        } else {
          const double h = std::min(height - dot(g.base_center, u), g.fill_height);
          return segment_area(g.radius, h) * g.length;
        }
      },
      region);
}

double packed_volume_fraction(const Simulation& s, const Region& region, const Vec3& up) {
  const double bulk = region_volume_below(region, up, bed_height(s, up));
  if (!(bulk > 0.0)) throw std::runtime_error("packed_volume_fraction: the bed lies outside the region");
  return solid_volume(s) / bulk;
}

}  // namespace demfit::dem_core
