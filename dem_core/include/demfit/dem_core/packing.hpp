#pragma once
// Packing generator and settling helper (the paper's "packed particle generation +
// densification"). Generation places non-overlapping spheres on a jittered cubic lattice inside a
// region, lowest sites first (so little settling is needed), fully seeded: std::mt19937_64 with
// our own uniform mapping (std distributions are implementation-defined).
#include <cstdint>
#include <functional>
#include <variant>
#include <vector>

#include "demfit/dem_core/vec3.hpp"

namespace demfit::dem_core {

class Simulation;

/// Axis-aligned box [m].
struct BoxRegion {
  Vec3 lower{};
  Vec3 upper{};
};
/// Cylinder interior: base centre, unit axis, radius, length along the axis [m].
struct CylinderRegion {
  Vec3 base_center{};
  Vec3 axis{0, 0, 1};
  double radius = 0.0;
  double length = 0.0;
};
/// Part of a (horizontal) cylinder below a fill level: the points of the cylinder (axis from
/// `base_center` along unit `axis`, radius, length) with (x - base_center)·up <= fill_height.
/// fill_height is measured from the axis: -radius = empty, 0 = half full, +radius = full.
/// `up` must be perpendicular to `axis`.
struct DrumSegmentRegion {
  Vec3 base_center{};
  Vec3 axis{0, 1, 0};
  double radius = 0.0;
  double length = 0.0;
  Vec3 up{0, 0, 1};
  double fill_height = 0.0;
};
using Region = std::variant<BoxRegion, CylinderRegion, DrumSegmentRegion>;

/// Region volume [m^3].
double region_volume(const Region& region);
/// True when the sphere (centre, radius) lies entirely inside the region.
bool region_contains(const Region& region, const Vec3& center, double radius);
/// Fill level of a drum segment whose bulk volume is `fraction` of the full cylinder (bisection on
/// the circular-segment area), measured from the axis as DrumSegmentRegion::fill_height.
double drum_fill_height(double radius, double fraction);

struct PackingRequest {
  Region region{};
  double radius_min = 0.0;  ///< [m]; radii uniform in [radius_min, radius_max] (equal = monodisperse)
  double radius_max = 0.0;  ///< [m]
  /// Polydispersity (effects library): relative radius spread s in [0, 0.9]; 0 = off. When > 0,
  /// radius_min must equal radius_max = R (the nominal radius) and the radii are uniform in
  /// [R(1 - s), R(1 + s)] (uniform rather than a truncated normal: the bounds are exact, so the
  /// lattice spacing and the stable step are known, and the spread has one meaning). The mean
  /// sphere volume is R^3 (1 + s^2) (mean_volume_factor): a solid_volume request (count = 0)
  /// therefore keeps the solid volume, hence the volume fraction, and places fewer spheres.
  double radius_spread = 0.0;
  std::size_t count = 0;      ///< number of spheres; 0 = use solid_volume
  double solid_volume = 0.0;  ///< [m^3] target total sphere volume when count == 0
  std::uint64_t seed = 1;
  Vec3 up{0, 0, 1};  ///< sites are filled from the lowest (along up) upwards
  double gap = 0.2;  ///< lattice spacing = 2 radius_max (1 + gap); jitter uses the free gap
  /// Explicit radii [m] (a sampled size distribution), placed in this order on the lowest sites;
  /// when not empty it replaces radius_min/max/spread and count/solid_volume (count = size).
  /// The sites are those of a monodisperse packing of the largest radius (same random draws per
  /// site), so no two spheres can overlap whatever the order.
  std::vector<double> radii{};
  /// Lattice of the sites: simple cubic (the historic default) or face-centred cubic, whose
  /// nearest-neighbour distance is the same 2 radius_max (1 + gap) but which holds sqrt(2) times
  /// more sites per volume (a broad size distribution needs them: the site is sized by the
  /// largest sphere).
  enum class Lattice { cubic, fcc } lattice = Lattice::cubic;
};

struct Packing {
  std::vector<Vec3> centers{};   ///< [m]
  std::vector<double> radii{};   ///< [m]
  double solid_volume = 0.0;     ///< [m^3]
  double volume_fraction = 0.0;  ///< solid_volume / region_volume
  std::size_t capacity = 0;      ///< lattice sites that fitted in the region
};

/// E[r^3]/R^3 = 1 + s^2 for radii uniform in [R(1 - s), R(1 + s)] (relative spread s).
double mean_volume_factor(double radius_spread);

/// Throws std::runtime_error (naming count/solid_volume and the capacity) when the region cannot
/// hold the request at this gap.
Packing generate_packing(const PackingRequest& request);
/// Add the packing's spheres to the simulation with the given material (zero velocity).
void add_packing(Simulation& simulation, const Packing& packing, std::size_t material = 0);

struct SettleOptions {
  double max_time = 2.0;  ///< [s] simulated time limit
  /// Stop when kinetic energy < tolerance * sum(m |g| R) (i.e. typical speed ~ sqrt(2 tol g R)).
  double kinetic_energy_tolerance = 1.0e-5;
  double min_time = 0.05;         ///< [s] do not stop before (the bed must first fall)
  double check_interval = 0.005;  ///< [s] between convergence checks
  /// Densification: settle with particle and wall friction (and rolling) set to zero, then
  /// restore them and settle again for `refriction_time`; gives a denser (near random close)
  /// packing, as the paper's densification stage.
  bool frictionless = false;
  double refriction_time = 0.05;  ///< [s]
  /// Called after every convergence check with the simulated time spent settling and max_time
  /// [s], so a long settle shows progress. May be empty.
  std::function<void(double elapsed, double max_time)> progress = {};
};

struct SettleReport {
  double simulated_time = 0.0;  ///< [s] spent settling
  std::uint64_t steps = 0;
  double kinetic_energy = 0.0;  ///< [J] at the end
  bool converged = false;       ///< kinetic-energy criterion met before max_time
};

SettleReport settle(Simulation& simulation, const SettleOptions& options = {});

/// Bed surface height along `up` [m]: mean of (x·up + R) over the highest `top_fraction` of the
/// particles (at least one).
double bed_height(const Simulation& simulation, const Vec3& up, double top_fraction = 0.05);
/// Total sphere volume [m^3].
double solid_volume(const Simulation& simulation);
/// Bulk volume [m^3] of the region below height h along up. Supported: box with up along a
/// coordinate axis, cylinder with axis parallel to up, drum segment (axis perpendicular to up).
double region_volume_below(const Region& region, const Vec3& up, double height);
/// Achieved volume fraction: solid volume of the particles / region_volume_below(bed height).
double packed_volume_fraction(const Simulation& simulation, const Region& region, const Vec3& up);

}  // namespace demfit::dem_core
