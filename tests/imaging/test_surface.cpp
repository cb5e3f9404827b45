// Free-surface extraction on pictures drawn with a known surface.
#include <catch2/catch.hpp>

#include <cmath>
#include <stdexcept>

#include "demfit/imaging/profile_metrics.hpp"
#include "demfit/imaging/surface.hpp"
#include "drawn_images.hpp"

using namespace demfit::imaging;
using demfit::imaging::test::DrawnDrum;

namespace {
constexpr double kDegree = M_PI / 180.0;
}

TEST_CASE("a straight surface at a known angle is extracted with the angle within 0.5 degrees") {
  const DrawnDrum drum;
  for (double angle : {0.0, 20.0, 35.0, 50.0}) {
    // Bed lifted on the left (clockwise drum as in the GranuDrum photos): dz/dx = -tan(angle).
    const auto surface = [angle](double x) { return 0.002 - std::tan(angle * kDegree) * x; };
    const SurfaceProfile profile =
        extract_surface(test::draw_surface(drum, surface), DrumFrame{drum.diameter}, ProfileOptions{});
    INFO("angle " << angle << " deg");
    REQUIRE(profile.x.size() == 41u);
    const SurfaceLine line = fit_surface_line(profile);
    CHECK(std::abs(-line.angle_deg - angle) < 0.5);
    // Half a pixel: on a level surface every edge pixel has the same grey level, so Otsu's
    // threshold may fall on either side of it (then the edge row counts as material or empty).
    CHECK(test::rms_against(profile, surface) < 0.5 * drum.pixel_size());
  }
}

TEST_CASE("a known S-curve is extracted within one pixel RMS") {
  const DrawnDrum drum;
  // Cascading-like surface: steep in the middle, flattening towards both walls.
  const auto surface = [](double x) { return 0.001 - 0.022 * std::tanh(x / 0.012); };
  const SurfaceProfile profile =
      extract_surface(test::draw_surface(drum, surface), DrumFrame{drum.diameter}, ProfileOptions{});
  REQUIRE(profile.x.size() >= 30u);
  CHECK(test::rms_against(profile, surface) < drum.pixel_size());
  // The curve is not a line: a straight fit leaves a residual of several pixels.
  CHECK(fit_surface_line(profile).residual_rms > 5.0 * drum.pixel_size());
}

TEST_CASE("inverted contrast (light material on dark) gives the same surface") {
  DrawnDrum drum;
  drum.material = 0.9f;
  drum.empty = 0.05f;
  const auto surface = [](double x) { return -0.004 - std::tan(30.0 * kDegree) * x; };
  ProfileOptions options;
  options.material_is_dark = false;
  const SurfaceProfile profile = extract_surface(test::draw_surface(drum, surface), DrumFrame{drum.diameter}, options);
  REQUIRE(profile.x.size() == 41u);
  CHECK(std::abs(-fit_surface_line(profile).angle_deg - 30.0) < 0.5);
  CHECK(test::rms_against(profile, surface) < 0.25 * drum.pixel_size());
  // Read with the photo's default (dark material), the empty part is taken for material: it
  // reaches the top of the circle in every column, so no free surface exists.
  CHECK_THROWS_WITH(extract_surface(test::draw_surface(drum, surface), DrumFrame{drum.diameter}, ProfileOptions{}),
                    Catch::Contains("no free surface"));
}

TEST_CASE("a drawn drum outline inside the margin is ignored, and breaks the extraction without the margin") {
  const DrawnDrum drum;
  const double radius = 0.5 * drum.diameter;
  const auto surface = [](double x) { return 0.003 - std::tan(40.0 * kDegree) * x; };
  GreyImage photo = test::draw_surface(drum, surface);
  test::paint_ring(photo, drum.diameter, 0.94 * radius, 0.99 * radius, 0.1f);                         // dark outline
  test::paint_ring(photo, drum.diameter, 0.99 * radius, 2.0 * radius, 0.6f);                          // grey corners
  const SurfaceProfile profile = extract_surface(photo, DrumFrame{drum.diameter}, ProfileOptions{});  // margin 0.1
  REQUIRE(profile.x.size() == 41u);
  CHECK(std::abs(-fit_surface_line(profile).angle_deg - 40.0) < 0.5);
  CHECK(test::rms_against(profile, surface) < 0.25 * drum.pixel_size());
  for (double x : profile.x) CHECK(std::abs(x) <= profile.compared_radius);
  // With no margin the dark ring joins the bed all round the drum: no column shows a free top.
  ProfileOptions no_margin;
  no_margin.margin = 0.0;
  CHECK_THROWS_WITH(extract_surface(photo, DrumFrame{drum.diameter}, no_margin), Catch::Contains("no free surface"));
}

TEST_CASE("isolated speckles above the bed and light holes inside it do not move the surface") {
  const DrawnDrum drum;
  const auto surface = [](double x) { return -0.002 - std::tan(25.0 * kDegree) * x; };
  GreyImage photo = test::draw_surface(drum, surface);
  const double h = drum.pixel_size();
  // 3 x 3 px dark speckles 3 mm above the surface and light holes 3 mm below it.
  for (double x = -0.03; x <= 0.03; x += 0.004) {
    const int column = static_cast<int>(std::lround((x + 0.5 * drum.diameter) / h));
    for (const auto& [offset, grey] : {std::pair{0.003, drum.material}, std::pair{-0.003, drum.empty}}) {
      const int row = static_cast<int>(std::lround((0.5 * drum.diameter - surface(x) - offset) / h));
      for (int r = row - 1; r <= row + 1; ++r)
        for (int c = column - 1; c <= column + 1; ++c)
          photo.value[static_cast<std::size_t>(r) * drum.pixels + c] = grey;
    }
  }
  const SurfaceProfile profile = extract_surface(photo, DrumFrame{drum.diameter}, ProfileOptions{});
  REQUIRE(profile.x.size() >= 30u);
  CHECK(test::rms_against(profile, surface) < 0.25 * h);
}

TEST_CASE("Otsu's threshold lies halfway between the two grey levels of a two-level picture") {
  const DrawnDrum drum;
  const GreyImage photo = test::draw_surface(drum, [](double x) { return -0.5 * x; });
  // Edge pixels hold intermediate levels; the threshold still falls between the two modes.
  const double threshold = otsu_threshold(photo, 0.1);
  CHECK(threshold > drum.material + 0.2);
  CHECK(threshold < drum.empty - 0.2);
  ProfileOptions given;
  given.threshold = 0.3;
  CHECK(extract_surface(photo, DrumFrame{drum.diameter}, given).threshold_used == 0.3);
}

TEST_CASE("a picture that is all dark or all light has no surface and the error names the image") {
  GreyImage dark;
  dark.width = dark.height = 100;
  dark.source = "dark.png";
  dark.value.assign(100 * 100, 0.05f);
  CHECK_THROWS_WITH(extract_surface(dark, DrumFrame{}, ProfileOptions{}),
                    Catch::Contains("dark.png") && Catch::Contains("single grey level"));
  ProfileOptions fixed;
  fixed.threshold = 0.5;
  CHECK_THROWS_WITH(extract_surface(dark, DrumFrame{}, fixed),
                    Catch::Contains("dark.png") && Catch::Contains("no free surface"));
  GreyImage light = dark;
  light.source = "light.png";
  light.value.assign(100 * 100, 0.95f);
  CHECK_THROWS_WITH(extract_surface(light, DrumFrame{}, fixed),
                    Catch::Contains("light.png") && Catch::Contains("no pixel is material"));
}

TEST_CASE("a non-square or tiny picture and a non-positive diameter are refused with the fix") {
  GreyImage wide;
  wide.width = 120;
  wide.height = 100;
  wide.source = "wide.bmp";
  wide.value.assign(120 * 100, 0.5f);
  CHECK_THROWS_WITH(extract_surface(wide, DrumFrame{}, ProfileOptions{}),
                    Catch::Contains("wide.bmp") && Catch::Contains("square"));
  GreyImage tiny;
  tiny.width = tiny.height = 16;
  tiny.value.assign(16 * 16, 0.5f);
  CHECK_THROWS_WITH(extract_surface(tiny, DrumFrame{}, ProfileOptions{}), Catch::Contains("at least 32"));
  const GreyImage photo = test::draw_surface(DrawnDrum{}, [](double x) { return -0.5 * x; });
  CHECK_THROWS_WITH(extract_surface(photo, DrumFrame{0.0}, ProfileOptions{}), Catch::Contains("diameter"));
  ProfileOptions bad_margin;
  bad_margin.margin = 1.0;
  CHECK_THROWS_WITH(extract_surface(photo, DrumFrame{}, bad_margin), Catch::Contains("margin"));
}
