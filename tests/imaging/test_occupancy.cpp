// The simulated side: discs projected into an occupancy image, then the same surface extraction.
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include "demfit/imaging/occupancy.hpp"
#include "demfit/imaging/profile_metrics.hpp"

using namespace demfit::imaging;

namespace {

constexpr double kDiameter = 0.084;

// Discs of radius r with centres on a square grid of pitch s (s << r) filling the drum below
// z_top - r: their union is flat-topped at z_top to within s^2 / (8 r) (here 0.008 mm).
struct DiscBed {
  std::vector<double> x, z, radius;
};
DiscBed flat_topped_bed(double z_top) {
  const double r = 0.001, s = 0.00025, wall = 0.5 * kDiameter;
  DiscBed bed;
  for (double zc = z_top - r; zc > -wall; zc -= s)
    for (double xc = -wall; xc <= wall; xc += s)
      if (std::hypot(xc, zc) < wall - r) {
        bed.x.push_back(xc);
        bed.z.push_back(zc);
        bed.radius.push_back(r);
      }
  return bed;
}

SurfaceProfile extract(const OccupancyAccumulator& accumulator) {
  return extract_surface(accumulator.occupancy(), DrumFrame{kDiameter}, occupancy_profile_options(ProfileOptions{}));
}

double mean_height(const SurfaceProfile& p) {
  double sum = 0.0;
  for (double z : p.z) sum += z;
  return sum / static_cast<double>(p.z.size());
}

}  // namespace

TEST_CASE("discs whose union has a flat top give that height within a pixel") {
  const int pixels = 200;
  const double h = kDiameter / (pixels - 1);
  const double z_top = 0.0053;
  OccupancyAccumulator accumulator(DrumFrame{kDiameter}, pixels);
  const DiscBed bed = flat_topped_bed(z_top);
  accumulator.add_snapshot(bed.x, bed.z, bed.radius);
  const SurfaceProfile profile = extract(accumulator);
  REQUIRE(profile.x.size() >= 30u);
  for (std::size_t i = 0; i < profile.z.size(); ++i) {
    INFO("x = " << profile.x[i]);
    CHECK(std::abs(profile.z[i] - z_top) < h);
  }
  CHECK(std::abs(fit_surface_line(profile).angle_deg) < 0.5);
  // Covered pixels are 1, empty ones 0: threshold 0.5 is occupancy 0.5.
  CHECK(equivalent_occupancy(profile) == Approx(0.5));
}

TEST_CASE("occupancy is the fraction of snapshots covering a pixel and the surface follows the majority") {
  const int pixels = 120;
  const double h = kDiameter / (pixels - 1);
  const DiscBed high = flat_topped_bed(0.008), low = flat_topped_bed(-0.006);
  OccupancyAccumulator mostly_high(DrumFrame{kDiameter}, pixels), mostly_low(DrumFrame{kDiameter}, pixels);
  mostly_high.add_snapshot(high.x, high.z, high.radius);
  mostly_high.add_snapshot(high.x, high.z, high.radius);
  mostly_high.add_snapshot(low.x, low.z, low.radius);
  mostly_low.add_snapshot(high.x, high.z, high.radius);
  mostly_low.add_snapshot(low.x, low.z, low.radius);
  mostly_low.add_snapshot(low.x, low.z, low.radius);
  REQUIRE(mostly_high.snapshots() == 3);
  // The pixel on the axis at z = 0 is covered by the high bed only: 2 of 3 and 1 of 3 snapshots.
  const int centre = (pixels - 1) / 2;
  const std::size_t k = static_cast<std::size_t>(centre) * pixels + centre;
  CHECK(mostly_high.occupancy().value[k] == Approx(2.0 / 3.0));
  CHECK(mostly_low.occupancy().value[k] == Approx(1.0 / 3.0));
  CHECK(std::abs(mean_height(extract(mostly_high)) - 0.008) < h);
  CHECK(std::abs(mean_height(extract(mostly_low)) + 0.006) < h);
}

TEST_CASE("occupancy accumulator refuses bad sizes and reading before any snapshot") {
  CHECK_THROWS_WITH(OccupancyAccumulator(DrumFrame{0.0}, 100), Catch::Contains("diameter"));
  CHECK_THROWS_WITH(OccupancyAccumulator(DrumFrame{kDiameter}, 8), Catch::Contains("at least 32"));
  OccupancyAccumulator accumulator(DrumFrame{kDiameter}, 64);
  CHECK_THROWS_WITH(accumulator.occupancy(), Catch::Contains("no snapshot"));
  CHECK_THROWS_WITH(accumulator.add_snapshot({0.0, 0.01}, {0.0}, {0.001, 0.001}), Catch::Contains("different lengths"));
  CHECK_THROWS_WITH(accumulator.add_snapshot({0.0}, {std::nan("")}, {0.001}), Catch::Contains("particle 0"));
}
