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

TEST_CASE("a gap made of a level offset a tilt and an even bump splits into exactly those three parts") {
  // Measured: z_b = 0.01 - 1.2 x on [-L, L]. Simulated: z_b + c + t x + k (|x| - L/2). The three
  // added parts are orthogonal on the symmetric range (|x| - L/2 has zero mean and is even), so the
  // split is exact: level c, tilt RMS |t| L / sqrt(3), shape RMS k L / (2 sqrt(3)).
  const double half = 0.02, c = -0.0012, t = 0.05, k = 0.08;
  const auto measured = [](double x) { return 0.01 - 1.2 * x; };
  const SurfaceProfile b = sampled(-half, half, 21, measured);
  const SurfaceProfile a =
      sampled(-half, half, 41, [&](double x) { return measured(x) + c + t * x + k * (std::abs(x) - 0.5 * half); });
  const ProfileGapParts parts = profile_gap_parts(a, b);
  CHECK(parts.level_offset == Approx(c).epsilon(1e-12));
  CHECK(parts.tilt_rms == Approx(t * half / std::sqrt(3.0)).epsilon(1e-10));
  CHECK(parts.shape_rms == Approx(k * half / (2.0 * std::sqrt(3.0))).epsilon(1e-8));
  CHECK(parts.angle_difference_deg == Approx((std::atan(-1.2 + t) - std::atan(-1.2)) * 180.0 / M_PI).epsilon(1e-10));
  CHECK(parts.rms == Approx(profile_rms_distance(a, b)).epsilon(1e-14));
  CHECK(parts.rms * parts.rms == Approx(parts.level_offset * parts.level_offset + parts.tilt_rms * parts.tilt_rms +
                                        parts.shape_rms * parts.shape_rms)
                                     .epsilon(1e-12));
  // Swapping the profiles flips the level and the angle, not the sizes.
  const ProfileGapParts swapped = profile_gap_parts(b, a);
  CHECK(swapped.level_offset == Approx(-c).epsilon(1e-12));
  CHECK(swapped.angle_difference_deg == Approx(-parts.angle_difference_deg).epsilon(1e-10));
  CHECK(swapped.shape_rms == Approx(parts.shape_rms).epsilon(1e-8));
}

TEST_CASE("a profile in millimetres becomes metres and an unsorted or non-finite one is refused by row") {
  const SurfaceProfile p = profile_from_mm({-20.0, 0.0, 12.5}, {3.0, -1.5, 0.25}, "photo.csv");
  REQUIRE(p.x.size() == 3);
  CHECK(p.x[0] == Approx(-0.020).epsilon(1e-15));
  CHECK(p.x[2] == Approx(0.0125).epsilon(1e-15));
  CHECK(p.z[1] == Approx(-0.0015).epsilon(1e-15));
  CHECK_THROWS_WITH(profile_from_mm({0.0, 2.0, 1.0}, {1.0, 1.0, 1.0}, "photo.csv"),
                    Catch::Contains("photo.csv") && Catch::Contains("row 3") && Catch::Contains("sort"));
  CHECK_THROWS_WITH(profile_from_mm({0.0, 1.0}, {1.0, std::nan("")}, "sim.csv"),
                    Catch::Contains("sim.csv") && Catch::Contains("row 2") && Catch::Contains("finite"));
  CHECK_THROWS_WITH(profile_from_mm({0.0, 1.0}, {1.0}, "sim.csv"), Catch::Contains("differ in length"));
}
