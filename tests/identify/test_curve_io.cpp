#include <catch2/catch.hpp>

#include <fstream>

#include "demfit/identify/curve_io.hpp"
#include "test_helpers.hpp"

using namespace demfit::identify;

TEST_CASE("A curve written as CSV reads back bit-identical with its unit labels", "[identify][csv]") {
  const auto dir = test::fresh_dir("csv_round_trip");
  Curve curve{"volume_cm3", "pressure_MPa", {1.0 / 3.0, 2.5e-7, 1e5}, {0.1, -2.0 / 7.0, 3.0}};
  write_curve_csv(dir / "c.csv", curve);
  const Curve back = read_curve_csv(dir / "c.csv", "volume_cm3", "pressure_MPa");
  CHECK(back.x == curve.x);
  CHECK(back.y == curve.y);
  CHECK(back.x_label == "volume_cm3");
  CHECK_FALSE(std::filesystem::exists(dir / "c.csv.tmp"));
}

TEST_CASE("Reading a CSV column that does not exist names the column and the header", "[identify][csv]") {
  const auto dir = test::fresh_dir("csv_missing");
  std::ofstream(dir / "c.csv") << "# comment\ntime_s,torque_Nm\n0,1\n1,2\n";
  CHECK(read_curve_csv(dir / "c.csv", "time_s", "torque_Nm").y == std::vector<double>{1, 2});
  try {
    read_curve_csv(dir / "c.csv", "time_s", "force_N");
    FAIL("expected an error");
  } catch (const std::runtime_error& e) {
    CHECK_THAT(e.what(), Catch::Contains("force_N") && Catch::Contains("time_s, torque_Nm"));
  }
  std::ofstream(dir / "bad.csv") << "a,b\n0,1\n1,x2\n";
  CHECK_THROWS_WITH(read_curve_csv(dir / "bad.csv", "a", "b"), Catch::Contains("line 3"));
}
