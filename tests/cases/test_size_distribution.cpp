// Size distributions of drum fills: reading measured sizes, size classes, cut-offs, and that
// seeded sampling reproduces the distribution (Kolmogorov–Smirnov at alpha = 0.01).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "demfit/cases/size_distribution.hpp"

using namespace demfit::cases;
using nlohmann::json;

namespace {

std::filesystem::path temp_dir() {
  const auto dir = std::filesystem::path(DEMFIT_BINARY_DIR) / "test_size_distribution";
  std::filesystem::create_directories(dir);
  return dir;
}

// Writes a CSV (UTF-8 BOM, CRLF, two columns like the Solidsizer export) and returns its name.
std::string write_csv(const std::string& name, const std::vector<std::string>& values) {
  std::ofstream out(temp_dir() / name, std::ios::binary);
  out << "\xEF\xBB\xBF"
      << "Particle,xFmax\r\n";
  for (std::size_t k = 0; k < values.size(); ++k) out << k + 1 << ',' << values[k] << "\r\n";
  return name;
}

// Largest distance between the empirical CDF of `sample` and `cdf` evaluated at the sample
// points, both one-sided limits (one-sample KS statistic; exact for a continuous or a step cdf).
template <class Cdf>
double ks_one_sample(std::vector<double> sample, Cdf cdf) {
  std::sort(sample.begin(), sample.end());
  const double n = static_cast<double>(sample.size());
  double d = 0.0;
  for (std::size_t i = 0; i < sample.size(); ++i) {
    if (i + 1 < sample.size() && sample[i + 1] == sample[i]) continue;  // evaluate after the last tie
    const double f = cdf(sample[i]);
    d = std::max(d, std::fabs(static_cast<double>(i + 1) / n - f));
  }
  return d;
}

// Two-sample KS statistic sup |F_a - F_b|.
double ks_two_sample(std::vector<double> a, std::vector<double> b) {
  std::sort(a.begin(), a.end());
  std::sort(b.begin(), b.end());
  std::size_t i = 0, j = 0;
  double d = 0.0;
  while (i < a.size() && j < b.size()) {
    const double x = std::min(a[i], b[j]);
    while (i < a.size() && a[i] <= x) ++i;
    while (j < b.size() && b[j] <= x) ++j;
    d = std::max(d, std::fabs(static_cast<double>(i) / a.size() - static_cast<double>(j) / b.size()));
  }
  return d;
}

constexpr double kKsAlpha001 = 1.628;  // c(alpha) of the asymptotic KS distribution at alpha = 0.01

}  // namespace

TEST_CASE("Sampling measured sizes reproduces their distribution above the cut-off (two-sample KS, alpha 0.01)") {
  // 3000 log-normal sizes in micrometres (median 1200 um), some below a 1000 um cut-off.
  std::mt19937_64 rng(7);
  std::vector<std::string> text;
  std::vector<double> kept;
  for (int k = 0; k < 3000; ++k) {
    const double u1 = (static_cast<double>(rng() >> 11) + 0.5) * 0x1.0p-53,
                 u2 = static_cast<double>(rng() >> 11) * 0x1.0p-53;
    const double normal = std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * std::numbers::pi * u2);
    const double size = 1200.0 * std::exp(0.15 * normal);
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.2f", size);
    text.emplace_back(buffer);
    if (std::stod(buffer) >= 1000.0) kept.push_back(0.5e-6 * std::stod(buffer));  // radius [m]
  }
  const std::string file = write_csv("lognormal.csv", text);
  const SizeDistributionSpec spec = parse_size_distribution(
      json{{"csv", file}, {"column", "xFmax"}, {"unit", "um"}, {"diameter_kind", "max_feret"}, {"min_size", 1000.0}},
      "drum.size_distribution", temp_dir());
  REQUIRE(spec.diameters.size() == kept.size());
  const std::vector<double> sample = spec.sample_radii(4000, 3);
  CHECK(*std::min_element(sample.begin(), sample.end()) >= 0.5e-3);  // the cut-off holds
  const double n = static_cast<double>(sample.size()), m = static_cast<double>(kept.size());
  const double critical = kKsAlpha001 * std::sqrt((n + m) / (n * m));
  const double d = ks_two_sample(sample, kept);
  INFO("KS D = " << d << ", critical " << critical);
  CHECK(d < critical);
  // A sampler that ignored the weights of the large sizes would fail: the 200 smallest kept
  // sizes alone are far from the distribution.
  std::vector<double> smallest = kept;
  std::sort(smallest.begin(), smallest.end());
  smallest.resize(200);
  CHECK(ks_two_sample(smallest, kept) > critical);
}

TEST_CASE("Sampling size classes with number fractions reproduces the class fractions (one-sample KS, alpha 0.01)") {
  // The GranuDrum MCC classes (data/granudrum_mcc/README.md).
  const std::vector<double> radius_mm{0.525, 0.55, 0.575, 0.6, 0.625, 0.65, 0.675, 0.7, 0.725, 0.75};
  const std::vector<double> fraction{0.0065, 0.0739, 0.2625, 0.2525, 0.1701, 0.1053, 0.0689, 0.0366, 0.0186, 0.0051};
  const SizeDistributionSpec spec = parse_size_distribution(
      json{{"radius", radius_mm}, {"unit", "mm"}, {"number_fraction", fraction}}, "drum.size_distribution", {});
  const std::size_t n = 3648;  // the s = 2 GranuDrum fill
  const std::vector<double> sample = spec.sample_radii(n, 1);
  auto cdf = [&](double r) {
    double f = 0.0, total = 0.0;
    for (std::size_t k = 0; k < fraction.size(); ++k) {
      total += fraction[k];
      if (radius_mm[k] * 1e-3 <= r * (1.0 + 1e-12)) f += fraction[k];
    }
    return f / total;
  };
  const double d = ks_one_sample(sample, cdf);
  const double critical = kKsAlpha001 / std::sqrt(static_cast<double>(n));
  INFO("KS D = " << d << ", critical " << critical);
  CHECK(d < critical);
  // Every sampled radius is one of the classes.
  for (double r : sample)
    CHECK(std::any_of(radius_mm.begin(), radius_mm.end(), [r](double c) { return std::fabs(c * 1e-3 - r) < 1e-15; }));
}

TEST_CASE("Sampling is deterministic in the fill seed and changes with it") {
  const SizeDistributionSpec spec = parse_size_distribution(
      json{{"diameter", {1.0, 2.0, 3.0}}, {"unit", "mm"}, {"number_fraction", {1.0, 1.0, 1.0}}}, "d", {});
  CHECK(spec.sample_radii(500, 4) == spec.sample_radii(500, 4));
  CHECK(spec.sample_radii(500, 4) != spec.sample_radii(500, 5));
}

TEST_CASE("Mass fractions become number fractions proportional to w / d^3") {
  // Equal mass in 1 mm and 2 mm classes: 8 times more small particles by number.
  const SizeDistributionSpec spec =
      parse_size_distribution(json{{"diameter", {1.0, 2.0}}, {"unit", "mm"}, {"mass_fraction", {0.5, 0.5}}}, "d", {});
  REQUIRE(spec.weights.size() == 2);
  CHECK(spec.weights[0] / spec.weights[1] == Approx(8.0).epsilon(1e-12));
  // E[v] by number = (8 v(1 mm) + v(2 mm)) / 9.
  const double v1 = std::numbers::pi / 6.0 * 1e-9, v2 = 8.0 * v1;
  CHECK(spec.mean_volume() == Approx((8.0 * v1 + v2) / 9.0).epsilon(1e-12));
}

TEST_CASE("A size CSV with a negative, empty or non-numeric value is refused naming the file and the row") {
  auto error_of = [](const std::vector<std::string>& values) {
    const std::string file = write_csv("bad.csv", values);
    try {
      parse_size_distribution(json{{"csv", file}, {"column", "xFmax"}, {"unit", "um"}}, "drum.size_distribution",
                              temp_dir());
    } catch (const std::exception& e) { return std::string(e.what()); }
    return std::string();
  };
  const std::string negative = error_of({"1200", "-5", "1100"});
  CHECK(negative.find("bad.csv") != std::string::npos);
  CHECK(negative.find("row 3") != std::string::npos);  // header is row 1
  CHECK(error_of({"1200", ""}).find("row 3") != std::string::npos);
  CHECK(error_of({"nan"}).find("row 2") != std::string::npos);
  CHECK(error_of({"12x"}).find("not a number") != std::string::npos);
  CHECK_THROWS_WITH(
      parse_size_distribution(json{{"csv", "bad.csv"}, {"column", "xF"}, {"unit", "um"}}, "d", temp_dir()),
      Catch::Contains("no column 'xF'"));
  CHECK_THROWS_WITH(parse_size_distribution(json{{"csv", "missing.csv"}, {"column", "xF"}}, "d", temp_dir()),
                    Catch::Contains("missing.csv"));
}
