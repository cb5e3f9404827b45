// The overlay picture: the profile is drawn in red where the profile is, the compared circle in
// blue, the rest is the photo in grey.
#include <catch2/catch.hpp>

#include <cmath>

#include "demfit/imaging/overlay.hpp"
#include "drawn_images.hpp"

using namespace demfit::imaging;

TEST_CASE("the overlay shows the profile in red at its pixels and the compared circle in blue") {
  const test::DrawnDrum drum;
  const GreyImage photo = test::draw_surface(drum, [](double x) { return 0.002 - 0.7 * x; });
  const SurfaceProfile profile = extract_surface(photo, DrumFrame{drum.diameter}, ProfileOptions{});
  const RgbImage overlay = draw_overlay(photo, DrumFrame{drum.diameter}, profile);
  REQUIRE(overlay.width == photo.width);
  REQUIRE(overlay.height == photo.height);
  const auto pixel = [&](double x, double z) {
    const int column = static_cast<int>(std::lround((x + 0.5 * drum.diameter) / drum.pixel_size()));
    const int row = static_cast<int>(std::lround((0.5 * drum.diameter - z) / drum.pixel_size()));
    return &overlay.rgb[3 * (static_cast<std::size_t>(row) * overlay.width + column)];
  };
  for (std::size_t i = 0; i < profile.x.size(); ++i) {
    const std::uint8_t* p = pixel(profile.x[i], profile.z[i]);
    CHECK(p[0] > 200);
    CHECK(p[1] < 50);
  }
  const std::uint8_t* circle = pixel(0.0, -profile.compared_radius);
  CHECK(circle[2] > 200);
  CHECK(circle[0] < 100);
  const std::uint8_t* bed = pixel(0.0, -0.02);  // inside the bed, away from the lines: grey
  CHECK(bed[0] == bed[1]);
  CHECK(bed[1] == bed[2]);
}
