// The CLI's parameter documentation is derived from the parameter table:
// `demfit simulate --help` lists every row with unit and range, and docs/parameters.md is what
// `demfit parameters` prints.
#include <catch2/catch.hpp>

#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

#include "demfit/cases/parameter_table.hpp"

using namespace demfit::cases;

namespace {

// stdout of `demfit <arguments>` (popen, as test_cli uses std::system: fixed arguments of this
// test only).
std::string demfit_output(const std::string& arguments) {
  const std::string command = std::string("'") + DEMFIT_EXE + "' " + arguments;
  FILE* pipe = popen(command.c_str(), "r");
  REQUIRE(pipe != nullptr);
  std::string text;
  char buffer[4096];
  std::size_t n;
  while ((n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0) text.append(buffer, n);
  CHECK(pclose(pipe) == 0);
  return text;
}

std::string file_text(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace

TEST_CASE("demfit simulate --help lists every model parameter with its unit, valid range and meaning",
          "[apps][parameters]") {
  const std::string help = demfit_output("simulate --help");
  for (const ParameterRow& row : parameter_table()) {
    INFO(row.name);
    const std::string entry = "  " + std::string(row.name) + " [" + row.unit + "] " + row.valid.to_string();
    const auto at = help.find(entry);
    REQUIRE(at != std::string::npos);
    const std::string line = help.substr(at, help.find('\n', at) - at);
    CHECK_THAT(line, Catch::Contains(row.meaning));
  }
}

TEST_CASE("docs/parameters.md is exactly what demfit parameters prints", "[apps][parameters]") {
  const std::string printed = demfit_output("parameters");
  CHECK(printed == parameters_markdown());
  CHECK(file_text(std::string(DEMFIT_SOURCE_DIR) + "/docs/parameters.md") == printed);
}

TEST_CASE("demfit parameters prints one Markdown row per table row", "[apps][parameters]") {
  const std::string printed = demfit_output("parameters");
  for (const ParameterRow& row : parameter_table())
    CHECK_THAT(printed, Catch::Contains("| `" + std::string(row.name) + "` | " + row.unit + " | " +
                                        row.valid.to_string() + " |"));
}
