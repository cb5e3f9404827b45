// Free-surface extractor: recovers known surfaces from designed particle sets, ignores particles
// thrown above the bed, and derives the angle of a plane.
#include <catch2/catch.hpp>

#include <array>
#include <cmath>
#include <functional>
#include <numbers>
#include <vector>

#include "demfit/cases/free_surface.hpp"

using namespace demfit::cases;

namespace {
constexpr double kR = 1.0e-3;

struct ParticleSet {
  std::vector<std::array<double, 3>> positions;
  std::vector<double> radii;
  void add(double x, double y, double z) {
    positions.push_back({x, y, z});
    radii.push_back(kR);
  }
};

// A bed whose silhouette top follows `surface`: columns every r/2 in x, staggered over four
// z-layers (neighbours in one layer touch), each column a stack of touching spheres whose top
// sphere's apex lies on the surface. Projected along z the envelope deviates from the surface by
// at most ~r(1 - sqrt(1 - 1/16)) + |slope| r/4.
ParticleSet bed_under(const std::function<double(double)>& surface, double x_half_width) {
  ParticleSet set;
  const double dx = 0.5 * kR;
  const int columns = static_cast<int>(2.0 * x_half_width / dx) + 1;
  for (int i = 0; i < columns; ++i) {
    const double x = -x_half_width + i * dx;
    const double z = (i % 4) * 2.0 * kR;
    for (double y = surface(x) - kR; y > -0.03; y -= 2.0 * kR) set.add(x, y, z);
  }
  return set;
}
}  // namespace

TEST_CASE("The extracted surface of a bed under an inclined plane recovers the plane") {
  const double slope = 0.3, offset = 0.002;
  auto plane = [&](double x) { return slope * x + offset; };
  ParticleSet bed = bed_under(plane, 0.04);
  SurfaceOptions options{-0.035, 0.035, 29, 0.1};
  const SurfaceProfile profile = extract_free_surface(bed.positions, bed.radii, options);
  const double tolerance = kR * (1.0 - std::sqrt(1.0 - 1.0 / 16.0)) + slope * kR / 4.0 + 1e-9;
  for (std::size_t k = 0; k < profile.x.size(); ++k) {
    REQUIRE(std::isfinite(profile.height[k]));
    CHECK(std::fabs(profile.height[k] - plane(profile.x[k])) <= tolerance);
  }
  // Angle of repose of the plane: atan(0.3) = 16.70 degrees.
  CHECK(repose_angle_degrees(profile, -0.03, 0.03) == Approx(std::atan(slope) * 180.0 / std::numbers::pi).margin(0.5));
}

TEST_CASE("The extracted surface of a curved bed recovers the curve") {
  auto curve = [](double x) { return 0.25 * x + 0.004 * std::sin(x / 0.04 * std::numbers::pi); };
  ParticleSet bed = bed_under(curve, 0.04);
  // Neighbouring stacks are offset vertically by up to r, so their closest spheres are up to
  // sqrt(5) r = 2.24 r apart: connect with a 15 % gap tolerance.
  SurfaceOptions options{-0.035, 0.035, 36, 0.15};
  const SurfaceProfile profile = extract_free_surface(bed.positions, bed.radii, options);
  // Maximum slope of the curve: 0.25 + 0.004 pi / 0.04 = 0.564.
  const double tolerance = kR * (1.0 - std::sqrt(1.0 - 1.0 / 16.0)) + 0.564 * kR / 4.0 + 1e-9;
  for (std::size_t k = 0; k < profile.x.size(); ++k) {
    CHECK(std::fabs(profile.height[k] - curve(profile.x[k])) <= tolerance);
  }
}

TEST_CASE("Particles thrown above the bed, alone or in a small group, do not change the surface") {
  auto plane = [](double x) { return -0.2 * x; };
  ParticleSet bed = bed_under(plane, 0.04);
  const SurfaceOptions options{-0.035, 0.035, 29, 0.1};
  const SurfaceProfile clean = extract_free_surface(bed.positions, bed.radii, options);
  ParticleSet flying = bed;
  flying.add(0.0, 0.02, 0.0);      // a single particle 2 cm above the surface
  flying.add(0.01, 0.015, 0.002);  // a touching pair
  flying.add(0.0115, 0.0165, 0.002);
  const SurfaceProfile with_flyers = extract_free_surface(flying.positions, flying.radii, options);
  REQUIRE(with_flyers.height.size() == clean.height.size());
  for (std::size_t k = 0; k < clean.height.size(); ++k) CHECK(with_flyers.height[k] == clean.height[k]);
  CHECK(largest_cluster(flying.positions, flying.radii, 0.1).size() == bed.positions.size());
}

TEST_CASE("Abscissae no particle covers are NaN and averaging keeps points present in half the profiles") {
  ParticleSet one;
  one.add(0.0, 0.0, 0.0);
  const SurfaceProfile p = extract_free_surface(one.positions, one.radii, {-0.002, 0.002, 5, 0.1});
  CHECK(std::isnan(p.height[0]));
  CHECK(p.height[2] == Approx(kR));
  CHECK(std::isnan(p.height[4]));
  SurfaceProfile a{{0.0, 1.0}, {1.0, std::nan("")}};
  SurfaceProfile b{{0.0, 1.0}, {3.0, 5.0}};
  SurfaceProfile c{{0.0, 1.0}, {2.0, std::nan("")}};
  const SurfaceProfile mean = average_profiles({a, b, c});
  CHECK(mean.height[0] == Approx(2.0));
  CHECK(std::isnan(mean.height[1]));  // present in 1 of 3 profiles only
}
