// Image targets and the profile_area metric, and the single-model study form
// resolving exactly as before the experiments form existed.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <random>

#include "demfit/identify/objective.hpp"
#include "demfit/identify/safe_output.hpp"
#include "demfit/identify/study_spec.hpp"
#include "demfit/imaging/image.hpp"
#include "demfit/imaging/profile_metrics.hpp"
#include "test_helpers.hpp"

using namespace demfit::identify;

namespace {

TargetSpec profile_target(const Curve& data, double scale, double weight = 1.0) {
  TargetSpec t;
  t.name = "surface";
  t.curve = "surface";
  t.data = data;
  t.metric = CurveMetric::profile_area;
  t.scale = scale;
  t.weight = weight;
  return t;
}

Curve line(double x0, double x1, int points, double z0, double slope) {
  Curve c{"x_mm", "z_mm", {}, {}};
  for (int i = 0; i < points; ++i) {
    const double x = x0 + (x1 - x0) * i / (points - 1);
    c.x.push_back(x);
    c.y.push_back(z0 + slope * x);
  }
  return c;
}

}  // namespace

TEST_CASE("The profile_area term is the squared mean gap over the common x-range in units of the scale",
          "[identify][profile_area]") {
  const CompositeObjective objective({profile_target(line(0, 10, 11, 0.0, 0.0), 2.0, 3.0)});
  // parallel, 1 mm above: area 10 mm^2 over 10 mm -> mean gap 1 mm -> term w (1/2)^2
  CHECK(objective.objective(objective.responses({{"surface", line(0, 10, 11, 1.0, 0.0)}})) == Approx(3.0 * 0.25));
  // crossing line z = x - 5: area 2 x 12.5 mm^2 -> mean gap 2.5 mm (exact where the gap changes sign)
  CHECK(objective.objective(objective.responses({{"surface", line(0, 10, 11, -5.0, 1.0)}})) ==
        Approx(3.0 * std::pow(2.5 / 2.0, 2)));
  // a simulated profile on [5, 15] only: common range [5, 10], gap 1 -> mean gap 1 mm as before
  CHECK(objective.objective(objective.responses({{"surface", line(5, 15, 11, 1.0, 0.0)}})) == Approx(3.0 * 0.25));
  // no common range: the run cannot be compared
  CHECK_THROWS_WITH(objective.responses({{"surface", line(20, 30, 11, 0.0, 0.0)}}),
                    Catch::Contains("does not overlap"));
}

TEST_CASE("The area between profiles equals demfit::imaging's differing area on a shared grid",
          "[identify][profile_area]") {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> z(-5.0, 5.0);
  for (int trial = 0; trial < 20; ++trial) {
    Curve a = line(-40, 40, 33, 0.0, 0.0), b = a;
    for (auto& y : a.y) y = z(rng);
    for (auto& y : b.y) y = z(rng);
    const double mine = profile_area_between(a.x, a.y.data(), b.y, -40.0, 40.0);
    demfit::imaging::SurfaceProfile pa, pb;  // independent implementation (merged breakpoints)
    for (std::size_t i = 0; i < a.x.size(); ++i) {
      pa.x.push_back(a.x[i]);
      pa.z.push_back(a.y[i]);
      pb.x.push_back(b.x[i]);
      pb.z.push_back(b.y[i]);
    }
    CHECK(mine == Approx(demfit::imaging::profile_differing_area(pa, pb)).epsilon(1e-12));
  }
}

TEST_CASE("A profile_area target needs increasing x", "[identify][profile_area]") {
  auto study = test::analytic_study();
  study["targets"][0]["metric"] = "profile_area";
  CHECK_NOTHROW(parse_study(study, "."));
  std::reverse(study["targets"][0]["x"].begin(), study["targets"][0]["x"].end());
  CHECK_THROWS_WITH(parse_study(study, "."), Catch::Contains("targets[0].metric: profile_area"));
}

TEST_CASE("An image target reads the photo's surface in millimetres in the drum frame", "[identify][image]") {
  // A drum picture drawn here: 201 px spanning 84 mm, dark powder below z = -10 mm, light above.
  const int n = 201;
  const double diameter = 0.084, level = -0.010;
  demfit::imaging::RgbImage picture{n, n, std::vector<std::uint8_t>(3 * n * n, 230)};
  for (int row = 0; row < n; ++row)
    for (int column = 0; column < n; ++column)
      if (diameter / 2 - row * diameter / (n - 1) < level)
        for (int c = 0; c < 3; ++c) picture.rgb[3 * (row * n + column) + c] = 40;
  const auto dir = test::fresh_dir("image_target");
  demfit::identify::write_file_atomically(dir / "drum.png", demfit::imaging::encode_png(picture));
  nlohmann::json study = test::analytic_study();
  study["targets"] = {{{"name", "surface"},
                       {"curve", "response"},
                       {"image", "drum.png"},
                       {"image_diameter", diameter},
                       {"image_margin", 0.2},
                       {"image_points", 21},
                       {"metric", "profile_area"}}};
  const StudySpec spec = parse_study(study, dir);
  const TargetSpec& t = spec.targets.at(0);
  CHECK(t.data.x_label == "x_mm");
  CHECK(t.data.y_label == "z_mm");
  REQUIRE(t.data.x.size() == 21);
  const double pixel_mm = 1e3 * diameter / (n - 1);
  for (double z : t.data.y) CHECK(std::abs(z - 1e3 * level) < pixel_mm);  // within one pixel
  CHECK(t.data.x.front() < -25.0);  // across the compared circle (radius 0.8 x 42 mm)
  CHECK(t.data.x.back() > 25.0);
  CHECK(to_json(spec)["targets"][0]["source"] == "drum.png");

  study["targets"][0]["image"] = "missing.png";
  CHECK_THROWS_WITH(parse_study(study, dir), Catch::Contains("targets[0].image:") && Catch::Contains("missing.png"));
  study["targets"][0]["image"] = "drum.png";
  study["targets"][0]["x_column"] = "x_mm";
  CHECK_THROWS_WITH(parse_study(study, dir), Catch::Contains("targets[0].image: an image target takes its points"));
  study["targets"][0].erase("x_column");
  demfit::identify::write_file_atomically(dir / "dark.png", demfit::imaging::encode_png(demfit::imaging::RgbImage{
                                                                n, n, std::vector<std::uint8_t>(3 * n * n, 10)}));
  study["targets"][0]["image"] = "dark.png";  // no surface to find: one line naming the field
  try {
    parse_study(study, dir);
    FAIL("an all-dark picture was accepted");
  } catch (const std::runtime_error& e) {
    const std::string message = e.what();
    CHECK(message.find("targets[0].image:") != std::string::npos);
    CHECK(message.find('\n') == std::string::npos);
  }
  study["targets"][0]["image"] = "drum.png";
  study["targets"][0]["image_diameter"] = 0.0;
  CHECK_THROWS_WITH(parse_study(study, dir), Catch::Contains("targets[0].image_diameter: must be > 0"));
}

TEST_CASE("A single-model study resolves and hashes exactly as before the experiments form",
          "[identify][experiments]") {
  // Hashes computed by study_hash of commit 3de5f3f (before "experiments" existed) for the shipped
  // study files: an old study.db keeps its hash, so --resume still accepts it.
  const auto analytic =
      load_study_file(std::filesystem::path(DEMFIT_SOURCE_DIR) / "tests/identify/data/analytic_study.json");
  CHECK(study_hash(analytic) == 17669872487009600220ull);
  const auto diagnose =
      load_study_file(std::filesystem::path(DEMFIT_SOURCE_DIR) / "tests/diagnose/data/hidden_stiffening_study.json");
  CHECK(study_hash(diagnose) == 17389005198030702979ull);
  nlohmann::json resolved = to_json(analytic);
  CHECK_FALSE(resolved.contains("experiments"));
  CHECK(resolved.contains("model"));
  CHECK(resolved.contains("targets"));
  resolved["targets"][0].erase("source");  // informational: where the CSV was (not kept by inline data)
  CHECK(to_json(parse_study(resolved, ".")) == resolved);
}
