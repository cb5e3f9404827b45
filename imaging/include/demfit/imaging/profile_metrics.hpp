#pragma once
// Distances between two free-surface profiles (drum frame, metres). Both are read as piecewise
// linear functions z(x) and compared on their common x-range [max(a.x0, b.x0), min(a.xn, b.xn)];
// the integrals are exact for piecewise linear functions (breakpoints of both profiles merged).
#include <string>
#include <vector>

#include "demfit/imaging/surface.hpp"

namespace demfit::imaging {

// sqrt( (1/L) * integral (z_a - z_b)^2 dx ) over the common range of length L [m].
// Throws std::runtime_error when the profiles have fewer than 2 points or no common range.
double profile_rms_distance(const SurfaceProfile& a, const SurfaceProfile& b);

// integral |z_a - z_b| dx over the common range [m^2]: the area between the two surfaces, i.e. the
// source's differing-pixel-area metric for single-valued surfaces inside the compared circle
// (pixels beyond the common x-range are not counted). Same errors as profile_rms_distance.
double profile_differing_area(const SurfaceProfile& a, const SurfaceProfile& b);

// The gap a - b split into three orthogonal parts over the common range (L2 projection onto 1 and
// x): RMS^2 = level_offset^2 + tilt^2 + shape_rms^2, where tilt is the RMS of the gap's linear
// trend. Why: a drum study that shares one fill between experiments can move every experiment's
// level together, not one against another; telling a level difference from a wrong angle or a
// wrong shape says which of them the calibration can still reach. Same errors as
// profile_rms_distance.
struct ProfileGapParts {
  double rms = 0.0;                   // [m] profile_rms_distance(a, b)
  double level_offset = 0.0;          // [m] mean of z_a - z_b (a above b when > 0)
  double angle_difference_deg = 0.0;  // atan(slope_a) - atan(slope_b), least-squares slopes on the common range
  double tilt_rms = 0.0;              // [m] RMS of the gap's least-squares linear trend (mean removed)
  double shape_rms = 0.0;             // [m] RMS of the gap left after removing its mean and linear trend
};
ProfileGapParts profile_gap_parts(const SurfaceProfile& a, const SurfaceProfile& b);

// A profile given in millimetres (the x_mm, z_mm curves of `demfit target from-image` and of the
// drum cases) as a SurfaceProfile in metres, for the comparisons above. `source` names the curve
// in errors. Throws std::runtime_error (one line naming the source, the row and the fix) when the
// columns differ in length, a value is not finite, or x does not increase from row to row.
SurfaceProfile profile_from_mm(const std::vector<double>& x_mm, const std::vector<double>& z_mm,
                               const std::string& source);

// Least-squares line z = intercept + slope x through the profile points.
struct SurfaceLine {
  double slope = 0.0;         // dz/dx [-]
  double intercept = 0.0;     // [m] height at the axis
  double angle_deg = 0.0;     // atan(slope) in degrees: negative when the bed is lifted on the left
  double residual_rms = 0.0;  // [m] RMS of z - line
};
SurfaceLine fit_surface_line(const SurfaceProfile& profile);

}  // namespace demfit::imaging
