// Synthetic noise statistics and the curve CSV written with a SYNTHETIC label read back exactly.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "demfit/cases/curve_table.hpp"
#include "demfit/cases/synthetic_noise.hpp"
#include "demfit/identify/curve_io.hpp"

using namespace demfit;

TEST_CASE("Relative noise has zero mean and standard deviation relative x max|y|, reproducibly per seed") {
  const std::size_t n = 40000;
  std::vector<double> y(n, 0.0);
  y[0] = -2.0;  // max|y| = 2
  const std::vector<double> a = cases::add_relative_noise(y, 0.01, 7);
  CHECK(a == cases::add_relative_noise(y, 0.01, 7));
  CHECK(a != cases::add_relative_noise(y, 0.01, 8));
  double mean = 0.0, square = 0.0;
  for (std::size_t i = 1; i < n; ++i) {
    mean += (a[i] - y[i]) / (n - 1);
    square += (a[i] - y[i]) * (a[i] - y[i]) / (n - 1);
  }
  const double sigma = 0.02;
  // Mean within 4 standard errors; sample standard deviation within 2 % (its standard error is
  // sigma / sqrt(2n) = 0.35 %).
  CHECK(std::fabs(mean) < 4.0 * sigma / std::sqrt(static_cast<double>(n)));
  CHECK(std::sqrt(square - mean * mean) == Approx(sigma).epsilon(0.02));
  CHECK(cases::add_relative_noise(y, 0.0, 1) == y);
}

TEST_CASE("A curve table with comment lines reads back exactly through identify::read_curve_csv") {
  const identify::Curve curve{"volume_cm3", "pressure_MPa", {67.1, 66.0, 65.2}, {0.0, 1.0 / 3.0, 3.000000001}};
  const std::filesystem::path path = std::filesystem::path(DEMFIT_BINARY_DIR) / "test_cases_curve.csv";
  cases::write_curve_table(path, cases::curve_table(curve, {"SYNTHETIC data: test"}));
  std::ifstream in(path);
  std::string first;
  std::getline(in, first);
  CHECK(first == "# SYNTHETIC data: test");
  const identify::Curve back = identify::read_curve_csv(path, "volume_cm3", "pressure_MPa");
  CHECK(back.x == curve.x);
  CHECK(back.y == curve.y);
}
