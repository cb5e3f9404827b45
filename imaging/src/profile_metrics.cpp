// Profile distances (profile_metrics.hpp): both profiles are piecewise linear in x; on each
// interval between merged breakpoints their difference d(x) is linear, so the integrals of d^2 and
// |d| are taken exactly.
#include "demfit/imaging/profile_metrics.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

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
