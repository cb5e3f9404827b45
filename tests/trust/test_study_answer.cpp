// The study's answer is one decision (study_answer.hpp): report.md, best_parameters.json and the
// LS-DYNA export all name the run the study stored as its answer, never a lower run that the
// final selection rejected; a store row edited after it was written is refused by every reader;
// a run whose budget is absurd is refused before it starts.
#include <catch2/catch.hpp>

#include <sqlite3.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "demfit/identify/study_spec.hpp"
#include "demfit/identify/study_store.hpp"
#include "trust_harness.hpp"

namespace {
namespace fs = std::filesystem;
namespace id = demfit::identify;
using json = nlohmann::json;
using trust::Sandbox;

// A pellet study whose store holds three runs: the lowest (FRICS 0.40017) was rejected by the
// final selection, which chose the second (FRICS 0.41002), as the shipped Table 3 study can.
void rejected_lowest_run_store(const fs::path& db) {
  const json study = {{"demfit_study_version", 1},
                      {"name", "selection"},
                      {"model", {{"case", "pellet_compression"}}},
                      {"variables", {{{"name", "frics"}, {"lower", 0.1}, {"upper", 0.9}, {"initial", 0.3}}}},
                      {"targets",
                       {{{"curve", "pressure_volume"},
                         {"x_column", "volume_cm3"},
                         {"y_column", "pressure_MPa"},
                         {"x", {60.0, 55.0, 50.0}},
                         {"y", {0.1, 0.5, 2.0}}}}},
                      {"final_selection", {{"candidates", 2}, {"replicates", 2}}},
                      {"seed", 3}};
  const id::StudySpec spec = id::parse_study(study, db.parent_path());
  auto store = id::StudyStore::open_for_run(db, spec, false, nullptr);
  const auto run = [](int iteration, int point, double frics, double objective) {
    id::EvaluationRecord r;
    r.iteration = iteration;
    r.point = point;
    r.kind = "design";
    r.unit_x = {(frics - 0.1) / 0.8};
    r.parameters = {{"frics", frics}, {"normk", 0.875046}, {"sheark", 0.299582}};
    r.curves["pressure_volume"] = id::Curve{"volume_cm3", "pressure_MPa", {60.0, 55.0, 50.0}, {0.1, 0.5, 2.0}};
    r.objective = objective;
    r.wall_seconds = 1.0;
    r.ok = true;
    return r;
  };
  store.add_evaluation(run(0, 0, 0.40017, 0.010));
  store.add_evaluation(run(0, 1, 0.41002, 0.012));
  store.add_evaluation(run(0, 2, 0.70000, 0.090));
  store.put_result({{"best_iteration", 0},
                    {"best_point", 1},
                    {"best_objective", 0.012},
                    {"best_parameters", {{"frics", 0.41002}, {"normk", 0.875046}, {"sheark", 0.299582}}},
                    {"best_variables", {{"frics", 0.41002}}},
                    {"runs", 3},
                    {"failed_runs", 0},
                    {"iterations", 1},
                    {"converged", false},
                    {"stop_reason", "iteration limit reached (1) without converging"},
                    {"final_selection", nullptr},
                    {"wall_seconds", 3.0},
                    {"uncertainty", nullptr}});
}

void sql(const fs::path& db, const std::string& statement) {
  sqlite3* handle = nullptr;
  REQUIRE(sqlite3_open(db.c_str(), &handle) == SQLITE_OK);
  REQUIRE(sqlite3_exec(handle, statement.c_str(), nullptr, nullptr, nullptr) == SQLITE_OK);
  sqlite3_close(handle);
}

bool one_error_line(const trust::Result& r, const std::string& text) {
  return r.status != 0 && r.status < 128 && r.err.rfind("demfit: error: ", 0) == 0 &&
         std::count(r.err.begin(), r.err.end(), '\n') == 1 && r.err.find(text) != std::string::npos;
}

}  // namespace

TEST_CASE("report, best_parameters.json and the LS-DYNA export all give the study's answer, not a rejected lower run") {
  Sandbox s("answer_everywhere");
  fs::create_directories(s.work / "study");
  rejected_lowest_run_store(s.work / "study" / "study.db");
  auto r = s.run({"report", "study/study.db", "--out", "rebuilt", "--no-plots"});
  INFO(r.err);
  REQUIRE(r.status == 0);
  const json best = json::parse(trust::read_text(s.work / "rebuilt" / "best_parameters.json"));
  INFO(best.dump());
  CHECK(best.dump().find("0.41002") != std::string::npos);
  CHECK(best.dump().find("0.40017") == std::string::npos);
  CHECK(trust::read_text(s.work / "rebuilt" / "report.md").find("0.40017") == std::string::npos);
  r = s.run({"export", "study/study.db", "--lsdyna", "answer.k"});
  INFO(r.err);
  REQUIRE(r.status == 0);
  const std::string cards = trust::read_text(s.work / "answer.k");
  CHECK(cards.find(".41002") != std::string::npos);  // FRICS of the answer, in its 10-character field
  CHECK(cards.find(".40017") == std::string::npos);
  CHECK(cards.find("run 0/1") != std::string::npos);
}

TEST_CASE("a run row edited after it was written is refused by export and report, naming the run") {
  Sandbox s("answer_edited_row");
  fs::create_directories(s.work / "study");
  rejected_lowest_run_store(s.work / "study" / "study.db");
  // Make the rejected run look like the answer's better twin: a plausible, well-formed edit.
  sql(s.work / "study" / "study.db", "UPDATE evaluations SET objective = 0.001 WHERE iteration = 0 AND point = 2");
  const auto before = trust::snapshot(s.work);
  auto r = s.run({"export", "study/study.db", "--lsdyna", "answer.k"});
  CHECK(one_error_line(r, "run 0/2 is corrupted or was changed after demfit wrote it"));
  r = s.run({"report", "study/study.db", "--out", "rebuilt", "--no-plots"});
  CHECK(one_error_line(r, "run 0/2 is corrupted or was changed after demfit wrote it"));
  CHECK(trust::snapshot(s.work) == before);
}

TEST_CASE("an edited stored answer is refused naming the entry") {
  Sandbox s("answer_edited_result");
  fs::create_directories(s.work / "study");
  rejected_lowest_run_store(s.work / "study" / "study.db");
  sql(s.work / "study" / "study.db",
      "UPDATE meta SET value = json_set(value, '$.best_point', 2) WHERE key = 'result_json'");
  const auto r = s.run({"export", "study/study.db", "--lsdyna", "answer.k"});
  CHECK(one_error_line(r, "'result_json' entry was changed after demfit wrote it"));
  CHECK(!fs::exists(s.work / "answer.k"));
}

TEST_CASE("a drum run estimated at days is refused before any work, naming the estimate and the way to allow it") {
  Sandbox s("budget_drum_duration");
  json drum = json::parse(trust::read_text(fs::path(DEMFIT_SOURCE_DIR) / "cases" / "rotary_drum.json"));
  drum["drum"]["duration"] = 1e6;
  trust::write_text(s.work / "drum.json", drum.dump(2));
  const auto r = s.run({"simulate", "drum.json", "--out", "out"});
  INFO(r.err);
  CHECK(one_error_line(r, "DEMFIT_ALLOW_LONG_RUNS=1"));
  CHECK(r.err.find("days") != std::string::npos);
  CHECK(!fs::exists(s.work / "out"));
  CHECK(!fs::exists(s.root / "cache"));  // refused before the fill
}

TEST_CASE("a pellet run with a time step of 1e-12 s is refused before any work") {
  Sandbox s("budget_pellet_step");
  json pellet = json::parse(trust::read_text(fs::path(DEMFIT_SOURCE_DIR) / "cases" / "pellet_compression.json"));
  pellet["time_step"] = {{"value", 1e-12}};
  trust::write_text(s.work / "pellet.json", pellet.dump(2));
  const auto r = s.run({"simulate", "pellet.json", "--out", "out"});
  INFO(r.err);
  CHECK(one_error_line(r, "estimated"));
  CHECK(r.err.find("DEMFIT_ALLOW_LONG_RUNS") != std::string::npos);
  CHECK(!fs::exists(s.work / "out"));
}

TEST_CASE("a drum turning so fast that the wall jumps over contacts in one step is refused") {
  Sandbox s("budget_drum_rpm");
  json drum = json::parse(trust::read_text(fs::path(DEMFIT_SOURCE_DIR) / "cases" / "rotary_drum.json"));
  drum["drum"]["rpm"] = 1e6;
  trust::write_text(s.work / "drum.json", drum.dump(2));
  const auto r = s.run({"simulate", "drum.json", "--out", "out"});
  INFO(r.err);
  CHECK(one_error_line(r, "'drum.rpm': the wall moves"));
  CHECK(!fs::exists(s.work / "out"));
}

TEST_CASE("an edited iteration record is refused by report, naming the record") {
  Sandbox s("answer_edited_iteration");
  fs::create_directories(s.work / "study");
  rejected_lowest_run_store(s.work / "study" / "study.db");
  {
    auto store = id::StudyStore::open_existing(s.work / "study" / "study.db");
    id::IterationRecord it;
    it.iteration = 0;
    it.region_center = {0.5};
    it.region_range = {1.0};
    it.predicted_optimum = {0.4};
    it.predicted_parameters = {{"frics", 0.42}};
    it.predicted_objective = 0.011;
    it.best_objective = 0.01;
    it.runs_done = 3;
    store.put_iteration(it);
  }
  sql(s.work / "study" / "study.db", "UPDATE iterations SET record = replace(record, '0.011', '0.001')");
  const auto r = s.run({"report", "study/study.db", "--out", "rebuilt", "--no-plots"});
  CHECK(one_error_line(r, "iteration record 0 was changed after demfit wrote it"));
  CHECK(!fs::exists(s.work / "rebuilt"));
}

TEST_CASE("a store of the previous schema is refused with its version by export and report") {
  Sandbox s("answer_old_schema");
  fs::create_directories(s.work / "study");
  rejected_lowest_run_store(s.work / "study" / "study.db");
  sql(s.work / "study" / "study.db", "UPDATE meta SET value = '1' WHERE key = 'schema_version'");
  const auto before = trust::snapshot(s.work);
  auto r = s.run({"export", "study/study.db", "--lsdyna", "answer.k"});
  CHECK(one_error_line(r, "has schema version 1, this demfit reads version 2"));
  r = s.run({"report", "study/study.db", "--out", "rebuilt", "--no-plots"});
  CHECK(one_error_line(r, "has schema version 1, this demfit reads version 2"));
  CHECK(trust::snapshot(s.work) == before);
}

TEST_CASE("a stored answer naming a missing or a failed run is refused") {
  for (const bool failed : {false, true}) {
    Sandbox s(failed ? "answer_failed_run" : "answer_missing_run");
    fs::create_directories(s.work / "study");
    rejected_lowest_run_store(s.work / "study" / "study.db");
    {
      auto store = id::StudyStore::open_existing(s.work / "study" / "study.db");
      auto result = *store.result();
      if (failed) {
        id::EvaluationRecord r = *store.find_evaluation(0, 2);
        r.ok = false;
        r.objective = NAN;
        r.error = "diverged";
        store.add_evaluation(r);
        result["best_point"] = 2;
      } else {
        result["best_point"] = 7;
      }
      store.put_result(result);
    }
    const auto r = s.run({"export", "study/study.db", "--lsdyna", "answer.k"});
    CHECK(one_error_line(r, failed ? "is a failed run" : "is missing"));
    CHECK(!fs::exists(s.work / "answer.k"));
  }
}

TEST_CASE("a failed run's error text with control and bidirectional characters cannot forge a line of report.md") {
  Sandbox s("answer_forged_error");
  fs::create_directories(s.work / "study");
  rejected_lowest_run_store(s.work / "study" / "study.db");
  {
    auto store = id::StudyStore::open_existing(s.work / "study" / "study.db");
    id::EvaluationRecord r = *store.find_evaluation(0, 2);
    r.point = 3;
    r.ok = false;
    r.objective = NAN;
    r.curves.clear();
    r.error = "diverged |\n\n- status: all good\x1b[2J \xE2\x80\xAE reversed";
    store.add_evaluation(r);
  }
  const auto r = s.run({"report", "study/study.db", "--out", "rebuilt", "--no-plots"});
  INFO(r.err);
  REQUIRE(r.status == 0);
  const std::string report = trust::read_text(s.work / "rebuilt" / "report.md");
  CHECK(report.find("\n- status: all good") == std::string::npos);  // no forged line
  CHECK(report.find('\x1b') == std::string::npos);
  CHECK(report.find("\xE2\x80\xAE") == std::string::npos);
  CHECK(report.find("diverged") != std::string::npos);  // the error is still shown, escaped
}
