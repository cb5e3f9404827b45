// The one Curve <-> JSON conversion shared by the study store, the result cache and MPI.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>

#include "demfit/identify/curve_json.hpp"

using namespace demfit::identify;

TEST_CASE("A curve set is written as an object of curves with labels and value arrays", "[identify][curve_json]") {
  const CurveSet curves{{"torque", Curve{"time_s", "torque_Nm", {0.0, 0.5}, {1.25, -2.0}}}};
  // The layout the study store, the result cache and the MPI wire format have always written
  // (keys sorted by nlohmann-json): stored stores and cache files stay readable and identical.
  CHECK(curves_to_json(curves).dump() ==
        R"({"torque":{"x":[0.0,0.5],"x_label":"time_s","y":[1.25,-2.0],"y_label":"torque_Nm"}})");
}

TEST_CASE("Curves survive the JSON round trip bit for bit", "[identify][curve_json]") {
  Curve curve{"volume_cm3", "pressure_MPa", {}, {}};
  for (int i = 0; i < 40; ++i) {
    curve.x.push_back(std::exp(0.1 * i) / 7.0);
    curve.y.push_back(std::sin(0.3 * i) * 1e-7);
  }
  const CurveSet back = curves_from_json(nlohmann::json::parse(curves_to_json({{"pv", curve}}).dump()));
  const Curve& c = back.at("pv");
  CHECK(c.x_label == "volume_cm3");
  CHECK(c.y_label == "pressure_MPa");
  REQUIRE(c.x.size() == curve.x.size());
  for (std::size_t i = 0; i < c.x.size(); ++i) {
    CHECK(std::memcmp(&c.x[i], &curve.x[i], sizeof(double)) == 0);
    CHECK(std::memcmp(&c.y[i], &curve.y[i], sizeof(double)) == 0);
  }
}

TEST_CASE("A curve missing a field is refused", "[identify][curve_json]") {
  CHECK_THROWS(curve_from_json(nlohmann::json{{"x_label", "a"}, {"x", {1.0}}, {"y", {2.0}}}));
}
