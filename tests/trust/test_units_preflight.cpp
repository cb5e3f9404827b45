// A study is checked against its model at the initial point: units converted within
// a dimension, a dimension mismatch, an unknown curve and a target outside the model's x-range
// refused; impossible fills refused before the packing generator builds anything.
#include <catch2/catch.hpp>

#include <cmath>

#include "demfit/dem_core/packing.hpp"
#include "demfit/identify/study_preflight.hpp"
#include "demfit/identify/units.hpp"

namespace {
namespace id = demfit::identify;
namespace dc = demfit::dem_core;

// Pressure [MPa] = k * volume change [cm3] on volumes 10..20 cm3 (a stand-in for the pellet case).
class LinearPelletModel final : public id::Model {
 public:
  std::vector<id::ParameterDescriptor> parameters() const override { return id::unbounded_descriptors({"k"}); }
  id::ParameterSet default_parameters() const override { return {{"k", 1.0}}; }
  id::CurveSet evaluate(const id::ParameterSet& p, const id::EvaluationContext&) const override {
    id::Curve c{"volume_cm3", "pressure_MPa", {}, {}};
    for (int i = 0; i <= 10; ++i) {
      c.x.push_back(20.0 - i);
      c.y.push_back(p.at("k") * i);
    }
    return {{"pressure_volume", c}};
  }
};

id::StudySpec study(const std::string& x_label, const std::string& y_label, std::vector<double> x,
                    std::vector<double> y, const std::string& curve = "pressure_volume") {
  id::StudySpec spec;
  spec.model_reference = "linear";
  spec.variables.push_back({"k", 0.5, 2.0, 1.0, false, 1.0});
  id::TargetSpec t;
  t.name = "measured";
  t.curve = curve;
  t.data = {x_label, y_label, std::move(x), std::move(y)};
  spec.targets.push_back(t);
  return spec;
}

// A drum-like model whose picture profile is a straight bed at `angle_deg` (x, z in mm, a picture
// spanning 84 mm), for the photo-target checks.
class TiltedBedModel final : public id::Model {
 public:
  std::vector<id::ParameterDescriptor> parameters() const override { return id::unbounded_descriptors({"angle_deg"}); }
  id::ParameterSet default_parameters() const override { return {{"angle_deg", 30.0}}; }
  std::vector<id::CurveDescriptor> curves() const override { return {{"free_surface_image", "x_mm", "z_mm", 0.084}}; }
  id::CurveSet evaluate(const id::ParameterSet& p, const id::EvaluationContext&) const override {
    return {{"free_surface_image", bed(p.at("angle_deg"))}};
  }
  static id::Curve bed(double angle_deg) {
    id::Curve c{"x_mm", "z_mm", {}, {}};
    for (int i = -20; i <= 20; i += 2) {
      c.x.push_back(i);
      c.y.push_back(std::tan(angle_deg * M_PI / 180.0) * i);
    }
    return c;
  }
};

// A photo target lifted on the left (-38 deg) framed `diameter` m across; the model starts at `initial_deg`.
id::StudySpec photo_study(double initial_deg, double diameter) {
  id::StudySpec spec;
  spec.model_reference = "tilted";
  spec.variables.push_back({"angle_deg", -60.0, 60.0, initial_deg, false, 1.0});
  id::TargetSpec t;
  t.name = "rpm15.surface";
  t.curve = "free_surface_image";
  t.data = TiltedBedModel::bed(-38.0);
  t.image = id::ImageTargetSpec{};
  t.image->diameter = diameter;
  spec.targets.push_back(t);
  return spec;
}

}  // namespace

TEST_CASE("a photo target whose bed slopes the other way from the model's initial bed is refused") {
  const TiltedBedModel model;
  CHECK_THROWS_WITH(id::preflight_study(photo_study(40.0, 0.084), model, {}),
                    Catch::Contains("targets[0].image ('rpm15.surface')") && Catch::Contains("-38.0 deg") &&
                        Catch::Contains("40.0 deg") && Catch::Contains("turns the other way"));
  CHECK_NOTHROW(id::preflight_study(photo_study(-25.0, 0.084), model, {}));
  CHECK_NOTHROW(id::preflight_study(photo_study(5.0, 0.084), model, {}));  // a nearly level bed is not judged
}

TEST_CASE("a photo target framed at another diameter than the model's picture is refused naming image_diameter") {
  const TiltedBedModel model;
  CHECK_THROWS_WITH(id::preflight_study(photo_study(-25.0, 84.0), model, {}),
                    Catch::Contains("targets[0].image_diameter ('rpm15.surface')") && Catch::Contains("84 m across") &&
                        Catch::Contains("spans 0.084 m"));
  CHECK_NOTHROW(id::preflight_study(photo_study(-25.0, 0.0845), model, {}));  // 0.6 %: a frame measured to a pixel
}

TEST_CASE("column units are read from the label and converted within a dimension") {
  CHECK(id::unit_factor("volume_mm3", "volume_cm3", "f") == Approx(1e-3).epsilon(1e-14));
  CHECK(id::unit_factor("pressure_kPa", "pressure_MPa", "f") == Approx(1e-3).epsilon(1e-14));
  CHECK(id::unit_factor("x_mm", "height_m", "f") == Approx(1e-3).epsilon(1e-14));
  CHECK(id::unit_factor("torque_Nmm", "torque_Nm", "f") == Approx(1e-3).epsilon(1e-14));
  CHECK(id::unit_factor("angle_deg", "angle_rad", "f") == Approx(M_PI / 180).epsilon(1e-14));
  CHECK(id::unit_factor("time_min", "time_s", "f") == 60.0);
  CHECK(id::unit_factor("x_1", "x_mm", "f") == 1.0);     // unknown unit: left as it is
  CHECK(id::unit_factor("p_mPa", "p_MPa", "f") == 1.0);  // case-sensitive: mPa is not a known unit
  CHECK_THROWS_WITH(id::unit_factor("volume_mm3", "height_mm", "targets[0].x_column"),
                    Catch::Contains("targets[0].x_column") && Catch::Contains("volume") && Catch::Contains("length"));
}

TEST_CASE("a mm3 and kPa target is converted to the model's cm3 and MPa before the study") {
  const LinearPelletModel model;
  // The model's own curve at k = 1.3, written in mm3 and kPa.
  std::vector<double> x, y;
  for (int i = 0; i <= 10; ++i) {
    x.push_back((20.0 - i) * 1000.0);
    y.push_back(1.3 * i * 1000.0);
  }
  const id::StudySpec checked = id::preflight_study(study("volume_mm3", "pressure_kPa", x, y), model, {});
  const id::Curve& t = checked.targets[0].data;
  CHECK(t.x_label == "volume_cm3");
  CHECK(t.y_label == "pressure_MPa");
  for (int i = 0; i <= 10; ++i) {
    CHECK(t.x[i] == Approx(20.0 - i).epsilon(1e-14));
    CHECK(t.y[i] == Approx(1.3 * i).epsilon(1e-14));
  }
}

TEST_CASE("a target of another dimension, an unknown curve or a disjoint x-range is refused") {
  const LinearPelletModel model;
  CHECK_THROWS_WITH(id::preflight_study(study("height_mm", "pressure_MPa", {1, 2}, {1, 2}), model, {}),
                    Catch::Contains("targets[0].x_column") && Catch::Contains("length"));
  CHECK_THROWS_WITH(id::preflight_study(study("volume_cm3", "force_N", {12, 14}, {1, 2}), model, {}),
                    Catch::Contains("targets[0].y_column"));
  CHECK_THROWS_WITH(id::preflight_study(study("volume_cm3", "pressure_MPa", {12, 14}, {1, 2}, "pv"), model, {}),
                    Catch::Contains("targets[0].curve") && Catch::Contains("it produces: pressure_volume"));
  // 2 % of the bed is fine, a target entirely beyond the model's volumes is not.
  CHECK_NOTHROW(id::preflight_study(study("volume_cm3", "pressure_MPa", {10.2, 20.4}, {1, 2}), model, {}));
  CHECK_THROWS_WITH(id::preflight_study(study("volume_cm3", "pressure_MPa", {21, 25}, {1, 2}), model, {}),
                    Catch::Contains("does not overlap"));
  // The same volumes in m3 (1e-6 x): out of range only if not converted.
  CHECK_NOTHROW(id::preflight_study(study("volume_m3", "pressure_MPa", {12e-6, 14e-6}, {1, 2}), model, {}));
}

TEST_CASE("an impossible fill is refused before the packing lattice is built") {
  dc::PackingRequest q;
  q.region = dc::CylinderRegion{{0, 0, 0}, {0, 0, 1}, 0.015, 0.064};  // 30 mm die, 64 mm high
  q.radius_min = q.radius_max = 0.001;
  q.count = 100000;  // 0.42 litre of solid in a 45 cm3 die
  CHECK_THROWS_WITH(dc::generate_packing(q), Catch::Contains("count") && Catch::Contains("more than"));
  q.count = 10;
  q.radius_min = q.radius_max = 0.05;  // wider than the die
  CHECK_THROWS_WITH(dc::generate_packing(q), Catch::Contains("radius_max"));
  q.radius_min = q.radius_max = 1e-7;  // 10^17 lattice sites
  q.count = 0;
  q.solid_volume = 1e-9;
  CHECK_THROWS_WITH(dc::generate_packing(q), Catch::Contains("too small"));
  // A feasible fill is still packed: solid volume pi/6 of the region is the lattice bound.
  q.radius_min = q.radius_max = 0.001;
  q.solid_volume = 0.0;
  q.count = 200;
  const dc::Packing p = dc::generate_packing(q);
  CHECK(p.centers.size() == 200);
}
