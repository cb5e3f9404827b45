#pragma once
// Automatic extraction of the free surface of a granular bed in a drum cross-section
// (docs/spec.md 2.2 `free_surface`; the paper extracted its target by hand, Fig. 7).
//
// Frame: the drum axis is the z axis through the origin, gravity points along -y; the profile is
// height y [m] as a function of the horizontal coordinate x [m] in the cross-section (all
// particles are projected along z).
//
// Method (documented in docs/cases.md):
//  1. The bed is the largest connected cluster of particles, two particles being connected when
//     their gap is below `contact_tolerance` times the sum of their radii. Particles thrown above
//     the bed (single or small groups) form other clusters and are ignored.
//  2. The surface at abscissa x is the top of the bed's silhouette: the maximum over bed particles
//     with |x - x_p| < r_p of y_p + sqrt(r_p^2 - (x - x_p)^2). This is exact for any sampling
//     density and does not depend on a column width tied to the particle size, so models with
//     different radii (coarse graining) are sampled on the same abscissae.
//  3. Several snapshots (a short window before the output time) may be averaged point by point.
#include <array>
#include <functional>
#include <vector>

namespace demfit::cases {

struct SurfaceOptions {
  double x_min = -0.05;            // first abscissa [m]
  double x_max = 0.05;             // last abscissa [m]
  int points = 41;                 // number of equally spaced abscissae (>= 2)
  double contact_tolerance = 0.1;  // connected when distance < (1 + tol)(r_i + r_j)
};

// Height of the surface [m] at each abscissa [m]; NaN where no bed particle covers x.
struct SurfaceProfile {
  std::vector<double> x;
  std::vector<double> height;
};

// Calls visit(i, j), i < j, for every pair closer than (1 + contact_tolerance)(r_i + r_j), through a
// cell grid (cost ~ N); pairs in a deterministic order.
void for_each_close_pair(const std::vector<std::array<double, 3>>& positions, const std::vector<double>& radii,
                         double contact_tolerance, const std::function<void(int, int)>& visit);

// Indices of the particles of the largest connected cluster (sorted ascending).
std::vector<int> largest_cluster(const std::vector<std::array<double, 3>>& positions, const std::vector<double>& radii,
                                 double contact_tolerance);

SurfaceProfile extract_free_surface(const std::vector<std::array<double, 3>>& positions,
                                    const std::vector<double>& radii, const SurfaceOptions& options);

// Point-by-point mean of profiles sampled on the same abscissae; a point is kept (finite) when
// at least half of the profiles have it. Throws if the abscissae differ.
SurfaceProfile average_profiles(const std::vector<SurfaceProfile>& profiles);

// Dynamic angle of repose [degrees]: least-squares line through the finite profile points with
// x in [x_low, x_high]; returns atan(|slope|). NaN when fewer than 2 points.
double repose_angle_degrees(const SurfaceProfile& profile, double x_low, double x_high);

}  // namespace demfit::cases
