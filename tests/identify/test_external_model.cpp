// The external model's rules at study load and per run: template substitution, declared
// parameters, output paths, time limit, failed runs (docs/external-model.md).
#include <catch2/catch.hpp>

#include <signal.h>

#include <chrono>
#include <cstdlib>
#include <fstream>
#include <thread>

#include "demfit/identify/external_model.hpp"
#include "demfit/identify/template_text.hpp"
#include "external_test_helpers.hpp"
#include "test_helpers.hpp"

using namespace demfit::identify;
namespace fs = std::filesystem;

namespace {

StudySpec fake_spec(const nlohmann::json& external) {
  return parse_study(test::fake_solver_study(external), test::external_data_dir());
}

// The message of the exception `make` throws ("" when it throws none).
template <class F>
std::string error_of(F make) {
  try {
    make();
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
}

std::string one_run_error(const std::string& mode, const fs::path& out, double limit = 20.0) {
  const auto model = make_external_model(fake_spec(test::fake_external(mode, limit)), out);
  return error_of([&] { model->evaluate({{"amplitude", 1.0}, {"rate", 2.0}}, {}); });
}

}  // namespace

TEST_CASE("A placeholder is replaced by the shortest text that reads back as the same double", "[identify][external]") {
  for (double value : {0.1, 1.0 / 3.0, -2.5e17, 1e-300, 4.9e-324, 0.0}) {
    const std::string text = substitute_template("x = {{a}};", {{"a", value}}, "t");
    const std::string number = text.substr(4, text.size() - 5);
    CHECK(std::strtod(number.c_str(), nullptr) == value);
  }
  CHECK(substitute_template("{{a}}{{b}} {{a}}\n", {{"a", 0.5}, {"b", 2.0}}, "t") == "0.52 0.5\n");
  CHECK_THROWS_WITH(substitute_template("{{a}}", {{"a", std::nan("")}}, "t"), Catch::Contains("not finite"));
}

TEST_CASE("A malformed placeholder is refused with its line", "[identify][external]") {
  CHECK_THROWS_WITH(template_placeholders("ok\n{{ a }}\n", "t"), Catch::Contains("t line 2: '{{ a }}' is not a placeholder"));
  CHECK_THROWS_WITH(template_placeholders("{{1a}}", "t"), Catch::Contains("is not a placeholder"));
  CHECK_THROWS_WITH(template_placeholders("{{a\n}}", "t"), Catch::Contains("without a closing '}}'"));
  CHECK(template_placeholders("a {{x_1}} {b} }} {{y}}", "t").size() == 2);
}

TEST_CASE("A parameter name that would inject text into the template is refused at study load",
          "[identify][external]") {
  auto external = test::fake_external();
  external["parameters"]["rate}}\nrun 100\n{{x"] = "-";
  CHECK_THROWS_WITH(fake_spec(external), Catch::Contains("model.external.parameters: 'rate}}\\x0Arun 100\\x0A{{x' is "
                                                         "not a parameter name"));
  external = test::fake_external();
  external["parameters"]["amplitude"] = 1;  // a unit must be text
  CHECK_THROWS_WITH(fake_spec(external), Catch::Contains("parameters.amplitude: expected the unit"));
}

TEST_CASE("A placeholder that is not a declared parameter is refused at study load", "[identify][external]") {
  const fs::path dir = test::fresh_dir("external_unknown_placeholder");
  std::ofstream(dir / "in.txt.template") << "amplitude = {{amplitude}}\nrate = {{rate}}\nextra = {{frics}}\n";
  auto external = test::fake_external();
  external["command"] = {test::external_data_dir() / "fake_solver.sh"};
  const StudySpec spec = parse_study(test::fake_solver_study(external), dir);
  CHECK_THROWS_WITH(make_external_model(spec, dir / "out"),
                    Catch::Contains("line 3: {{frics}} is not a declared parameter"));
}

TEST_CASE("A declared parameter the template does not use or the study does not set is refused at study load",
          "[identify][external]") {
  auto external = test::fake_external();
  external["parameters"]["restitution"] = "-";
  CHECK_THROWS_WITH(make_external_model(fake_spec(external), "unused"),
                    Catch::Contains("parameters.restitution: the template 'in.txt.template' never uses"));
  nlohmann::json study = test::fake_solver_study(test::fake_external());
  study["variables"].erase(1);  // rate neither varied nor fixed
  CHECK_THROWS_WITH(make_external_model(parse_study(study, test::external_data_dir()), "unused"),
                    Catch::Contains("parameters.rate: the study neither varies nor fixes it"));
  study["model"]["fixed_parameters"] = {{"rate", 4.2}};
  CHECK_NOTHROW(make_external_model(parse_study(study, test::external_data_dir()), "unused"));
}

TEST_CASE("An output path that is absolute or contains '..' is refused at study load", "[identify][external]") {
  for (const std::string file : {"../response.csv", "/tmp/response.csv", "a/../../response.csv", ""}) {
    auto external = test::fake_external();
    external["outputs"]["response"]["file"] = file;
    CHECK_THROWS_WITH(fake_spec(external), Catch::Contains("model.external.outputs.response.file"));
  }
}

TEST_CASE("A missing program is a clear error at study load", "[identify][external]") {
  auto external = test::fake_external();
  external["command"] = {"demfit-no-such-solver", "-in", "in.sim"};
  CHECK_THROWS_WITH(make_external_model(fake_spec(external), "unused"),
                    Catch::Contains("command[0]: program 'demfit-no-such-solver' is not found in $PATH"));
  external["command"] = {"./no_such_solver.py"};
  CHECK_THROWS_WITH(make_external_model(fake_spec(external), "unused"), Catch::Contains("is not an executable file"));
}

TEST_CASE("A run writes its input into a fresh run folder and reads the curve its program wrote",
          "[identify][external]") {
  const fs::path out = test::fresh_dir("external_one_run") / "study";  // made by the first run
  const auto model = make_external_model(fake_spec(test::fake_external()), out);
  const CurveSet curves = model->evaluate({{"amplitude", 0.1}, {"rate", 2.0}}, {});
  const Curve& c = curves.at("response");
  REQUIRE(c.x.size() == 21);
  CHECK(c.y[20] == Approx(0.1 * (1.0 - std::exp(-2.0))).epsilon(1e-14));
  CHECK(c.y_label == "force_N");
  model->evaluate({{"amplitude", 0.2}, {"rate", 2.0}}, {});
  std::ifstream first(out / kExternalRunsFolder / "run-000001" / "in.txt");
  std::string text((std::istreambuf_iterator<char>(first)), std::istreambuf_iterator<char>());
  CHECK_THAT(text, Catch::Contains("amplitude = 0.1\nrate = 2\n"));
  CHECK(fs::exists(out / kExternalRunsFolder / "run-000002" / "response.csv"));
  CHECK(fs::exists(out / ".demfit-output"));  // the output folder is identify's
}

TEST_CASE("A program that hangs is killed with its process group at the time limit", "[identify][external]") {
  const fs::path out = test::fresh_dir("external_hang");
  const auto start = std::chrono::steady_clock::now();
  CHECK_THAT(one_run_error("hang_child", out, 1.0), Catch::Contains("exceeded the time limit of 1 s (killed)"));
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  CHECK(seconds < 2.5);
  std::ifstream pid_file(out / kExternalRunsFolder / "run-000001" / "child.pid");
  int child = 0;
  pid_file >> child;
  REQUIRE(child > 0);
  // The solver's own child is gone too: no process, or a zombie (killed, not yet reaped by
  // whichever process adopted it).
  bool gone = false;
  for (int i = 0; i < 100 && !gone; ++i) {
    std::ifstream stat("/proc/" + std::to_string(child) + "/stat");
    std::string pid, name, state;
    gone = !(stat >> pid >> name >> state) || state == "Z";
    if (!gone) std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  CHECK(gone);
}

TEST_CASE("A run that fails, writes no output, a NaN or an empty curve is a failed run with its reason",
          "[identify][external]") {
  const fs::path out = test::fresh_dir("external_failures");
  CHECK_THAT(one_run_error("fail", out), Catch::Contains("exit status 3 (its output: stdout.txt, stderr.txt)"));
  CHECK_THAT(one_run_error("no_output", out), Catch::Contains("wrote no 'response.csv'"));
  CHECK_THAT(one_run_error("nan", out), Catch::Contains("point 10 is not finite"));
  CHECK_THAT(one_run_error("empty", out), Catch::Contains("fewer than 2 points"));
  CHECK_THAT(one_run_error("fail", out), Catch::StartsWith("external run '") && Catch::Contains("external_runs/run-000005'"));
}

TEST_CASE("An output that is a symbolic link leaving the run folder is refused", "[identify][external]") {
  const fs::path out = test::fresh_dir("external_link");
  CHECK_THAT(one_run_error("link_out", out), Catch::Contains("leads outside the run folder"));
}

TEST_CASE("An external study reads back from its resolved JSON, and its time limit is not part of its hash",
          "[identify][external]") {
  auto external = test::fake_external();
  external["files"] = {"in.txt.template"};
  const StudySpec spec = fake_spec(external);
  const StudySpec again = parse_study(to_json(spec), test::external_data_dir());
  CHECK(to_json(again) == to_json(spec));
  CHECK(study_hash(again) == study_hash(spec));
  external["time_limit_s"] = 5.0;
  CHECK(study_hash(fake_spec(external)) == study_hash(spec));
  external["command"] = {"./fake_solver.sh", "nan"};
  CHECK(study_hash(fake_spec(external)) != study_hash(spec));
  nlohmann::json study = test::fake_solver_study(test::fake_external());
  study["model"]["case"] = "external";
  CHECK_THROWS_WITH(parse_study(study, test::external_data_dir()), Catch::Contains("either \"case\""));
}
