// The parameter table is the one place a model parameter's range lives: the
// case parser, with_parameters, dem_core's own validation and the effect catalogue agree with it.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <string>

#include "../../cases/src/dem_setup.hpp"
#include "case_test_options.hpp"
#include "demfit/cases/case_spec.hpp"
#include "demfit/cases/effect_catalogue.hpp"
#include "demfit/cases/model_factory.hpp"
#include "demfit/cases/parameter_table.hpp"
#include "demfit/dem_core/packing.hpp"
#include "demfit/identify/lsdyna_export.hpp"
#include "demfit/identify/study.hpp"

using namespace demfit::cases;
using nlohmann::json;

namespace {

const double kInf = std::numeric_limits<double>::infinity();

// A case file the row belongs to: a Hertz drum for Hertz-only rows, a drum for drum-only rows
// (given as particle count or fill volume, as the row needs), else the pellet.
json document_for(const ParameterRow& row) {
  const std::string dir = std::string(DEMFIT_SOURCE_DIR) + "/cases/";
  if (row.laws == ParameterLaws::hertz_mindlin) return read_case_json(dir + "granudrum_mcc.json");
  if (row.drum_only) {
    json drum = read_case_json(dir + "rotary_drum.json");
    drum["drum"].erase("fill_fraction");
    return drum;
  }
  return read_case_json(dir + "pellet_compression.json");
}

json with_field(json document, const std::string& path, double value, bool integer) {
  const auto dot = path.find('.');
  json& section = document[path.substr(0, dot)];
  if (integer)
    section[path.substr(dot + 1)] = static_cast<long long>(value);
  else
    section[path.substr(dot + 1)] = value;
  return document;
}

bool is_integer(const ParameterRow& row) { return std::string(row.name) == "particle_count"; }

// Inside values at each end (the end itself when closed, the next double inward when open, a
// finite stand-in for an infinite end) and values just outside (the end itself when open, the
// next double outward when closed; none beyond an infinite end).
double inside_lower(const ParameterRow& r) {
  return r.valid.lower_open ? std::nextafter(r.valid.lower, kInf) : r.valid.lower;
}
double inside_upper(const ParameterRow& r) {
  if (std::isinf(r.valid.upper)) return 1.0;  // every unbounded row accepts 1 (a drum holds 1 mL)
  return r.valid.upper_open ? std::nextafter(r.valid.upper, -kInf) : r.valid.upper;
}
double outside_lower(const ParameterRow& r) {
  if (is_integer(r)) return r.valid.lower - 1.0;
  return r.valid.lower_open ? r.valid.lower : std::nextafter(r.valid.lower, -kInf);
}
double outside_upper(const ParameterRow& r) {
  return r.valid.upper_open ? r.valid.upper : std::nextafter(r.valid.upper, kInf);
}

}  // namespace

TEST_CASE(
    "Every parameter row's valid ends are accepted by the case parser and a value just outside is refused naming the "
    "field",
    "[cases][parameters]") {
  for (const ParameterRow& row : parameter_table()) {
    const json base = document_for(row);
    const std::string path =
        base["contact"].value("law", "") == "hertz_mindlin" && row.hertz_path ? row.hertz_path : row.case_path;
    INFO(row.name << " at " << path);
    for (double value : {inside_lower(row), inside_upper(row)}) {
      const CaseSpec spec = parse_case(with_field(base, path, value, is_integer(row)));
      CHECK(row.get(spec) == value);
    }
    CHECK_THAT(test::case_refusal(with_field(base, path, outside_lower(row), is_integer(row))), Catch::Contains(path));
    if (!std::isinf(row.valid.upper))
      CHECK_THAT(test::case_refusal(with_field(base, path, outside_upper(row), is_integer(row))),
                 Catch::Contains(path));
  }
}

TEST_CASE(
    "Every parameter row's valid ends are accepted by with_parameters and a value just outside is refused naming it",
    "[cases][parameters]") {
  for (const ParameterRow& row : parameter_table()) {
    INFO(row.name);
    const CaseSpec base = parse_case(document_for(row));
    for (double value : {inside_lower(row), inside_upper(row)})
      CHECK(row.get(detail::with_parameters(base, {{row.name, value}})) == value);
    std::vector<double> outside{outside_lower(row)};
    if (!std::isinf(row.valid.upper)) outside.push_back(outside_upper(row));
    for (double value : outside)
      CHECK_THROWS_WITH(
          detail::with_parameters(base, {{row.name, value}}),
          Catch::Contains("parameter '" + std::string(row.name) + "'") && Catch::Contains(row.valid.to_string()));
  }
}

TEST_CASE("dem_core's own validation accepts both valid ends of every contact, wall and effect row",
          "[cases][parameters]") {
  for (const ParameterRow& row : parameter_table()) {
    if (row.home == ParameterHome::fill) continue;  // the fill amount is the case's, dem_core has no such input
    INFO(row.name);
    for (double value : {inside_lower(row), inside_upper(row)}) {
      CaseSpec spec = parse_case(document_for(row));
      row.set(spec, value);
      if (std::string(row.name) == "radius_spread") {
        demfit::dem_core::PackingRequest q;
        q.region = demfit::dem_core::BoxRegion{{0, 0, 0}, {0.02, 0.02, 0.02}};
        q.radius_min = q.radius_max = 1e-3;
        q.radius_spread = value;
        q.count = 8;
        CHECK_NOTHROW(demfit::dem_core::generate_packing(q));
        continue;
      }
      CHECK_NOTHROW(demfit::dem_core::validate(spec.contact));
      CHECK_NOTHROW(demfit::dem_core::validate(spec.wall));
    }
  }
}

TEST_CASE(
    "The effect catalogue's fitting ranges lie inside the parameter table's valid ranges, with the table's off values",
    "[cases][parameters]") {
  for (const char* case_name : {"pellet_compression", "rotary_drum"})
    for (const EffectInfo& effect : effects_for_case(case_name))
      for (const EffectParameterInfo& p : effect.parameters) {
        INFO(case_name << ": " << effect.name << ": " << p.name);
        const ParameterRow* row = find_parameter(p.name);
        REQUIRE(row != nullptr);
        CHECK(row->is_effect);
        CHECK(row->valid.contains_interval(p.lower, p.upper));
        CHECK(p.off_value == row->off_value);
        CHECK(p.unit == row->unit);
      }
}

TEST_CASE("An unknown parameter name is refused with the table's names listed", "[cases][parameters]") {
  const CaseSpec base = parse_case(document_for(*find_parameter("normk")));
  std::string message;
  try {
    detail::with_parameters(base, {{"normal_stiffness", 0.1}});
  } catch (const std::exception& e) { message = e.what(); }
  CHECK_THAT(message, Catch::Contains("'normal_stiffness' is unknown"));
  for (const ParameterRow& row : parameter_table()) CHECK_THAT(message, Catch::Contains(std::string(" ") + row.name));
}

TEST_CASE("A NaN parameter value is refused with nan shown in the message", "[cases][parameters]") {
  const CaseSpec base = parse_case(document_for(*find_parameter("normk")));
  std::string message;
  try {
    detail::with_parameters(base, {{"normk", std::numeric_limits<double>::quiet_NaN()}});
  } catch (const std::exception& e) { message = e.what(); }
  CHECK_THAT(message, Catch::Contains("'normk' = nan must lie in"));
}

TEST_CASE(
    "parameters_of gives the parameters of the case's contact law and the fill amount in the form the case gives it",
    "[cases][parameters]") {
  using Names = std::vector<std::string>;
  auto names_of = [](const CaseSpec& spec) {
    Names names;
    for (const auto& [name, value] : detail::parameters_of(spec)) names.push_back(name);
    return names;
  };
  const std::string dir = std::string(DEMFIT_SOURCE_DIR) + "/cases/";
  CHECK(names_of(parse_case(read_case_json(dir + "pellet_compression.json"))) ==
        Names{"dc", "fricd", "fricr", "frics", "ndamp", "normk", "radius_spread", "sheark", "stiffness_exponent",
              "surface_energy", "tdamp", "unloading_stiffness_ratio", "wall_damp", "wall_fricd", "wall_frics",
              "wall_sfp"});
  // The GranuDrum case is Hertz-Mindlin (with its SJKR cohesion off and its wall friction tied
  // to the particles' at the ratio 1) with its fill given as a particle count.
  CHECK(names_of(parse_case(read_case_json(dir + "granudrum_mcc.json"))) ==
        Names{"cohesion_energy_density", "fricr", "frics", "particle_count", "restitution", "wall_fricd", "wall_frics",
              "wall_friction_ratio"});
  json by_volume = read_case_json(dir + "rotary_drum.json");
  by_volume["drum"].erase("fill_fraction");
  by_volume["drum"]["fill_volume_ml"] = 50.0;
  const Names drum = names_of(parse_case(by_volume));
  CHECK(std::count(drum.begin(), drum.end(), "fill_volume_ml") == 1);
  CHECK(std::count(drum.begin(), drum.end(), "particle_count") == 0);
  CHECK(drum.size() == 17);
}

TEST_CASE(
    "A DEM study whose damping bounds reach 1 is refused before the store exists, naming the valid range 0 to 1 with 1 "
    "excluded",
    "[cases][parameters]") {
  const json study = {
      {"demfit_study_version", 1},
      {"model", {{"case", "pellet_compression"}}},
      {"variables", json::array({{{"name", "ndamp"}, {"lower", 0.1}, {"upper", 1.0}, {"initial", 0.5}}})},
      {"targets", json::array({{{"curve", "pressure_volume"},
                                {"x_column", "volume_cm3"},
                                {"y_column", "pressure_MPa"},
                                {"x", {50.0, 60.0}},
                                {"y", {1.0, 0.0}}}})}};
  const demfit::identify::StudySpec spec = demfit::identify::parse_study(study, DEMFIT_BINARY_DIR);
  const auto model = make_study_model(spec);
  demfit::identify::RunOptions options;
  options.output_dir = std::string(DEMFIT_BINARY_DIR) + "/test_cases_bounds_refused";
  options.plots = false;
  options.progress = false;
  std::filesystem::remove_all(options.output_dir);
  std::filesystem::create_directories(options.output_dir);
  CHECK_THROWS_WITH(demfit::identify::run_study(spec, *model, options),
                    Catch::Contains("'ndamp'") && Catch::Contains("[0.1, 1]") && Catch::Contains("[0, 1) [-]"));
  CHECK_FALSE(std::filesystem::exists(options.output_dir / "study.db"));
}

TEST_CASE("Every parameter-table row with an LS-DYNA field is exported to that field and reads back",
          "[cases][parameters][export]") {
  const auto descriptors = parameter_descriptors();
  // Distinct, exactly representable values, one per row with an LS-DYNA field.
  demfit::identify::ParameterSet given;
  double value = 0.125;
  for (const auto& d : descriptors) {
    if (d.lsdyna_field.empty()) continue;
    given[d.name] = value;
    value += 0.0625;
  }
  REQUIRE(given.size() >= 12);
  const std::string text = demfit::identify::lsdyna_keywords(given, descriptors, "all fields");
  const auto back = demfit::identify::parse_lsdyna_keywords(text, descriptors);
  for (const auto& [name, v] : given) {
    if (name == "wall_sfp") {  // written as a comment (its card position differs between versions)
      CHECK(text.find("SFP used by demfit: " + demfit::identify::lsdyna_field(v)) != std::string::npos);
      continue;
    }
    INFO(name);
    REQUIRE(back.count(name) == 1);
    CHECK(back.at(name) == v);
  }
}
