#pragma once
// Dynamic angle of a drum bed by named definitions. The angle a user compares depends on how the
// surface is found and which part of it is fitted: on the Hertz anchor drum the definitions below
// differ by 4-5 degrees on the same bed, more than the tolerance of a calibration check. So every
// angle demfit prints carries the name of its definition (docs/cases.md, "Angle definitions").
//
// Frame (as free_surface.hpp): drum axis = z from 0 to the drum length, centre of the section at
// x = y = 0, gravity along -y. Positions and radii in metres; angles in degrees, atan(|slope|).
#include <array>
#include <string_view>
#include <vector>

namespace demfit::cases {

// "cluster surface": the silhouette of the largest connected cluster (free_surface.hpp), line fit
// over |x| < R/2: the definition of the `free_surface` curve and of the drum summary's first angle.
inline constexpr std::string_view kClusterSurfaceAngleName = "cluster surface, line fit over |x| < R/2";

// "mid-depth slab": particles whose centre lies within two mean radii of the mid-depth plane and
// that touch at least 3 others (gap below 10 % of the radii sum, so lone bouncing particles are
// out); per bin of four mean radii in x, the highest centre + radius; line through the bins in the
// middle 60 % of the chord they span. The way a surface is read off a LIGGGHTS dump by hand.
inline constexpr std::string_view kSlabSurfaceAngleName =
    "mid-depth slab, particles with >= 3 neighbours, top per 4-radius bin, line over the middle 60 % of the chord";
double slab_surface_angle_degrees(const std::vector<std::array<double, 3>>& positions,
                                  const std::vector<double>& radii, double drum_length);

// "GranuDrum instrument": the instrument photographs the drum through its transparent end walls,
// so it sees the depth-averaged solid fraction. phi(x, y) = sum over particles of the chord
// 2 sqrt(r^2 - d^2) through the sphere at in-plane distance d, divided by the drum length, on a
// grid of half a mean radius, smoothed by a Gaussian of one mean radius (a single snapshot stands
// in for the instrument's average over many photos). The interface is the contour at half the
// maximum of phi, found per column from the top; the angle is the line fitted to the contour
// points inside the circle of diameter D/5 around the drum centre. NaN when fewer than 3 contour
// points lie in that circle (a bed whose surface passes more than D/10 from the centre).
inline constexpr std::string_view kInstrumentAngleName =
    "GranuDrum instrument, half-maximum depth-averaged solid-fraction contour inside the central circle of "
    "diameter D/5, line fit";
double instrument_angle_degrees(const std::vector<std::array<double, 3>>& positions, const std::vector<double>& radii,
                                double drum_diameter, double drum_length);

// Least-squares line through (x, y) points; atan(|slope|) in degrees, NaN for fewer than 2 points
// or all x equal.
double line_fit_angle_degrees(const std::vector<double>& x, const std::vector<double>& y);

}  // namespace demfit::cases
