// The second battery of hostile inputs, values: a number is the whole text or an error, every
// count and range has a documented limit, a device or pipe is never read as an input, echoed
// names are escaped, and file names derived from names stay unique. The rules each case obeys
// are in hostile_battery.hpp.
#include <sys/stat.h>

#include "demfit/identify/safe_output.hpp"
#include <catch2/catch.hpp>

#include "hostile_battery.hpp"

using namespace hostile;

TEST_CASE("a number is the whole text or an error, and every range is stated") {
  const auto pellet = file("case.json", kPellet);
  const auto study = study_with([](json&) {});
  auto profiles = [](std::string value) {
    return all({file("a.csv", "x_mm,z_mm\n-10,0\n10,0\n"), file("b.csv", "x_mm,z_mm\n-10," + value + "\n10,0\n")});
  };
  check_all({
      {"--set frics=0,3 (decimal comma)",
       pellet,
       {"simulate", "case.json", "--set", "frics=0,3", "--out", "out"},
       "--set frics"},
      {"--set normk=0.5abc", pellet, {"simulate", "case.json", "--set", "normk=0.5abc", "--out", "out"}, "--set normk"},
      {"--set normk=1e999", pellet, {"simulate", "case.json", "--set", "normk=1e999", "--out", "out"}, "--set normk"},
      {"--set of a case field with a decimal comma",
       pellet,
       {"simulate", "case.json", "--set", "pellet.piston_speed=0,1", "--out", "out"},
       "--set pellet.piston_speed"},
      {"--set of a case field beyond double range",
       pellet,
       {"simulate", "case.json", "--set", "particle.radius=1e999", "--out", "out"},
       "--set particle.radius"},
      {"--jobs 1e3 (not a whole number)",
       study,
       {"identify", "study.json", "--jobs", "1e3", "--out", "out"},
       "--jobs: '1e3' is not a number"},
      {"--noise 0.5abc",
       pellet,
       {"simulate", "case.json", "--noise", "0.5abc", "--out", "out"},
       "--noise: '0.5abc' is not a number"},
      {"--seed -1", pellet, {"simulate", "case.json", "--seed", "-1", "--out", "out"}, "--seed"},
      {"simulate --out ''", pellet, {"simulate", "case.json", "--out", ""}, "--out"},
      {"identify --out ''", study, {"identify", "study.json", "--out", ""}, "--out"},
      {"diagnose --out ''", study, {"diagnose", "study.json", "--out", ""}, "--out"},
      {"report --out ''", file("x.db", "s"), {"report", "x.db", "--out", ""}, "--out"},
      {"--diameter 1e-300",
       file("photo.bmp", "BM"),
       {"target", "from-image", "photo.bmp", "--diameter", "1e-300", "--out", "out"},
       "at least 1 mm"},
      {"--diameter 1e999mm",
       file("photo.bmp", "BM"),
       {"target", "from-image", "photo.bmp", "--diameter", "1e999mm", "--out", "out"},
       "--diameter"},
      {"target compare with 1e308", profiles("1e308"), {"target", "compare", "a.csv", "b.csv"}, "limit of 1e6 mm"},
      {"target compare with -1e308", profiles("-1e308"), {"target", "compare", "b.csv", "a.csv"}, "limit of 1e6 mm"},
      {"a snapshot after the end of the drum run",
       file("case.json", kDrum),
       {"simulate", "case.json", "--snapshots", "1,100", "--out", "out"},
       "100 s is after the end"},
      {"a snapshot after the longest pellet stroke",
       file("case.json", R"({"case": "pellet_compression", "output": {"snapshot_times": [50]}})"),
       {"simulate", "case.json", "--out", "out"},
       "max_travel / piston_speed"},
  });
}

TEST_CASE("count options have documented upper limits") {
  check_all({
      {"--points 2000000000",
       file("photo.bmp", "BM"),
       {"target", "from-image", "photo.bmp", "--diameter", "84mm", "--points", "2000000000", "--out", "out"},
       "--points"},
      {"--scatter-replicas 100000",
       study_with([](json&) {}),
       {"diagnose", "study.json", "--scatter-replicas", "100000", "--out", "out"},
       "--scatter-replicas"},
      {"--refit-best 100000",
       study_with([](json&) {}),
       {"diagnose", "study.json", "--refit-best", "100000", "--out", "out"},
       "--refit-best"},
  });
}

TEST_CASE("an input that is a device or a pipe is refused before it is read") {
  auto fifo = [](const Sandbox& s) { REQUIRE(::mkfifo((s.work / "pipe.json").c_str(), 0644) == 0); };
  check_all({
      {"identify /dev/zero", [](const Sandbox&) {}, {"identify", "/dev/zero", "--out", "out"}, "not a regular file"},
      {"a target curve /dev/zero",
       study_with([](json& j) { j["targets"][0]["csv"] = "/dev/zero"; }),
       {"identify", "study.json", "--out", "out", "--no-plots"},
       "not a regular file"},
      {"simulate /dev/zero", [](const Sandbox&) {}, {"simulate", "/dev/zero", "--out", "out"}, "not a regular file"},
      {"target compare /dev/zero",
       file("a.csv", "x_mm,z_mm\n-10,0\n10,0\n"),
       {"target", "compare", "a.csv", "/dev/zero"},
       "not a regular file"},
      {"identify a named pipe (would wait for a writer)",
       fifo,
       {"identify", "pipe.json", "--out", "out"},
       "not a regular file"},
  });
}

TEST_CASE("names echoed in messages have control and bidirectional characters escaped") {
  // U+202E (right-to-left override) in a file name: "x<RLO>vsc.txt" would show as "xtxt.csv".
  const std::string rlo = "\xE2\x80\xAE";
  Sandbox s("battery2/bidi_name");
  write_study(s, [&] {
    json j = analytic_study();
    j["targets"][0]["csv"] = "x" + rlo + "vsc.txt";
    return j;
  }());
  const auto r = s.run({"identify", "study.json", "--out", "out", "--no-plots"});
  INFO(r.err);
  CHECK(r.status == 1);
  CHECK(r.err.rfind("demfit: error: ", 0) == 0);
  CHECK(r.err.find("x\\u202Evsc.txt") != std::string::npos);
  CHECK(r.err.find(rlo) == std::string::npos);
  CHECK(!fs::exists(s.work / "out"));
}

TEST_CASE("a bidirectional control character in a name that reaches a file or a report is refused") {
  const std::string rlo = "\xE2\x80\xAE";
  check_all({
      {"U+202E in a target name",
       study_with([&](json& j) { j["targets"][0]["name"] = "p" + rlo + "vsc.exe"; }),
       {"identify", "study.json", "--out", "out", "--no-plots"},
       "targets[0].name: contains a bidirectional"},
      {"U+2066 in the study name",
       study_with([](json& j) { j["name"] = "s\xE2\x81\xA6x"; }),
       {"identify", "study.json", "--out", "out", "--no-plots"},
       "U+2066"},
      {"U+202E in --out",
       study_with([](json&) {}),
       {"identify", "study.json", "--out", "o" + rlo + "x", "--no-plots"},
       "--out: contains a bidirectional"},
  });
}

TEST_CASE("errors of the file system reach the user as one line naming the path, never a raw library text") {
  const auto pellet = file("case.json", kPellet);
  check_all({
      {"simulate --out below a plain file",
       all({pellet, file("plain", "a file\n")}),
       {"simulate", "case.json", "--out", "plain/sub"},
       "--out"},
      {"identify --out below a plain file",
       all({study_with([](json&) {}), file("plain", "a file\n")}),
       {"identify", "study.json", "--out", "plain/sub", "--no-plots"},
       "plain"},
  });
}

TEST_CASE("a working folder removed under demfit gives one line, not a raw file-system exception") {
  Sandbox s("battery2/removed_cwd");
  write_study(s, analytic_study());
  const fs::path gone = s.work / "gone";
  fs::create_directory(gone);
  const fs::path err = s.root / "stderr.txt";
  const pid_t child = fork();
  if (child == 0) {
    const int e = open(err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    dup2(e, 2);
    if (chdir(gone.c_str()) != 0 || rmdir(gone.c_str()) != 0) _exit(126);
    const std::string study = (s.work / "study.json").string();
    execl(DEMFIT_EXE, DEMFIT_EXE, "identify", study.c_str(), "--out", "out", "--no-plots", static_cast<char*>(nullptr));
    _exit(127);
  }
  int status = 0;
  waitpid(child, &status, 0);
  const std::string text = trust::read_text(err);
  INFO(text);
  REQUIRE(WIFEXITED(status));
  CHECK(WEXITSTATUS(status) == 1);
  CHECK(text.rfind("demfit: error: demfit identify: ", 0) == 0);
  CHECK(text.find("filesystem error") == std::string::npos);
  CHECK(text.find("working folder") != std::string::npos);
  CHECK(std::count(text.begin(), text.end(), '\n') == 1);
}

TEST_CASE("a shortened file name keeps its extension and stays unique") {
  const std::string long_name = std::string(120, 'p');
  const std::string csv = id::safe_slug("target_" + long_name + ".csv");
  const std::string png = id::safe_slug("target_" + long_name + ".png");
  CHECK(csv.size() <= 80);
  CHECK(csv.substr(csv.size() - 4) == ".csv");
  CHECK(png.substr(png.size() - 4) == ".png");
  CHECK(csv != png);
  CHECK(id::safe_slug("target_" + long_name + "a.csv") != id::safe_slug("target_" + long_name + "b.csv"));
  CHECK(id::safe_slug("pressure_volume") == "pressure_volume");  // ordinary names unchanged
}

TEST_CASE("a folder marked without a kind is taken over only when it holds no study") {
  Sandbox s("battery2/legacy_marker");
  trust::write_text(s.work / "old" / ".demfit-output", "");
  id::prepare_output_folder(s.work / "old", {id::OutputKind::diagnose, {}});
  CHECK(trust::read_text(s.work / "old" / ".demfit-output").rfind("diagnose\n", 0) == 0);
  trust::write_text(s.work / "study" / ".demfit-output", "");
  trust::write_text(s.work / "study" / "study.db", "a store\n");
  CHECK_THROWS_WITH(id::prepare_output_folder(s.work / "study", {id::OutputKind::diagnose, {}}),
                    Catch::Contains("does not name the command"));
  id::prepare_output_folder(s.work / "study", {id::OutputKind::identify, {}});  // identify --resume of an old study
  CHECK(trust::read_text(s.work / "study" / ".demfit-output").rfind("identify\n", 0) == 0);
}

TEST_CASE("report of a study into its own folder keeps the folder identify's") {
  Sandbox s("battery2/report_own");
  trust::write_text(s.work / "a" / ".demfit-output", kIdentifyMarker);
  trust::write_text(s.work / "a" / "study.db", "a store\n");
  id::OutputRequest request{id::OutputKind::report, {s.work / "a" / "study.db"}};
  request.study_store = s.work / "a" / "study.db";
  CHECK_NOTHROW(id::prepare_output_folder(s.work / "a", request));
  CHECK(trust::read_text(s.work / "a" / ".demfit-output") == kIdentifyMarker);
  // A new folder of a report records its study: a later report of another study is refused there.
  id::prepare_output_folder(s.work / "b", request);
  id::OutputRequest other = request;
  other.study_store = s.work / "c" / "study.db";
  trust::write_text(other.study_store, "another store\n");
  CHECK_THROWS_WITH(id::prepare_output_folder(s.work / "b", other), Catch::Contains("report of another study"));
}

TEST_CASE("a cheap level that cannot run is refused naming its field, before anything is written") {
  auto with_cheap_level = [](json cheap_level, std::string strategy) {
    return study_with([cheap_level, strategy](json& study) {
      study["sampling"] = {{"strategy", strategy}, {"points_per_iteration", 4}};
      study["cheap_level"] = cheap_level;
    });
  };
  const std::vector<std::string> identify{"identify", "study.json", "--out", "out", "--no-plots"};
  check_all({
      {"cheap level with SRSM sampling",
       with_cheap_level({{"overrides", {{"points", 9}}}, {"runs", 12}}, "srsm"),
       identify,
       "cheap_level"},
      {"cheap level overriding an unknown case field",
       with_cheap_level({{"overrides", {{"bogus", 9}}}, {"runs", 12}}, "expected_improvement"),
       identify,
       "cheap_level.overrides"},
      {"cheap level without runs",
       with_cheap_level({{"overrides", {{"points", 9}}}}, "expected_improvement"),
       identify,
       "cheap_level.runs"},
      {"cheap level of a billion runs",
       with_cheap_level({{"overrides", {{"points", 9}}}, {"runs", 1000000000}}, "expected_improvement"),
       identify,
       "cheap_level.runs"},
  });
}
