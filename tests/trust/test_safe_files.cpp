// Files are never lost, links never followed, write errors never silent, stores never shared
//, checked on the command line where it matters and on the library where it is exact.
#include <catch2/catch.hpp>

#include <sqlite3.h>

#include <atomic>
#include <cmath>
#include <thread>

#include <nlohmann/json.hpp>

#include "demfit/identify/json_document.hpp"
#include "demfit/identify/model_fingerprint.hpp"
#include "demfit/identify/safe_output.hpp"
#include "demfit/identify/store_lock.hpp"
#include "demfit/identify/study_spec.hpp"
#include "demfit/identify/study_store.hpp"
#include "trust_harness.hpp"

namespace {
using nlohmann::json;
using trust::Sandbox;
namespace fs = std::filesystem;
namespace id = demfit::identify;

const fs::path kData = fs::path(DEMFIT_SOURCE_DIR) / "tests" / "identify" / "data";

// A finished analytic study in work/out (a few seconds), with the study as written.
json finished_study(const Sandbox& s, json study = json()) {
  if (study.is_null()) study = json::parse(trust::read_text(kData / "analytic_study.json"));
  study["stopping"]["max_iterations"] = 2;
  trust::write_text(s.work / "study.json", study.dump(2));
  fs::copy_file(kData / "analytic_target.csv", s.work / "analytic_target.csv", fs::copy_options::overwrite_existing);
  const auto r = s.run({"identify", "study.json", "--out", "out", "--no-plots"});
  INFO(r.err);
  REQUIRE(r.status == 0);
  return study;
}

void sql(const fs::path& db, const std::string& statement) {
  sqlite3* handle = nullptr;
  REQUIRE(sqlite3_open(db.c_str(), &handle) == SQLITE_OK);
  REQUIRE(sqlite3_exec(handle, statement.c_str(), nullptr, nullptr, nullptr) == SQLITE_OK);
  sqlite3_close(handle);
}

bool one_error_line(const trust::Result& r, const std::string& field) {
  return r.status != 0 && r.status < 128 && r.err.rfind("demfit: error: ", 0) == 0 &&
         std::count(r.err.begin(), r.err.end(), '\n') == 1 && r.err.find(field) != std::string::npos;
}

}  // namespace

TEST_CASE("the atomic writer replaces a symbolic link instead of writing through it") {
  Sandbox s("lib_symlink");
  fs::create_symlink(s.outside / "precious.txt", s.work / "report.md");
  id::write_file_atomically(s.work / "report.md", "new report\n");
  CHECK(fs::is_regular_file(fs::symlink_status(s.work / "report.md")));
  CHECK(trust::read_text(s.work / "report.md") == "new report\n");
  CHECK(trust::read_text(s.outside / "precious.txt") == "a file of the user that no command may touch\n");
}

TEST_CASE("two threads writing the same file at once both succeed and leave no temporary") {
  Sandbox s("lib_threads");
  // Two evaluations of one study may cache the same fill at the same moment.
  std::atomic<int> failures{0};
  auto writer = [&](char fill) {
    for (int i = 0; i < 200; ++i) {
      try {
        id::write_file_atomically(s.work / "fill.txt", std::string(4000, fill));
      } catch (const std::exception&) { ++failures; }
    }
  };
  std::thread a(writer, 'a'), b(writer, 'b');
  a.join();
  b.join();
  CHECK(failures == 0);
  const std::string content = trust::read_text(s.work / "fill.txt");
  CHECK((content == std::string(4000, 'a') || content == std::string(4000, 'b')));
  CHECK(trust::leftovers(s.work).empty());
}

TEST_CASE("the atomic writer reports a full disk and leaves neither the file nor a temporary") {
  Sandbox s("lib_full_disk");
  // A child process with a 1000-byte file size limit stands for a full disk (write fails, EFBIG).
  const pid_t child = fork();
  if (child == 0) {
    signal(SIGXFSZ, SIG_IGN);
    rlimit limit{1000, 1000};
    setrlimit(RLIMIT_FSIZE, &limit);
    try {
      id::write_file_atomically(s.work / "big.json", std::string(5000, 'x'));
      _exit(0);
    } catch (const std::runtime_error& e) {
      _exit(std::string(e.what()).find("big.json") != std::string::npos ? 3 : 4);
    }
  }
  int status = 0;
  waitpid(child, &status, 0);
  CHECK(WIFEXITED(status));
  CHECK(WEXITSTATUS(status) == 3);  // threw, naming the file
  CHECK(!fs::exists(s.work / "big.json"));
  CHECK(trust::leftovers(s.work).empty());
}

TEST_CASE("report on a full disk exits non-zero with one line and no temporary left") {
  Sandbox s("cli_full_disk");
  // A 20000-point target makes target_<name>.csv (~0.8 MB) the one file above the limit; the
  // store (read only) and its 32 kB shared-memory file stay below it.
  std::string csv = "x_1,y_1\n";
  for (int i = 0; i < 20000; ++i) {
    const double x = i / 19999.0;
    csv += std::to_string(x) + "," + std::to_string(1.3 * (1 - std::exp(-4.2 * x)) + 0.5 * x) + "\n";
  }
  finished_study(s);
  trust::write_text(s.work / "analytic_target.csv", csv);
  fs::remove_all(s.work / "out");
  REQUIRE(s.run({"identify", "study.json", "--out", "out", "--no-plots"}).status == 0);
  const auto r = s.run({"report", "out/study.db", "--out", "rebuilt", "--no-plots"}, 200000);
  INFO(r.err);
  CHECK(one_error_line(r, "failed"));
  // The first file over the limit fails: the resolved study (the 20000-point target inline) or
  // the target table; neither may be left half-written.
  CHECK((r.err.find("study_resolved.json") != std::string::npos ||
         r.err.find("target_response.csv") != std::string::npos));
  CHECK(!fs::exists(s.work / "rebuilt" / "target_response.csv"));
  CHECK(!fs::exists(s.work / "rebuilt" / "study_resolved.json"));
  CHECK(trust::leftovers(s.work).empty());
}

TEST_CASE("report replaces a planted link in its folder and leaves the link's target untouched") {
  Sandbox s("cli_planted_link");
  finished_study(s);
  fs::remove(s.work / "out" / "report.md");
  fs::create_symlink(s.outside / "precious.txt", s.work / "out" / "report.md");
  const auto before = trust::snapshot(s.outside);
  const auto r = s.run({"report", "out/study.db", "--no-plots"});
  INFO(r.err);
  CHECK(r.status == 0);
  CHECK(trust::snapshot(s.outside) == before);
  CHECK(fs::is_regular_file(fs::symlink_status(s.work / "out" / "report.md")));
}

TEST_CASE("stale temporaries of a killed run are removed on the next run, live ones kept") {
  Sandbox s("lib_stale");
  trust::write_text(s.work / "out" / ".demfit-output", "");
  trust::write_text(s.work / "out" / "report.md.tmp999999999", "half");  // no such process
  trust::write_text(s.work / "out" / ("report.md.tmp" + std::to_string(getppid())), "live");
  id::prepare_output_folder(s.work / "out", {id::OutputKind::identify, {}});
  CHECK(!fs::exists(s.work / "out" / "report.md.tmp999999999"));
  CHECK(fs::exists(s.work / "out" / ("report.md.tmp" + std::to_string(getppid()))));
  trust::write_text(s.work / "out" / "fill.txt.tmp999999999-3", "half");  // today's form: <pid>-<sequence>
  trust::write_text(s.work / "out" / ("fill.txt.tmp" + std::to_string(getppid()) + "-3"), "live");
  id::prepare_output_folder(s.work / "out", {id::OutputKind::identify, {}});
  CHECK(!fs::exists(s.work / "out" / "fill.txt.tmp999999999-3"));
  CHECK(fs::exists(s.work / "out" / ("fill.txt.tmp" + std::to_string(getppid()) + "-3")));
}

TEST_CASE("a second identify on a study in use fails with one line naming the store") {
  Sandbox s("cli_lock");
  finished_study(s);
  const id::StoreLock held(s.work / "out");  // this process stands for the first demfit
  const auto before = trust::snapshot(s.work);
  const auto r = s.run({"identify", "study.json", "--out", "out", "--resume", "--no-plots"});
  INFO(r.err);
  CHECK(one_error_line(r, "in use by another demfit process"));
  CHECK(r.err.find("study.db") != std::string::npos);
  CHECK(trust::snapshot(s.work) == before);
}

TEST_CASE("resume refuses a changed model and names the field that changed") {
  Sandbox s("lib_resume_model");
  json study = json::parse(trust::read_text(kData / "analytic_study.json"));
  study["targets"][0]["csv"] = (kData / "analytic_target.csv").string();
  const id::StudySpec spec = id::parse_study(study, kData);
  const json model = {{"pellet", {{"count", 1450}, {"piston_speed", 0.05}}}, {"material", {{"radius", 0.001}}}};
  { id::StudyStore::open_for_run(s.work / "study.db", spec, false, model); }
  { CHECK_NOTHROW(id::StudyStore::open_for_run(s.work / "study.db", spec, true, model)); }
  json changed = model;
  changed["pellet"]["count"] = 1500;
  try {
    id::StudyStore::open_for_run(s.work / "study.db", spec, true, changed);
    FAIL("a changed model was accepted");
  } catch (const std::runtime_error& e) {
    CHECK(std::string(e.what()).find("pellet.count: was 1450, now 1500") != std::string::npos);
  }
  CHECK(id::first_difference(model, model).empty());
}

TEST_CASE("a corrupted row of study.db names the store and the run") {
  Sandbox s("cli_corrupt_row");
  finished_study(s);
  sql(s.work / "out" / "study.db",
      "UPDATE evaluations SET parameters = '{\"amplitude\": [' WHERE iteration = 0 AND point = 1");
  const auto r = s.run({"report", "out/study.db", "--out", "rebuilt", "--no-plots"});
  INFO(r.err);
  CHECK(one_error_line(r, "run 0/1 is corrupted"));
  CHECK(r.err.find("study.db") != std::string::npos);
  CHECK(!fs::exists(s.work / "rebuilt"));
}

TEST_CASE("export refuses a study of the analytic model and a keyword file that is the store") {
  Sandbox s("cli_export");
  finished_study(s);
  auto r = s.run({"export", "out/study.db", "--lsdyna", "out.k"});
  CHECK(one_error_line(r, "not a DEM case"));
  CHECK(!fs::exists(s.work / "out.k"));
  // The same store claiming a DEM case: --lsdyna naming the store itself is refused.
  sql(s.work / "out" / "study.db",
      "UPDATE meta SET value = json_set(value, '$.model.case', 'pellet_compression') WHERE key = 'study_json'");
  const auto before = trust::snapshot(s.work);
  r = s.run({"export", "out/study.db", "--lsdyna", "out/study.db"});
  CHECK(one_error_line(r, "is the study store itself"));
  CHECK(trust::snapshot(s.work) == before);
}

TEST_CASE("a target name with ../ and gnuplot syntax writes only slug files inside the output folder") {
  Sandbox s("cli_hostile_name");
  json study = json::parse(trust::read_text(kData / "analytic_study.json"));
  study["targets"][0]["name"] = "../../outside/x'; system(\"touch pwned\"); '";
  study["stopping"]["max_iterations"] = 2;
  trust::write_text(s.work / "study.json", study.dump());
  fs::copy_file(kData / "analytic_target.csv", s.work / "analytic_target.csv");
  const auto before = trust::snapshot(s.outside);
  const auto r = s.run({"identify", "study.json", "--out", "out"});  // with plots: gnuplot runs
  INFO(r.err);
  CHECK(r.status == 0);
  CHECK(trust::snapshot(s.outside) == before);
  CHECK(!fs::exists(s.work / "pwned"));
  CHECK(!fs::exists(s.work / "out" / "pwned"));
  for (const auto& e : fs::directory_iterator(s.work)) {
    const std::string name = e.path().filename().string();
    CHECK((name == "out" || name == "study.json" || name == "analytic_target.csv"));
  }
  CHECK(
      fs::exists(s.work / "out" / id::safe_slug("target_" + study["targets"][0]["name"].get<std::string>() + ".csv")));
}

TEST_CASE("a CSV with a UTF-8 byte-order mark is read like one without") {
  Sandbox s("cli_bom");
  json study = json::parse(trust::read_text(kData / "analytic_study.json"));
  study["stopping"]["max_iterations"] = 2;
  trust::write_text(s.work / "study.json", study.dump());
  trust::write_text(s.work / "analytic_target.csv", "\xEF\xBB\xBF" + trust::read_text(kData / "analytic_target.csv"));
  const auto r = s.run({"identify", "study.json", "--out", "out", "--no-plots"});
  INFO(r.err);
  CHECK(r.status == 0);
}

TEST_CASE("threads above the core count are capped with a note") {
  Sandbox s("cli_threads");
  finished_study(s);
  const auto r =
      s.run({"identify", "study.json", "--out", "out", "--resume", "--no-plots", "--threads-per-job", "100000"});
  INFO(r.err);
  CHECK(r.status == 0);
  CHECK(r.err.find("note: --threads-per-job 100000 is above the") != std::string::npos);
}

TEST_CASE("safe_slug keeps ordinary names and never yields a path") {
  CHECK(id::safe_slug("pressure_volume") == "pressure_volume");
  CHECK(id::safe_slug("../../etc/passwd") == "_._.._etc_passwd");
  CHECK(id::safe_slug("") == "unnamed");
  CHECK(id::safe_slug(std::string(500, 'a')).size() == 80);
  CHECK_THROWS_WITH(id::path_inside("out", ".."), Catch::Contains("would leave the output folder"));
  CHECK_THROWS_WITH(id::path_inside("out", "a/b"), Catch::Contains("would leave the output folder"));
}

TEST_CASE("JSON inputs: duplicate keys, depth and size are refused, a byte-order mark accepted") {
  CHECK_THROWS_WITH(id::parse_json_document(R"({"a": 1, "b": {"c": 1, "c": 2}})", "x"),
                    Catch::Contains("'c' appears twice"));
  CHECK_NOTHROW(id::parse_json_document(R"({"a": {"c": 1}, "b": {"c": 2}})", "x"));
  CHECK_THROWS_WITH(id::parse_json_document(std::string(65, '[') + std::string(65, ']'), "x"),
                    Catch::Contains("nested deeper"));
  CHECK_NOTHROW(id::parse_json_document(std::string(64, '[') + std::string(64, ']'), "x"));
  CHECK_NOTHROW(id::parse_json_document("\"[[[[\"", "x"));  // brackets inside strings do not count
  CHECK(id::parse_json_document("\xEF\xBB\xBF{\"a\": 1}", "x")["a"] == 1);
  CHECK(id::json_excerpt(json(std::string(1000, 'a'))).size() < 50);
}
