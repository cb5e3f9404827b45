// The shipped GranuDrum calibration: its study files load with both photo
// targets, and `reproduce granudrum`'s report parts (surface errors, side-by-side and overlay
// pictures, the anchor path) work on known profiles and a tiny drum.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "demfit/cases/model_factory.hpp"
#include "demfit/cases/reproduce_granudrum.hpp"
#include "demfit/identify/study_spec.hpp"
#include "demfit/imaging/image.hpp"

using namespace demfit;
namespace fs = std::filesystem;

namespace {

const fs::path kSource = DEMFIT_SOURCE_DIR;

fs::path scratch(const std::string& name) {
  const fs::path dir = fs::path(DEMFIT_BINARY_DIR) / "test_granudrum_scratch" / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

// The study's photo profiles moved up by `shift_mm`, as the curves of a design point.
identify::CurveSet shifted_targets(const identify::StudySpec& spec, double shift_mm) {
  identify::CurveSet curves;
  for (const auto& t : spec.targets) {
    identify::Curve c = t.data;
    for (double& z : c.y) z += shift_mm;
    curves[t.curve] = c;
  }
  return curves;
}

}  // namespace

TEST_CASE("The shipped GranuDrum studies load both photos as targets of at least 30 surface points", "[granudrum]") {
  for (const char* file : {"granudrum_calibration.json", "granudrum_calibration_quick.json"}) {
    INFO(file);
    const identify::StudySpec spec = identify::load_study_file(kSource / "cases" / file);
    REQUIRE(spec.experiments.size() == 2);
    REQUIRE(spec.targets.size() == 2);
    for (const auto& t : spec.targets) {
      INFO(t.name);
      REQUIRE(t.image.has_value());
      CHECK(t.metric == identify::CurveMetric::profile_area);
      CHECK(t.data.x.size() >= 30);
      // Inside the compared circle of 0.7 R = 29.4 mm.
      for (std::size_t i = 0; i < t.data.x.size(); ++i) CHECK(std::hypot(t.data.x[i], t.data.y[i]) <= 29.4 + 0.21);
    }
    std::vector<std::string> names;
    for (const auto& v : spec.variables) names.push_back(v.name);
    CHECK(names == std::vector<std::string>{"frics", "fricr", "particle_count"});
    // Every variable reaches a drum model (make_study_model checks the cases and overrides).
    const auto model = cases::make_study_model(spec);
    const std::vector<std::string> accepted = model->parameter_names();
    for (const auto& name : names) CHECK(std::count(accepted.begin(), accepted.end(), name) == 1);
  }
}

TEST_CASE("Surface errors of a profile moved up by 2 mm are 2 mm RMS and 2 mm times the chord in area", "[granudrum]") {
  const identify::StudySpec spec = identify::load_study_file(kSource / "cases" / "granudrum_calibration_quick.json");
  const auto errors = cases::surface_errors(spec, shifted_targets(spec, 2.0));
  REQUIRE(errors.size() == 2);
  for (std::size_t k = 0; k < errors.size(); ++k) {
    const auto& x = spec.targets[k].data.x;
    CHECK(errors[k].target == spec.targets[k].name);
    CHECK(errors[k].rms_mm == Approx(2.0).epsilon(1e-9));
    CHECK(errors[k].area_mm2 == Approx(2.0 * (x.back() - x.front())).epsilon(1e-9));
  }
}

TEST_CASE("The granudrum report writes side-by-side and overlay pictures per speed and states the errors",
          "[granudrum]") {
  const identify::StudySpec spec = identify::load_study_file(kSource / "cases" / "granudrum_calibration_quick.json");
  const fs::path dir = scratch("pictures");
  const identify::CurveSet best = shifted_targets(spec, -3.0);
  const auto files = cases::write_surface_pictures(spec, best, dir);
  REQUIRE(files.size() == 4);
  for (const std::string& f : files) {
    INFO(f);
    const imaging::GreyImage picture = imaging::read_grey_image(dir / f);
    const bool pair = f.find("side_by_side") != std::string::npos;
    CHECK(picture.height == 406);
    CHECK(picture.width == (pair ? 2 * 406 + 8 : 406));
  }
  identify::StudyResult result;
  result.best = {{"frics", 0.6}, {"fricr", 0.3}, {"particle_count", 30000}};
  identify::ReportedInterval frics_interval;
  frics_interval.available = true;
  frics_interval.lower = 0.55;
  frics_interval.upper = 0.66;
  frics_interval.method = "posterior";
  result.intervals["frics"] = frics_interval;
  result.runs = 7;
  result.wall_seconds = 123;
  const auto errors = cases::surface_errors(spec, best);
  cases::AnchorResult anchor;
  anchor.errors = errors;
  anchor.runs = {{"rpm15", 1.0, 1234.0, 1}, {"rpm15", 3.0, 56.0, 1}};
  anchor.resolution = {{"rpm15.surface", 3.0, 1.25, 50.0, 4.5, 180.0}};
  anchor.wall_seconds = 1300.0;
  const std::string text = cases::granudrum_report(spec, result, errors, anchor, files);
  CHECK(text.find("| rpm15.surface | 3.00 |") != std::string::npos);
  CHECK(text.find("| rpm45.surface | 3.00 |") != std::string::npos);
  CHECK(text.find("| frics | 0.6 | [0.55, 0.66] (posterior) |") != std::string::npos);
  CHECK(text.find("7 evaluations") != std::string::npos);
  CHECK(text.find("granudrum_rpm45_overlay.png") != std::string::npos);
  CHECK(text.find("| rpm15 | 1 | 1234 | 1 |") != std::string::npos);
  CHECK(text.find("| rpm15.surface | 3 | 1.25 | 50 | 4.50 | 180 |") != std::string::npos);
}

namespace {

// A tiny GranuDrum (s = 5: ~230 particles, 0.15 s of rotation) for the code paths that run DEM.
nlohmann::json tiny_drum(double rpm) {
  return {{"drum",
           {{"rpm", rpm},
            {"scale_factor", 5.0},
            {"duration", 0.15},
            {"surface_window", 0.05},
            {"surface_snapshots", 3},
            {"densify_time", 0.1}}}};
}

// The shipped quick study with the tiny drum, 3 points per iteration and one iteration, written
// into the scratch folder with absolute paths to the case and photos. Its coarse-grained time step
// stays, so the anchor must drop it (a larger step than the original particles allow).
fs::path tiny_study(const fs::path& dir) {
  nlohmann::json study = nlohmann::json::parse(std::ifstream(kSource / "cases" / "granudrum_calibration_quick.json"));
  for (auto& e : study["experiments"]) {
    const double rpm = e["model"]["overrides"]["drum"]["rpm"];
    e["model"]["case"] = (kSource / "cases" / "granudrum_mcc.json").string();
    e["model"]["overrides"].merge_patch(tiny_drum(rpm));  // keeps the study's time step (4e-5 s)
    for (auto& t : e["targets"])
      t["image"] = (kSource / "cases" / t["image"].get<std::string>()).lexically_normal().string();
  }
  study["sampling"]["points_per_iteration"] = 3;
  study["stopping"]["max_iterations"] = 1;
  std::ofstream(dir / "tiny_study.json") << study.dump(1);
  return dir / "tiny_study.json";
}

}  // namespace

TEST_CASE("reproduce granudrum runs its study and the anchor on a tiny drum and writes its report",
          "[granudrum][slow]") {
  const fs::path dir = scratch("tiny");
  ::setenv("DEMFIT_CACHE_DIR", (fs::path(DEMFIT_BINARY_DIR) / "test_cache").c_str(), 1);
  cases::GranudrumOptions options;
  options.base.out_dir = dir / "out";
  options.base.jobs = 2;
  options.study_file = tiny_study(dir);
  options.anchor = true;
  options.resolution_scales = {6.0};  // one coarser run per speed beside the (tiny) anchor
  options.anchor_overrides = {{"drum",
                               {{"scale_factor", 5.0},
                                {"duration", 0.15},
                                {"surface_window", 0.05},
                                {"surface_snapshots", 3},
                                {"densify_time", 0.1}}}};
  const std::string text = cases::reproduce_granudrum(options);
  for (const char* f :
       {"granudrum.md", "granudrum_rpm15_side_by_side.png", "granudrum_rpm45_overlay.png", "study/study.db"})
    CHECK(fs::exists(options.base.out_dir / f));
  CHECK(text.find("source's parameters at s = 1") != std::string::npos);
  CHECK(text.find("| rpm45.surface | ") != std::string::npos);
  CHECK(text.find("| rpm45.surface | 6 | ") != std::string::npos);
  CHECK(fs::exists(options.base.out_dir / "published_rpm15_s1_free_surface_image.csv"));
  CHECK(fs::exists(options.base.out_dir / "published_rpm45_s6_free_surface_image.csv"));
  // The HTML page beside granudrum.md: self-contained, its pictures embedded.
  std::ifstream html_file(options.base.out_dir / "granudrum.html");
  const std::string html((std::istreambuf_iterator<char>(html_file)), std::istreambuf_iterator<char>());
  CHECK(html.find("data:image/png;base64,") != std::string::npos);
  CHECK(html.find("src=\"http") == std::string::npos);
  CHECK(html.find("| rpm45.surface |") == std::string::npos);  // the tables are rendered, not left as text
}

TEST_CASE("The granudrum report splits each gap into level tilt and shape and names a level difference no fill removes",
          "[granudrum]") {
  const identify::StudySpec spec = identify::load_study_file(kSource / "cases" / "granudrum_calibration_quick.json");
  REQUIRE(spec.targets.size() == 2);
  // One speed's bed 1 mm below its photo, the other's 1.5 mm above: a pure level split.
  identify::CurveSet split = shifted_targets(spec, -1.0);
  for (double& z : split.at(spec.targets[1].curve).y) z += 2.5;
  const auto errors = cases::surface_errors(spec, split);
  REQUIRE(errors.size() == 2);
  CHECK(errors[0].level_offset_mm == Approx(-1.0).epsilon(1e-9));
  CHECK(errors[1].level_offset_mm == Approx(1.5).epsilon(1e-9));
  for (const auto& e : errors) {
    CHECK(std::abs(e.angle_difference_deg) < 1e-9);
    CHECK(e.tilt_rms_mm < 1e-6);
    CHECK(e.shape_rms_mm < 1e-6);
  }
  const std::string note = cases::level_split_note(errors);
  CHECK(note.find("1.00 mm below the photo's in " + spec.targets[0].name) != std::string::npos);
  CHECK(note.find("1.50 mm above it in " + spec.targets[1].name + ": 2.50 mm apart") != std::string::npos);
  const std::string text = cases::granudrum_report(spec, identify::StudyResult{}, errors, cases::AnchorResult{}, {});
  CHECK(text.find("| " + spec.targets[1].name + " | demfit calibrated | +1.50 | +0.0 | 0.00 | 0.00 |") !=
        std::string::npos);
  CHECK(text.find(note) != std::string::npos);
  // The report states how the photos enter the objective (the split between them is its choice).
  identify::StudySpec scaled = spec;
  scaled.targets[1].scale = 1.35;
  const std::string scaled_text = cases::granudrum_report(scaled, identify::StudyResult{}, errors, {}, {});
  CHECK(scaled_text.find(spec.targets[0].name + ": weight 1, scale max |z| of the photo profile; " +
                         spec.targets[1].name + ": weight 1, scale 1.35 mm.") != std::string::npos);
  // Both beds above their photos: one fill lowers both, so no note.
  CHECK(cases::level_split_note(cases::surface_errors(spec, shifted_targets(spec, 2.0))).empty());
}
