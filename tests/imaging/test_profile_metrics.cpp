// Profile distances against analytic values (piecewise-linear integrals are exact, so the
// tolerances are round-off: 1e-12 relative).
#include <catch2/catch.hpp>

#include <cmath>
#include <functional>

#include "demfit/imaging/profile_metrics.hpp"

using namespace demfit::imaging;

namespace {

SurfaceProfile sampled(double x0, double x1, int points, const std::function<double(double)>& z) {
  SurfaceProfile p;
  for (int k = 0; k < points; ++k) {
    const double x = x0 + (x1 - x0) * k / (points - 1);
    p.x.push_back(x);
    p.z.push_back(z(x));
  }
  return p;
}

}  // namespace

TEST_CASE("profiles offset by d are d apart in RMS and d times the common chord in area") {
  const double d = 0.0015;
  const auto line = [](double x) { return 0.004 - 0.7 * x; };
  // Different abscissae and ranges: common range [-0.025, 0.03], length 0.055 m.
  const SurfaceProfile a = sampled(-0.03, 0.03, 41, line);
  const SurfaceProfile b = sampled(-0.025, 0.035, 23, [&](double x) { return line(x) + d; });
  CHECK(profile_rms_distance(a, b) == Approx(d).epsilon(1e-12));
  CHECK(profile_differing_area(a, b) == Approx(d * 0.055).epsilon(1e-12));
  CHECK(profile_rms_distance(b, a) == Approx(d).epsilon(1e-12));
}

TEST_CASE("crossing profiles z = s x and z = -s x give 2 s L / sqrt(3) RMS and 2 s L^2 area") {
  const double s = 0.4, half = 0.03;
  // An even number of points: the crossing at x = 0 falls inside an interval.
  const SurfaceProfile a = sampled(-half, half, 40, [s](double x) { return s * x; });
  const SurfaceProfile b = sampled(-half, half, 40, [s](double x) { return -s * x; });
  CHECK(profile_rms_distance(a, b) == Approx(2.0 * s * half / std::sqrt(3.0)).epsilon(1e-12));
  CHECK(profile_differing_area(a, b) == Approx(2.0 * s * half * half).epsilon(1e-12));
}

TEST_CASE("a line fit recovers slope, intercept and a zero residual of a straight profile") {
  const SurfaceProfile p = sampled(-0.02, 0.03, 17, [](double x) { return 0.002 - std::tan(0.6) * x; });
  const SurfaceLine line = fit_surface_line(p);
  CHECK(line.slope == Approx(-std::tan(0.6)).epsilon(1e-12));
  CHECK(line.intercept == Approx(0.002).epsilon(1e-10));
  CHECK(line.angle_deg == Approx(-0.6 * 180.0 / M_PI).epsilon(1e-12));
  CHECK(line.residual_rms < 1e-12);
}

TEST_CASE("profiles without a common x-range or with fewer than two points cannot be compared") {
  const SurfaceProfile left = sampled(-0.03, -0.01, 5, [](double) { return 0.0; });
  const SurfaceProfile right = sampled(0.0, 0.02, 5, [](double) { return 0.0; });
  CHECK_THROWS_WITH(profile_rms_distance(left, right), Catch::Contains("no x-range"));
  SurfaceProfile single;
  single.x = {0.0};
  single.z = {0.0};
  CHECK_THROWS_WITH(profile_differing_area(left, single), Catch::Contains("fewer than 2 points"));
}
