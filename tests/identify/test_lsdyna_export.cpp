#include <catch2/catch.hpp>

#include <fstream>
#include <sstream>
#include <vector>

#include "demfit/identify/lsdyna_export.hpp"
#include "test_helpers.hpp"

using namespace demfit::identify;

namespace {

// A model whose parameters carry the LS-DYNA fields (the DEM cases get theirs from the parameter
// table; tests/cases checks that table's export). Defaults: LS-DYNA's (Keyword Manual); FRICD
// has none (NaN: it defaults to FRICS).
std::vector<ParameterDescriptor> lsdyna_model() {
  auto field = [](const char* name, double default_value, const char* lsdyna) {
    return ParameterDescriptor{name, "-", {}, default_value, std::nullopt, lsdyna};
  };
  return {field("ndamp", 0.0, "*CONTROL_DISCRETE_ELEMENT NDAMP"),
          field("tdamp", 0.0, "*CONTROL_DISCRETE_ELEMENT TDAMP"),
          field("frics", 0.0, "*CONTROL_DISCRETE_ELEMENT FRICS"),
          field("fricr", 0.0, "*CONTROL_DISCRETE_ELEMENT FRICR"),
          field("normk", 0.01, "*CONTROL_DISCRETE_ELEMENT NORMK"),
          field("sheark", 2.0 / 7.0, "*CONTROL_DISCRETE_ELEMENT SHEARK"),
          field("fricd", NAN, "*CONTROL_DISCRETE_ELEMENT FRICD"),
          field("dc", 0.0, "*CONTROL_DISCRETE_ELEMENT DC"),
          field("wall_frics", 0.0, "*DEFINE_DE_TO_SURFACE_COUPLING FRICS"),
          field("wall_fricd", 0.0, "*DEFINE_DE_TO_SURFACE_COUPLING FRICD"),
          field("wall_damp", 0.0, "*DEFINE_DE_TO_SURFACE_COUPLING DAMP"),
          field("wall_sfp", 1.0, "*DEFINE_DE_TO_SURFACE_COUPLING SFP (written as a comment)")};
}

}  // namespace

TEST_CASE("Every LS-DYNA field is exactly 10 characters and reads back close to its value", "[identify][export]") {
  for (double v : {0.875046, 0.299582, 0.004870718, 1.23456789e-5, -3.5e12, 0.0, 2.0 / 7.0, 123456789.0}) {
    const std::string field = lsdyna_field(v);
    CHECK(field.size() == 10);
    CHECK(std::stod(field) == Approx(v).epsilon(1e-4));
  }
}

TEST_CASE("Exported keyword cards parse back to the identified and default values", "[identify][export]") {
  const ParameterSet identified{{"ndamp", 0.558648808},      {"tdamp", 0.547304765},      {"frics", 0.437766112},
                                {"fricr", 0.088137162},      {"normk", 0.095010325},      {"sheark", 0.004870718},
                                {"wall_frics", 0.398444369}, {"wall_fricd", 0.186624382}, {"wall_damp", 0.101806949}};
  const auto dir = test::fresh_dir("export");
  write_lsdyna_keywords(dir / "out.k", identified, lsdyna_model(), "Table 3 values");
  std::ifstream in(dir / "out.k");
  std::stringstream text;
  text << in.rdbuf();
  const ParameterSet back = parse_lsdyna_keywords(text.str(), lsdyna_model());
  for (const auto& [name, value] : identified) CHECK(back.at(name) == Approx(value).epsilon(1e-6));
  CHECK(back.at("fricd") == Approx(0.437766112).epsilon(1e-6));  // FRICD defaults to FRICS
  CHECK(back.at("dc") == 0.0);
  // Data lines never exceed 8 fields of 10 characters.
  std::istringstream lines(text.str());
  std::string line;
  while (std::getline(lines, line))
    if (!line.empty() && line[0] != '$' && line[0] != '*') CHECK(line.size() <= 80);
  // Defaults for everything not given.
  const ParameterSet defaults = parse_lsdyna_keywords(lsdyna_keywords({}, lsdyna_model(), "defaults"), lsdyna_model());
  CHECK(defaults.at("normk") == Approx(0.01));
  CHECK(defaults.at("sheark") == Approx(2.0 / 7.0).epsilon(1e-6));
}

// Column positions from the LS-DYNA Keyword User's Manual, read here independently of the
// exporter's own parser: NORMK is field 5 (columns 41-50) of *CONTROL_DISCRETE_ELEMENT card 1,
// SHEARK field 6, FRICD field 4 of card 3; wall DAMP is field 3 of the coupling's card 2.
TEST_CASE("Exported values sit in the manual's columns of each card", "[identify][export]") {
  const ParameterSet p{
      {"normk", 0.875046}, {"sheark", 0.299582}, {"frics", 0.3}, {"fricd", 0.25}, {"wall_damp", 0.101806949}};
  std::istringstream in(lsdyna_keywords(p, lsdyna_model(), "columns"));
  std::vector<std::string> control, coupling;
  std::vector<std::string>* current = nullptr;
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("*CONTROL_DISCRETE_ELEMENT", 0) == 0)
      current = &control;
    else if (line.rfind("*DEFINE_DE_TO_SURFACE_COUPLING", 0) == 0)
      current = &coupling;
    else if (!line.empty() && line[0] == '*')
      current = nullptr;
    else if (current && !line.empty() && line[0] != '$')
      current->push_back(line);
  }
  REQUIRE(control.size() == 3);
  REQUIRE(coupling.size() == 2);
  auto column = [](const std::string& card, int first_column) { return std::stod(card.substr(first_column - 1, 10)); };
  CHECK(column(control[0], 41) == Approx(0.875046).epsilon(1e-6));
  CHECK(column(control[0], 51) == Approx(0.299582).epsilon(1e-6));
  CHECK(column(control[0], 21) == Approx(0.3).epsilon(1e-9));
  CHECK(column(control[2], 31) == Approx(0.25).epsilon(1e-9));
  CHECK(column(coupling[1], 21) == Approx(0.101806949).epsilon(1e-6));
}

// The model's descriptors say which effects LS-DYNA cannot carry (off value, no LS-DYNA field).
static std::vector<ParameterDescriptor> plasticity_model() {
  ParameterDescriptor normk{"normk", "-",          {0.0, 1e300, true, true},
                            0.01,    std::nullopt, "*CONTROL_DISCRETE_ELEMENT NORMK"};
  ParameterDescriptor ratio{"unloading_stiffness_ratio", "-", {1.0, 100.0}, 1.0, 1.0, ""};
  return {normk, ratio};
}

TEST_CASE("An identified effect without an LS-DYNA field is named in a warning comment, not dropped silently",
          "[identify][export]") {
  const std::string with_effect =
      lsdyna_keywords({{"normk", 0.5}, {"unloading_stiffness_ratio", 2.5}}, plasticity_model(), "plastic");
  CHECK(with_effect.find("$ WARNING: unloading_stiffness_ratio = 2.5 has no LS-DYNA DES field") != std::string::npos);
  const std::string effect_off =
      lsdyna_keywords({{"normk", 0.5}, {"unloading_stiffness_ratio", 1.0}}, plasticity_model(), "elastic");
  CHECK(effect_off.find("WARNING") == std::string::npos);
  CHECK(parse_lsdyna_keywords(with_effect, plasticity_model()).at("normk") == Approx(0.5));
}

TEST_CASE("A field no model parameter names is left blank, so LS-DYNA applies its own default", "[identify][export]") {
  const std::string text = lsdyna_keywords({{"normk", 0.5}}, plasticity_model(), "normk only");
  std::istringstream in(text);
  std::string line, card1;
  bool after_control = false;
  while (std::getline(in, line)) {
    if (line.rfind("*CONTROL_DISCRETE_ELEMENT", 0) == 0)
      after_control = true;
    else if (after_control && !line.empty() && line[0] != '$') {
      card1 = line;
      break;
    }
  }
  REQUIRE(card1.size() == 60);
  CHECK(card1.substr(0, 40).find_first_not_of(' ') == std::string::npos);  // NDAMP..FRICR blank
  CHECK(std::stod(card1.substr(40, 10)) == Approx(0.5));                   // NORMK
  CHECK(text.find("SFP used by demfit") == std::string::npos);
}
