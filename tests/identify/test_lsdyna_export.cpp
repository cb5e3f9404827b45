#include <catch2/catch.hpp>

#include <fstream>
#include <sstream>

#include "demfit/identify/lsdyna_export.hpp"
#include "test_helpers.hpp"

using namespace demfit::identify;

TEST_CASE("Every LS-DYNA field is exactly 10 characters and reads back close to its value", "[identify][export]") {
  for (double v : {0.875046, 0.299582, 0.004870718, 1.23456789e-5, -3.5e12, 0.0, 2.0 / 7.0, 123456789.0}) {
    const std::string field = lsdyna_field(v);
    CHECK(field.size() == 10);
    CHECK(std::stod(field) == Approx(v).epsilon(1e-4));
  }
}

TEST_CASE("Exported keyword cards parse back to the identified and default values", "[identify][export]") {
  const ParameterSet identified{{"ndamp", 0.558648808}, {"tdamp", 0.547304765}, {"frics", 0.437766112},
                                {"fricr", 0.088137162}, {"normk", 0.095010325}, {"sheark", 0.004870718},
                                {"wall_frics", 0.398444369}, {"wall_fricd", 0.186624382}, {"wall_damp", 0.101806949}};
  const auto dir = test::fresh_dir("export");
  write_lsdyna_keywords(dir / "out.k", identified, "Table 3 values");
  std::ifstream in(dir / "out.k");
  std::stringstream text;
  text << in.rdbuf();
  const ParameterSet back = parse_lsdyna_keywords(text.str());
  for (const auto& [name, value] : identified) CHECK(back.at(name) == Approx(value).epsilon(1e-6));
  CHECK(back.at("fricd") == Approx(0.437766112).epsilon(1e-6));  // FRICD defaults to FRICS
  CHECK(back.at("dc") == 0.0);
  // Data lines never exceed 8 fields of 10 characters.
  std::istringstream lines(text.str());
  std::string line;
  while (std::getline(lines, line))
    if (!line.empty() && line[0] != '$' && line[0] != '*') CHECK(line.size() <= 80);
  // Defaults for everything not given.
  const ParameterSet defaults = parse_lsdyna_keywords(lsdyna_keywords({}, "defaults"));
  CHECK(defaults.at("normk") == Approx(0.01));
  CHECK(defaults.at("sheark") == Approx(2.0 / 7.0).epsilon(1e-6));
}
