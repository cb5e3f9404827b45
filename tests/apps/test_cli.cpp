// demfit simulate with bad input: exit status != 0, a single "demfit: error: ..." line naming the
// field, and no output folder (nor staging folder) left behind.
#include <catch2/catch.hpp>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

namespace fs = std::filesystem;

namespace {

struct CliRun {
  int status = 0;
  std::string error;  // stderr
};

fs::path scratch(const std::string& name) {
  const fs::path dir = fs::path(DEMFIT_BINARY_DIR) / "test_cli_scratch" / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

// Runs `command` (stdout discarded) and returns its exit status and stderr (kept in dir).
CliRun run_command(const std::string& command, const fs::path& dir) {
  const fs::path err = dir / "stderr.txt";
  const int raw = std::system((command + " > /dev/null 2> '" + err.string() + "'").c_str());
  CliRun run;
  run.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  std::ifstream in(err);
  std::stringstream text;
  text << in.rdbuf();
  run.error = text.str();
  return run;
}

CliRun run_demfit(const std::string& arguments, const fs::path& dir) {
  return run_command(
      std::string("DEMFIT_CACHE_DIR='") + (dir / "cache").string() + "' '" + DEMFIT_EXE + "' " + arguments, dir);
}

void write(const fs::path& path, const std::string& text) { std::ofstream(path) << text; }

// Nothing named out* (the output or a staging folder) exists in dir.
bool no_output_left(const fs::path& dir) {
  for (const auto& entry : fs::directory_iterator(dir)) {
    const std::string name = entry.path().filename().string();
    if (name.find("out") != std::string::npos) return false;
  }
  return true;
}

// README: every error is one "demfit: error: " line naming the field, exit status 1, no output.
void check_clean_failure(const CliRun& run, const std::string& field, const fs::path& dir) {
  CHECK(run.status == 1);
  INFO("stderr: " << run.error);
  CHECK(run.error.rfind("demfit: error: ", 0) == 0);
  CHECK(run.error.find(field) != std::string::npos);
  CHECK(std::count(run.error.begin(), run.error.end(), '\n') == 1);
  CHECK(no_output_left(dir));
}

}  // namespace

TEST_CASE("simulate with malformed JSON fails naming the file and writes nothing") {
  const fs::path dir = scratch("malformed");
  write(dir / "case.json", "{\"case\": \"pellet_compression\", \"particle\": {\"radius\": }");
  check_clean_failure(
      run_demfit("simulate '" + (dir / "case.json").string() + "' --out '" + (dir / "out").string() + "'", dir),
      "case.json", dir);
}

TEST_CASE("simulate with an unknown key fails naming the dotted key and writes nothing") {
  const fs::path dir = scratch("unknown_key");
  write(dir / "case.json", R"({"case": "pellet_compression", "pellet": {"piston_sped": 0.1}})");
  check_clean_failure(
      run_demfit("simulate '" + (dir / "case.json").string() + "' --out '" + (dir / "out").string() + "'", dir),
      "pellet.piston_sped", dir);
}

TEST_CASE("simulate with a negative radius fails naming particle.radius and writes nothing") {
  const fs::path dir = scratch("negative_radius");
  write(dir / "case.json", R"({"case": "pellet_compression", "particle": {"radius": -0.001}})");
  check_clean_failure(
      run_demfit("simulate '" + (dir / "case.json").string() + "' --out '" + (dir / "out").string() + "'", dir),
      "particle.radius", dir);
}

TEST_CASE("simulate with a time step above the stable limit fails naming time_step.value and writes nothing") {
  const fs::path dir = scratch("time_step");
  write(dir / "case.json", R"({"case": "rotary_drum", "time_step": {"value": 0.01}})");
  check_clean_failure(
      run_demfit("simulate '" + (dir / "case.json").string() + "' --out '" + (dir / "out").string() + "'", dir),
      "time_step.value", dir);
}

TEST_CASE("simulate with a missing case file fails naming the file and writes nothing") {
  const fs::path dir = scratch("missing");
  check_clean_failure(
      run_demfit("simulate '" + (dir / "nope.json").string() + "' --out '" + (dir / "out").string() + "'", dir),
      "nope.json", dir);
}

TEST_CASE("simulate with an unknown --set parameter path fails naming it and writes nothing") {
  const fs::path dir = scratch("bad_set");
  check_clean_failure(
      run_demfit(std::string("simulate '") + DEMFIT_SOURCE_DIR + "/cases/rotary_drum.json' --set drum.rpmm=30 --out '" +
                     (dir / "out").string() + "'",
                 dir),
      "drum.rpmm", dir);
}

TEST_CASE("an unknown command fails in one line listing the commands and writes nothing") {
  const fs::path dir = scratch("unknown_command");
  const CliRun top = run_demfit("frobnicate", dir);
  check_clean_failure(top, "unknown command 'frobnicate'", dir);
  CHECK(top.error.find("simulate, identify") != std::string::npos);
  const CliRun nested = run_demfit("reproduce table9", dir);
  check_clean_failure(nested, "unknown command 'table9'", dir);
  CHECK(nested.error.find("table1") != std::string::npos);
  CHECK(nested.error.find("'demfit reproduce --help'") != std::string::npos);
}

TEST_CASE("an option written before its command is named with where it belongs") {
  const fs::path dir = scratch("misplaced_option");
  // before, the option's value was reported as an unknown command ('2')
  check_clean_failure(run_demfit("reproduce --jobs 2 table1", dir),
                      "option '--jobs' belongs after the command (e.g. 'demfit reproduce table1 --jobs ...')", dir);
  check_clean_failure(run_demfit("reproduce --jobs=2 table9", dir), "option '--jobs' belongs after the command", dir);
}

TEST_CASE("a missing argument or option mistake fails in one line naming it with exit status 1") {
  const fs::path dir = scratch("usage");
  const CliRun missing = run_demfit("identify", dir);
  check_clean_failure(missing, "study is required", dir);
  CHECK(missing.error.find("'demfit identify --help'") != std::string::npos);
  check_clean_failure(
      run_demfit(std::string("identify '") + DEMFIT_SOURCE_DIR + "/cases/table1_study.json' --bogus", dir), "--bogus",
      dir);
  check_clean_failure(run_demfit("reproduce", dir), "a command is required", dir);
  check_clean_failure(run_demfit("reproduce table1 --jobs \"$(printf '2\\nx')\"", dir),
                      "--jobs: '2\\x0Ax' is not a number",
                      dir);  // one line
}

TEST_CASE("identify refuses a photo target whose image_diameter is not the simulated drum's naming the field") {
  const fs::path dir = scratch("photo_diameter");
  std::ifstream in(fs::path(DEMFIT_SOURCE_DIR) / "cases" / "granudrum_calibration_quick.json");
  nlohmann::json study = nlohmann::json::parse(in);
  for (auto& experiment : study["experiments"]) {
    experiment["model"]["case"] = std::string(DEMFIT_SOURCE_DIR) + "/cases/granudrum_mcc.json";
    auto& target = experiment["targets"][0];
    target["image"] = std::string(DEMFIT_SOURCE_DIR) + "/" + target["image"].get<std::string>().substr(3);
  }
  study["experiments"][1]["targets"][0]["image_diameter"] = 84;  // mm written where metres are meant
  write(dir / "study.json", study.dump());
  const CliRun run =
      run_demfit("identify '" + (dir / "study.json").string() + "' --out '" + (dir / "out").string() + "'", dir);
  check_clean_failure(run, "image_diameter ('rpm45.surface')", dir);
  CHECK(run.error.find("84 m across") != std::string::npos);
  CHECK(run.error.find("spans 0.084 m") != std::string::npos);
}

namespace {

// stderr of `demfit --version` with OpenMP's start-up settings displayed (OMP_DISPLAY_ENV is
// printed by libgomp when it loads, i.e. once per executable image).
std::string displayed_openmp_environment(const std::string& environment, const fs::path& dir) {
  const CliRun run = run_command("env -u OMP_WAIT_POLICY -u GOMP_SPINCOUNT OMP_DISPLAY_ENV=verbose " + environment +
                                     " '" + DEMFIT_EXE + "' --version",
                                 dir);
  REQUIRE(run.status == 0);
  return run.error;
}

}  // namespace

TEST_CASE("demfit starts OpenMP with a bounded spin before sleeping unless the user chose a waiting policy") {
  // a setenv in main comes after libgomp has read its environment, so it was ignored.
  const fs::path dir = scratch("openmp_waiting");
  const std::string chosen = displayed_openmp_environment("", dir);
  INFO(chosen);
  // The image libgomp finally runs in (the last display) has the bounded spin.
  const auto last = chosen.rfind("GOMP_SPINCOUNT");
  REQUIRE(last != std::string::npos);
  CHECK(chosen.find("'30000'", last) != std::string::npos);
  const std::string user = displayed_openmp_environment("OMP_WAIT_POLICY=passive", dir);
  INFO(user);
  CHECK(user.find("'30000'") == std::string::npos);  // the user's policy wins: no re-execution
  CHECK(user.find("GOMP_SPINCOUNT = '0'") != std::string::npos);
}
