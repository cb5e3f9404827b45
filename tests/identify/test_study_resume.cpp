#include <catch2/catch.hpp>

#include <fstream>
#include <iterator>

#include <sqlite3.h>

#include "demfit/identify/analytic_model.hpp"
#include "demfit/identify/report.hpp"
#include "demfit/identify/study.hpp"
#include "demfit/identify/study_store.hpp"
#include "test_helpers.hpp"

using namespace demfit::identify;

namespace {

using test::SimulatedKill;

using test::quiet_options;

}  // namespace

TEST_CASE("Resuming after a kill mid-iteration repeats no run and reaches the uninterrupted result",
          "[identify][resume]") {
  const auto spec = parse_study(test::analytic_study(0.01, 6), ".");
  const AnalyticCurveModel model;
  const auto reference = run_study(spec, model, quiet_options(test::fresh_dir("resume_reference")));

  const auto dir = test::fresh_dir("resume_killed");
  auto killed = quiet_options(dir);
  killed.jobs = 2;
  const int kill_after = 2 * spec.points_per_iteration + 3;  // in the middle of iteration 2
  killed.after_evaluation = [&](int done) {
    if (done == kill_after) throw SimulatedKill{};
  };
  CHECK_THROWS_AS(run_study(spec, model, killed), SimulatedKill);
  CHECK(StudyStore::open_existing(dir / "study.db").evaluations().size() == static_cast<std::size_t>(kill_after));
  // The store of a killed study still gives a report, marked unfinished.
  write_report(StudyStore::open_existing(dir / "study.db"), dir / "partial", false);
  std::ifstream partial(dir / "partial" / "report.md");
  const std::string partial_text((std::istreambuf_iterator<char>(partial)), std::istreambuf_iterator<char>());
  CHECK_THAT(partial_text, Catch::Contains("NOT finished"));

  auto resumed_options = quiet_options(dir);
  resumed_options.resume = true;
  int evaluated_after_resume = 0;
  resumed_options.after_evaluation = [&](int done) { evaluated_after_resume = done; };
  const auto resumed = run_study(spec, model, resumed_options);
  CHECK(evaluated_after_resume == reference.runs - kill_after);
  CHECK(resumed.runs == reference.runs);
  CHECK(resumed.best == reference.best);  // bit-identical
  CHECK(resumed.best_objective == reference.best_objective);
  CHECK(resumed.ci_half_width == reference.ci_half_width);
}

TEST_CASE("An existing store is refused without resume, and a store of another study always", "[identify][resume]") {
  const auto dir = test::fresh_dir("resume_refused");
  const auto spec = parse_study(test::analytic_study(0.0, 2), ".");
  run_study(spec, AnalyticCurveModel(), quiet_options(dir));
  CHECK_THROWS_WITH(run_study(spec, AnalyticCurveModel(), quiet_options(dir)),
                    Catch::Contains("already exists") && Catch::Contains("--resume"));
  auto other = test::analytic_study(0.0, 2);
  other["variables"][0]["upper"] = 3.0;
  auto options = quiet_options(dir);
  options.resume = true;
  CHECK_THROWS_WITH(run_study(parse_study(other, "."), AnalyticCurveModel(), options),
                    Catch::Contains("belongs to another study"));
  // Resuming a finished study with a higher iteration limit continues it.
  auto longer = test::analytic_study(0.0, 3);
  const auto more = run_study(parse_study(longer, "."), AnalyticCurveModel(), options);
  CHECK(more.iterations == 3);
  // Iteration 2 starts at the optimum the finished study verified: that run is reused.
  CHECK(more.runs == 3 * spec.points_per_iteration + 1);
  CHECK(StudyStore::open_existing(dir / "study.db").evaluations().size() ==
        static_cast<std::size_t>(3 * spec.points_per_iteration + 1));
}

TEST_CASE("A store written with another schema version is refused with a message", "[identify][resume]") {
  const auto dir = test::fresh_dir("resume_schema");
  const auto spec = parse_study(test::analytic_study(0.0, 1), ".");
  run_study(spec, AnalyticCurveModel(), quiet_options(dir));
  sqlite3* db = nullptr;
  REQUIRE(sqlite3_open((dir / "study.db").string().c_str(), &db) == SQLITE_OK);
  REQUIRE(sqlite3_exec(db, "UPDATE meta SET value = '999' WHERE key = 'schema_version'", nullptr, nullptr, nullptr) ==
          SQLITE_OK);
  sqlite3_close(db);
  auto options = quiet_options(dir);
  options.resume = true;
  CHECK_THROWS_WITH(run_study(spec, AnalyticCurveModel(), options), Catch::Contains("schema version 999"));
  CHECK_THROWS_WITH(StudyStore::open_existing(dir / "study.db"), Catch::Contains("schema version 999"));
  std::ofstream(dir / "not_a_store.db") << "hello";
  CHECK_THROWS(StudyStore::open_existing(dir / "not_a_store.db"));
}
