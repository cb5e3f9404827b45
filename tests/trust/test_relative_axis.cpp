// Relative axes from first contact ("fill offset"): a bed holding 2 % more powder is
// shifted on the absolute volume axis but identical on the axes measured from first contact.
#include <catch2/catch.hpp>

#include "demfit/identify/objective.hpp"
#include "demfit/identify/relative_axis.hpp"
#include "demfit/identify/study_preflight.hpp"

namespace {
namespace id = demfit::identify;

// Pressure [MPa] of a bed of initial volume v0 [cm3] compressed to 70 %: zero until the piston
// touches (at v0), then 50 MPa per unit volumetric strain.
id::Curve compression(double v0) {
  id::Curve c{"volume_cm3", "pressure_MPa", {}, {}};
  for (int i = 0; i <= 40; ++i) {
    const double v = 1.1 * v0 - i * (0.4 * v0) / 40.0;  // starts 10 % above contact
    c.x.push_back(v);
    c.y.push_back(v < v0 ? 50.0 * (v0 - v) / v0 : 0.0);
  }
  return c;
}

}  // namespace

TEST_CASE("the strain axis from first contact removes a 2 % fill offset") {
  const id::Curve model = compression(20.0), bed = compression(20.4);
  const id::Curve a = id::relative_axis_curve(model, "strain", "pv@strain");
  const id::Curve b = id::relative_axis_curve(bed, "strain", "pv@strain");
  CHECK(a.x_label == "volumetric_strain_1");
  // First contact: the first point with pressure above 1 % of the maximum (15 MPa), i.e. above 0.15 MPa.
  REQUIRE(a.x.size() >= 10);
  CHECK(a.y.front() > 0.15);
  // Compare the two beds at common strains.
  const std::vector<double> at{0.05, 0.1, 0.2, 0.25};
  const auto pa = id::resample_monotone(a, at), pb = id::resample_monotone(b, at);
  // Both grids touch at the same relative step, so both read p = 0.5 + 49.5 strain exactly.
  for (std::size_t i = 0; i < at.size(); ++i) {
    CHECK(pa[i] == Approx(0.5 + 49.5 * at[i]).epsilon(1e-12));
    CHECK(pb[i] == Approx(0.5 + 49.5 * at[i]).epsilon(1e-12));
  }
  // On the absolute axis the same two beds differ by 0.74 MPa at 15 cm3 (12.5 vs 13.24 MPa): a misfit
  // larger than the relative-axis difference above.
  const auto absolute_a = id::resample_monotone(model, {15.0}), absolute_b = id::resample_monotone(bed, {15.0});
  CHECK(std::abs(absolute_a[0] - absolute_b[0]) == Approx(50.0 * 5.4 / 20.4 - 12.5).epsilon(1e-12));
}

TEST_CASE("the from-contact axis keeps the unit, so a mm3 target is converted to the model's cm3") {
  const id::Curve c = id::relative_axis_curve(compression(20.0), "from_contact", "pv@from_contact");
  CHECK(c.x_label == "volume_change_cm3");
  CHECK(c.x.front() == 0.0);
  CHECK_THROWS_WITH(id::relative_axis_curve(compression(20.0), "offset", "pv@offset"), Catch::Contains("unknown axis"));
  id::Curve flat{"volume_cm3", "pressure_MPa", {3, 2, 1}, {0, 0, 0}};
  CHECK_THROWS_WITH(id::relative_axis_curve(flat, "strain", "pv@strain"), Catch::Contains("no first contact"));
}
