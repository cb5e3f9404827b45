// The real GranuDrum MCC photos shipped in data/granudrum_mcc (GPL-3.0 measurements): both give a
// profile; 15 rpm (rolling) is nearly straight, 45 rpm (cascading) S-shaped; the bed is lifted on
// the left (the drum turns clockwise as seen in the photos).
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>

#include "demfit/imaging/image.hpp"
#include "demfit/imaging/profile_metrics.hpp"
#include "demfit/imaging/surface.hpp"

using namespace demfit::imaging;

namespace {

SurfaceProfile photo_profile(const std::string& name) {
  const GreyImage photo = read_grey_image(std::filesystem::path(DEMFIT_SOURCE_DIR) / "data" / "granudrum_mcc" / name);
  REQUIRE(photo.width == 406);
  REQUIRE(photo.height == 406);
  return extract_surface(photo, DrumFrame{0.084}, ProfileOptions{});
}

}  // namespace

TEST_CASE("the GranuDrum photos give bed surfaces lifted on the left, straight at 15 rpm and S-shaped at 45 rpm") {
  const SurfaceProfile rolling = photo_profile("granudrum_mcc_15rpm.bmp");
  const SurfaceProfile cascading = photo_profile("granudrum_mcc_45rpm.bmp");
  REQUIRE(rolling.x.size() >= 30u);
  REQUIRE(cascading.x.size() >= 30u);
  const SurfaceLine rolling_line = fit_surface_line(rolling), cascading_line = fit_surface_line(cascading);
  WARN("15 rpm: angle " << rolling_line.angle_deg << " deg, residual " << rolling_line.residual_rms * 1e3
                        << " mm, threshold " << rolling.threshold_used << ", x " << rolling.x.front() * 1e3 << ".."
                        << rolling.x.back() * 1e3 << " mm");
  WARN("45 rpm: angle " << cascading_line.angle_deg << " deg, residual " << cascading_line.residual_rms * 1e3
                        << " mm, threshold " << cascading.threshold_used << ", x " << cascading.x.front() * 1e3 << ".."
                        << cascading.x.back() * 1e3 << " mm");
  WARN("material / empty grey levels: 15 rpm " << rolling.material_level << " / " << rolling.empty_level << ", 45 rpm "
                                               << cascading.material_level << " / " << cascading.empty_level
                                               << "; equivalent occupancy " << equivalent_occupancy(rolling) << ", "
                                               << equivalent_occupancy(cascading));
  for (const SurfaceProfile* p : {&rolling, &cascading}) {
    CHECK(p->z.front() > p->z.back() + 0.03);  // lifted on the left by more than 30 mm
    // Otsu's threshold on the averaged photo is where a pixel is powder about half the time, the
    // same rule as the simulated side's occupancy > 0.5 (within 0.1).
    CHECK(std::abs(equivalent_occupancy(*p) - 0.5) < 0.1);
  }
  CHECK(rolling_line.angle_deg < -20.0);
  CHECK(cascading_line.angle_deg < rolling_line.angle_deg);  // faster drum, steeper mean surface
  // Roughly straight at 15 rpm: a line leaves under 2 mm RMS (< 4 % of the ~60 mm chord); the
  // S-shaped 45 rpm surface leaves clearly more.
  CHECK(rolling_line.residual_rms < 0.002);
  CHECK(cascading_line.residual_rms > 1.5 * rolling_line.residual_rms);
}
