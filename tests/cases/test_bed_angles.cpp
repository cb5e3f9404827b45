// The named angle definitions (cases/bed_angles.hpp) on beds whose surface angle is known by
// construction: spheres filling the drum below a straight line.
#include <catch2/catch.hpp>

#include <array>
#include <cmath>
#include <numbers>
#include <vector>

#include "demfit/cases/bed_angles.hpp"
#include "demfit/cases/free_surface.hpp"

using namespace demfit::cases;

namespace {

constexpr double kDiameter = 0.1, kLength = 0.02, kRadius = 0.001;

struct Bed {
  std::vector<std::array<double, 3>> positions;
  std::vector<double> radii;
};

// Columns of spheres one radius apart in x (overlapping neighbours, as in a dense packing seen from
// the side), two radii apart in y and z, each column's top sphere touching the line
// y = tan(angle) x + offset from below, cut by the drum wall: the bed's crowns lie on that line.
Bed line_topped_bed(double angle_deg, double offset) {
  Bed bed;
  const double slope = std::tan(angle_deg * std::numbers::pi / 180.0);
  const int columns = static_cast<int>(0.5 * kDiameter / kRadius);
  for (int i = -columns; i <= columns; ++i) {
    const double x = i * kRadius;
    for (double y = slope * x + offset - kRadius; y > -0.5 * kDiameter; y -= 2.0 * kRadius)
      for (double z = kRadius; z + kRadius <= kLength + 1e-12; z += 2.0 * kRadius) {
        if (std::hypot(x, y) + kRadius > 0.5 * kDiameter) continue;
        bed.positions.push_back({x, y, z});
        bed.radii.push_back(kRadius);
      }
  }
  return bed;
}

double cluster_angle(const Bed& bed) {
  SurfaceOptions options;
  options.x_min = -0.5 * kDiameter;
  options.x_max = 0.5 * kDiameter;
  options.points = 201;
  return repose_angle_degrees(extract_free_surface(bed.positions, bed.radii, options), -0.25 * kDiameter,
                              0.25 * kDiameter);
}

}  // namespace

TEST_CASE("Each angle definition recovers the slope of a bed cut by a straight line within 1.5 degrees",
          "[bed_angles]") {
  for (double angle : {20.0, 35.0, 50.0}) {
    const Bed bed = line_topped_bed(angle, 0.0);
    INFO("construction angle " << angle << " deg");
    CHECK(cluster_angle(bed) == Approx(angle).margin(1.5));
    CHECK(slab_surface_angle_degrees(bed.positions, bed.radii, kLength) == Approx(angle).margin(1.5));
    CHECK(instrument_angle_degrees(bed.positions, bed.radii, kDiameter, kLength) == Approx(angle).margin(1.5));
  }
}

TEST_CASE("The slab definition ignores particles thrown above the bed", "[bed_angles]") {
  Bed bed = line_topped_bed(35.0, 0.0);
  const double before = slab_surface_angle_degrees(bed.positions, bed.radii, kLength);
  // Two lone particles high above the left half, at mid depth: fewer than 3 neighbours each.
  for (double x : {-0.02, -0.01}) {
    bed.positions.push_back({x, 0.04, 0.5 * kLength});
    bed.radii.push_back(kRadius);
  }
  CHECK(slab_surface_angle_degrees(bed.positions, bed.radii, kLength) == before);
}

TEST_CASE("The instrument angle is not defined when the surface passes outside the central circle of diameter D/5",
          "[bed_angles]") {
  // A 30 % filled drum: the surface lies 0.3 R = 15 mm from the centre, beyond D/10 = 10 mm.
  const Bed low = line_topped_bed(30.0, -0.015 / std::cos(30.0 * std::numbers::pi / 180.0));
  CHECK(std::isnan(instrument_angle_degrees(low.positions, low.radii, kDiameter, kLength)));
  CHECK(slab_surface_angle_degrees(low.positions, low.radii, kLength) == Approx(30.0).margin(1.5));
}

TEST_CASE("A line fit through exact points gives the angle of their slope", "[bed_angles]") {
  const std::vector<double> x = {-2.0, -1.0, 0.5, 3.0};
  std::vector<double> y;
  for (double v : x) y.push_back(-0.75 * v + 4.0);
  CHECK(line_fit_angle_degrees(x, y) == Approx(std::atan(0.75) * 180.0 / std::numbers::pi).epsilon(1e-12));
  CHECK(std::isnan(line_fit_angle_degrees({1.0}, {2.0})));
  CHECK(std::isnan(line_fit_angle_degrees({1.0, 1.0}, {2.0, 3.0})));
}

TEST_CASE("The instrument angle of a drum many thousand radii across is sampled on a capped grid, not refused",
          "[bed_angles]") {
  // D / r = 100,000: half a radius per cell would be 200,000 cells a side (3 x 320 GB of doubles).
  const std::vector<std::array<double, 3>> positions = {{0.0, -0.01, 0.01}, {0.001, -0.01, 0.01}};
  const std::vector<double> radii = {1e-6, 1e-6};
  double angle = 0.0;
  CHECK_NOTHROW(angle = instrument_angle_degrees(positions, radii, kDiameter, kLength));
  CHECK(std::isnan(angle));  // two specks: no contour inside the central circle
}
