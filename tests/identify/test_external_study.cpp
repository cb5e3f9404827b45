// Whole studies on an external program (the fake solver of data/external): identification,
// resume, and failed runs recorded in the store.
#include <catch2/catch.hpp>

#include <fstream>

#include "demfit/identify/external_model.hpp"
#include "demfit/identify/study.hpp"
#include "demfit/identify/study_store.hpp"
#include "external_test_helpers.hpp"
#include "test_helpers.hpp"

using namespace demfit::identify;
namespace fs = std::filesystem;

namespace {

int run_folders(const fs::path& out) {
  int count = 0;
  for ([[maybe_unused]] const auto& entry : fs::directory_iterator(out / kExternalRunsFolder)) ++count;
  return count;
}

// A copy of the fake solver's template in `dir`, with `extra` appended (a changed template).
void copy_template(const fs::path& dir, const std::string& extra) {
  std::ifstream in(test::external_data_dir() / "in.txt.template");
  std::ofstream out(dir / "in.txt.template");
  out << in.rdbuf() << extra;
}

}  // namespace

TEST_CASE("A study on an external program recovers the parameters its curve was made with",
          "[identify][external]") {
  const fs::path out = test::fresh_dir("external_study");
  const StudySpec spec = parse_study(test::fake_solver_study(test::fake_external(), 6), test::external_data_dir());
  const auto model = make_external_model(spec, out);
  const StudyResult result = run_study(spec, *model, test::quiet_options(out, 2));
  // The target is the solver's curve at (1.3, 4.2), computed here: noise-free, so the loop
  // converges to it; 0.5 % is far inside the bounds' width (0.5-2 and 1-8).
  CHECK(result.best.at("amplitude") == Approx(1.3).epsilon(0.005));
  CHECK(result.best.at("rate") == Approx(4.2).epsilon(0.005));
  CHECK(result.failed_runs == 0);
  CHECK(run_folders(out) == result.runs);  // each run its own folder, with --jobs 2 too
}

TEST_CASE("An external study resumes without repeating runs and refuses a changed template",
          "[identify][external][resume]") {
  const fs::path dir = test::fresh_dir("external_resume");
  copy_template(dir, "");
  auto external = test::fake_external();
  external["command"] = {(test::external_data_dir() / "fake_solver.sh").string()};
  const fs::path out = dir / "out";
  auto options = test::quiet_options(out);
  options.resolved_model = resolved_external_model(to_json(parse_external_spec(external, "e")), dir);
  const StudySpec short_spec = parse_study(test::fake_solver_study(external, 1), dir);
  const auto first = run_study(short_spec, *make_external_model(short_spec, out), options);

  const StudySpec longer = parse_study(test::fake_solver_study(external, 2), dir);
  options.resume = true;
  int repeated = 0;
  options.after_evaluation = [&](int done) { repeated = done; };
  const auto resumed = run_study(longer, *make_external_model(longer, out), options);
  CHECK(resumed.runs > first.runs);
  CHECK(repeated == resumed.runs - first.runs);  // only the new iterations ran
  CHECK(run_folders(out) == resumed.runs);

  copy_template(dir, "# a changed template\n");
  options.resolved_model = resolved_external_model(to_json(parse_external_spec(external, "e")), dir);
  CHECK_THROWS_WITH(run_study(longer, *make_external_model(longer, out), options),
                    Catch::Contains("external.template_lines"));
}

TEST_CASE("A failing external run is recorded in the store as a failed run and the study goes on",
          "[identify][external]") {
  const fs::path out = test::fresh_dir("external_failed_runs");
  // The solver exits 3 whenever amplitude > 1.7 (the upper part of the bounds).
  const StudySpec spec = parse_study(test::fake_solver_study(test::fake_external("fail_high"), 2),
                                     test::external_data_dir());
  const StudyResult result = run_study(spec, *make_external_model(spec, out), test::quiet_options(out, 2));
  REQUIRE(result.failed_runs > 0);
  int recorded = 0;
  for (const auto& run : StudyStore::open_existing(out / "study.db").evaluations())
    if (!run.ok) {
      ++recorded;
      CHECK(run.parameters.at("amplitude") > 1.7);
      CHECK_THAT(run.error, Catch::Contains("exit status 3"));
    }
  CHECK(recorded == result.failed_runs);
}
