// Profile distances (profile_metrics.hpp): both profiles are piecewise linear in x; on each
// interval between merged breakpoints their difference d(x) is linear, so the integrals of d^2 and
// |d| are taken exactly.
#include "demfit/imaging/profile_metrics.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace demfit::imaging {
namespace {

double interpolate(const SurfaceProfile& p, double x) {
  const auto upper = std::upper_bound(p.x.begin(), p.x.end(), x);
  if (upper == p.x.begin()) return p.z.front();
  if (upper == p.x.end()) return p.z.back();
  const std::size_t i = static_cast<std::size_t>(upper - p.x.begin());
  const double w = (x - p.x[i - 1]) / (p.x[i] - p.x[i - 1]);
  return (1.0 - w) * p.z[i - 1] + w * p.z[i];
}

void check_profile(const SurfaceProfile& p, const char* which) {
  if (p.x.size() < 2 || p.x.size() != p.z.size())
    throw std::runtime_error(std::string("profile ") + which +
                             " has fewer than 2 points (or x and z differ in length); extract a surface first");
}

// Merged breakpoints of a and b inside their common x-range, and the difference a - b at each.
void merged_differences(const SurfaceProfile& a, const SurfaceProfile& b, std::vector<double>& x,
                        std::vector<double>& d) {
  check_profile(a, "a");
  check_profile(b, "b");
  const double lo = std::max(a.x.front(), b.x.front()), hi = std::min(a.x.back(), b.x.back());
  if (!(hi > lo))
    throw std::runtime_error("the two profiles share no x-range; compare profiles of the same drum frame");
  x = {lo, hi};
  for (const SurfaceProfile* p : {&a, &b})
    for (double xi : p->x)
      if (xi > lo && xi < hi) x.push_back(xi);
  std::sort(x.begin(), x.end());
  x.erase(std::unique(x.begin(), x.end()), x.end());
  d.resize(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) d[i] = interpolate(a, x[i]) - interpolate(b, x[i]);
}

}  // namespace

double profile_rms_distance(const SurfaceProfile& a, const SurfaceProfile& b) {
  std::vector<double> x, d;
  merged_differences(a, b, x, d);
  double integral = 0.0;
  for (std::size_t i = 0; i + 1 < x.size(); ++i)
    integral += (x[i + 1] - x[i]) * (d[i] * d[i] + d[i] * d[i + 1] + d[i + 1] * d[i + 1]) / 3.0;
  return std::sqrt(integral / (x.back() - x.front()));
}

double profile_differing_area(const SurfaceProfile& a, const SurfaceProfile& b) {
  std::vector<double> x, d;
  merged_differences(a, b, x, d);
  double area = 0.0;
  for (std::size_t i = 0; i + 1 < x.size(); ++i) {
    const double length = x[i + 1] - x[i], d0 = d[i], d1 = d[i + 1];
    if (d0 * d1 >= 0.0) {
      area += 0.5 * length * std::abs(d0 + d1);
    } else {  // the surfaces cross inside the interval: two triangles
      area += 0.5 * length * (d0 * d0 + d1 * d1) / (std::abs(d0) + std::abs(d1));
    }
  }
  return area;
}

ProfileGapParts profile_gap_parts(const SurfaceProfile& a, const SurfaceProfile& b) {
  std::vector<double> x, d;
  merged_differences(a, b, x, d);
  // Moments over the common range; every integrand is at most quadratic on an interval (x, z_a,
  // z_b linear there), so Simpson's rule is exact.
  double length = 0.0, sum_x = 0.0, sum_xx = 0.0, sum_d = 0.0, sum_xd = 0.0, sum_dd = 0.0, sum_xa = 0.0, sum_a = 0.0;
  for (std::size_t i = 0; i + 1 < x.size(); ++i) {
    const double h = x[i + 1] - x[i], xm = 0.5 * (x[i] + x[i + 1]), dm = 0.5 * (d[i] + d[i + 1]);
    const double a0 = interpolate(a, x[i]), a1 = interpolate(a, x[i + 1]), am = 0.5 * (a0 + a1);
    const auto simpson = [h](double f0, double fm, double f1) { return h * (f0 + 4.0 * fm + f1) / 6.0; };
    length += h;
    sum_x += h * xm;
    sum_xx += simpson(x[i] * x[i], xm * xm, x[i + 1] * x[i + 1]);
    sum_d += h * dm;
    sum_xd += simpson(x[i] * d[i], xm * dm, x[i + 1] * d[i + 1]);
    sum_dd += simpson(d[i] * d[i], dm * dm, d[i + 1] * d[i + 1]);
    sum_a += h * am;
    sum_xa += simpson(x[i] * a0, xm * am, x[i + 1] * a1);
  }
  const double mean_x = sum_x / length, variance_x = sum_xx / length - mean_x * mean_x;
  ProfileGapParts parts;
  parts.level_offset = sum_d / length;
  const double gap_slope = (sum_xd / length - mean_x * parts.level_offset) / variance_x;
  const double slope_a = (sum_xa / length - mean_x * sum_a / length) / variance_x;
  parts.angle_difference_deg = (std::atan(slope_a) - std::atan(slope_a - gap_slope)) * 180.0 / M_PI;
  const double mean_square = sum_dd / length;
  parts.rms = std::sqrt(mean_square);
  parts.tilt_rms = std::abs(gap_slope) * std::sqrt(variance_x);
  const double shape_square = mean_square - parts.level_offset * parts.level_offset - parts.tilt_rms * parts.tilt_rms;
  parts.shape_rms = std::sqrt(std::max(0.0, shape_square));  // round-off can leave -1e-20
  return parts;
}

SurfaceProfile profile_from_mm(const std::vector<double>& x_mm, const std::vector<double>& z_mm,
                               const std::string& source) {
  if (x_mm.size() != z_mm.size())
    throw std::runtime_error(source + ": x_mm and z_mm differ in length; give one height per abscissa");
  SurfaceProfile profile;
  for (std::size_t i = 0; i < x_mm.size(); ++i) {
    const std::string row = " (row " + std::to_string(i + 1) + ")";
    if (!std::isfinite(x_mm[i]) || !std::isfinite(z_mm[i]))
      throw std::runtime_error(source + ": a value is not a finite number" + row +
                               "; give numbers in mm in both columns");
    if (i > 0 && !(x_mm[i] > x_mm[i - 1]))
      throw std::runtime_error(source + ": x_mm must increase from row to row" + row + "; sort the profile by x");
    profile.x.push_back(1e-3 * x_mm[i]);  // mm -> m: the profile metrics work in SI units
    profile.z.push_back(1e-3 * z_mm[i]);
  }
  return profile;
}

SurfaceLine fit_surface_line(const SurfaceProfile& profile) {
  check_profile(profile, "to fit");
  const double n = static_cast<double>(profile.x.size());
  double mx = 0.0, mz = 0.0;
  for (std::size_t i = 0; i < profile.x.size(); ++i) {
    mx += profile.x[i] / n;
    mz += profile.z[i] / n;
  }
  double sxx = 0.0, sxz = 0.0;
  for (std::size_t i = 0; i < profile.x.size(); ++i) {
    sxx += (profile.x[i] - mx) * (profile.x[i] - mx);
    sxz += (profile.x[i] - mx) * (profile.z[i] - mz);
  }
  SurfaceLine line;
  line.slope = sxz / sxx;
  line.intercept = mz - line.slope * mx;
  line.angle_deg = std::atan(line.slope) * 180.0 / M_PI;
  double squares = 0.0;
  for (std::size_t i = 0; i < profile.x.size(); ++i) {
    const double r = profile.z[i] - (line.intercept + line.slope * profile.x[i]);
    squares += r * r;
  }
  line.residual_rms = std::sqrt(squares / n);
  return line;
}

}  // namespace demfit::imaging
