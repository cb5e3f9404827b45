// The second battery of hostile inputs: a command never destroys another command's study or
// results, never writes over what is not its own (devices, links, existing files, paths through
// links), refuses unwritable places before the work, and never turns a malformed or extreme number
// into a silent wrong one. Each case ends with exit status != 0 and ONE line "demfit: error: ..."
// naming the field, leaves every file of the working folder and of the rest of the disk as it was,
// and leaves no partial output. No case runs a simulation: every refusal comes before the run.
#include <catch2/catch.hpp>

#include <linux/fs.h>
#include <sys/ioctl.h>
#include <sys/stat.h>

#include <functional>
#include <optional>

#include <nlohmann/json.hpp>

#include <sqlite3.h>

#include "demfit/identify/safe_output.hpp"
#include "demfit/identify/store_lock.hpp"
#include "trust_harness.hpp"

namespace {
using nlohmann::json;
using trust::Sandbox;
namespace fs = std::filesystem;
namespace id = demfit::identify;

const fs::path kData = fs::path(DEMFIT_SOURCE_DIR) / "tests" / "identify" / "data";
const char* kPellet = R"({"case": "pellet_compression"})";
const char* kDrum = R"({"case": "rotary_drum"})";

struct Hostile {
  std::string name;                           // what is wrong
  std::function<void(const Sandbox&)> setup;  // writes the inputs into work/
  std::vector<std::string> args;              // demfit arguments (run in work/)
  std::string field;                          // the message must contain this
  bool lock_out = false;                      // this process holds work/out's study lock meanwhile
};

json analytic_study() { return json::parse(trust::read_text(kData / "analytic_study.json")); }

void write_study(const Sandbox& s, const json& study) {
  trust::write_text(s.work / "study.json", study.dump(2));
  fs::copy_file(kData / "analytic_target.csv", s.work / "analytic_target.csv", fs::copy_options::overwrite_existing);
}
std::function<void(const Sandbox&)> study_with(std::function<void(json&)> edit) {
  return [edit](const Sandbox& s) {
    json study = analytic_study();
    edit(study);
    write_study(s, study);
  };
}
std::function<void(const Sandbox&)> file(std::string name, std::string text) {
  return [name, text](const Sandbox& s) { trust::write_text(s.work / name, text); };
}
// Several set-ups in order.
std::function<void(const Sandbox&)> all(std::vector<std::function<void(const Sandbox&)>> steps) {
  return [steps](const Sandbox& s) {
    for (const auto& step : steps) step(s);
  };
}
// A folder as `demfit <kind>` leaves it (marker first line: the kind), with a study's files when
// it is a study folder. The study.db is a stand-in: every refusal here comes before it is read.
std::function<void(const Sandbox&)> made_by(std::string folder, std::string marker, bool study_files) {
  return [folder, marker, study_files](const Sandbox& s) {
    trust::write_text(s.work / folder / ".demfit-output", marker);
    if (!study_files) return;
    trust::write_text(s.work / folder / "study.db", "a finished study's store\n");
    trust::write_text(s.work / folder / "report.md", "# a finished study's report\n");
    trust::write_text(s.work / folder / "best_parameters.json", "{\"amplitude\": 1.2}\n");
  };
}
const std::string kIdentifyMarker = "identify\nThis folder was created by 'demfit identify'.\n";
const std::string kSimulateMarker = "simulate\nThis folder was created by 'demfit simulate'.\n";
const std::string kLegacyMarker = "This folder was created by demfit (--out). demfit may replace it.\n";

void check_refused(const Hostile& h) {
  Sandbox s("battery2/" + trust::safe_name(h.name));
  h.setup(s);
  std::optional<id::StoreLock> lock;
  if (h.lock_out) lock.emplace(s.work / "out");  // this process stands for a running identify
  const auto before_work = trust::snapshot(s.work);
  const auto before_outside = trust::snapshot(s.outside);
  const trust::Result r = s.run(h.args);
  INFO("input: " << h.name << "\nstderr: " << r.err);
  CHECK(r.status != 0);
  CHECK(r.status < 128);  // an error, not a crash
  CHECK(r.err.rfind("demfit: error: ", 0) == 0);
  CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
  CHECK(r.err.size() < 600);
  CHECK(r.err.find(h.field) != std::string::npos);
  CHECK(trust::snapshot(s.work) == before_work);  // nothing created, changed or removed
  CHECK(trust::snapshot(s.outside) == before_outside);
  CHECK(trust::leftovers(s.root).empty());
}

void check_all(const std::vector<Hostile>& inputs) {
  for (const auto& h : inputs) {
    DYNAMIC_SECTION(h.name) { check_refused(h); }
  }
}

}  // namespace

TEST_CASE("a command never replaces or writes into another command's folder or a running study's") {
  const auto pellet = file("case.json", kPellet);
  const std::vector<std::string> simulate{"simulate", "case.json", "--out", "out"};
  check_all({
      {"simulate --out a finished identify folder", all({pellet, made_by("out", kIdentifyMarker, true)}), simulate,
       "holds the output of 'demfit identify'"},
      {"simulate --out the folder of a running study (store locked)",
       all({pellet, made_by("out", kLegacyMarker, false)}), simulate, "in use by another demfit process",
       /*lock_out=*/true},
      {"simulate --out a study folder whose marker names no command", all({pellet, made_by("out", "", true)}), simulate,
       "does not name the command"},
      {"identify --out a simulate folder",
       all({study_with([](json&) {}), made_by("out", kSimulateMarker, false)}),
       {"identify", "study.json", "--out", "out", "--no-plots"},
       "holds the output of 'demfit simulate'"},
      {"diagnose --out an identify folder",
       all({study_with([](json&) {}), made_by("out", kIdentifyMarker, true)}),
       {"diagnose", "study.json", "--out", "out"},
       "holds the output of 'demfit identify'"},
      {"target from-image --out an identify folder",
       all({file("photo.bmp", "BM"), made_by("out", kIdentifyMarker, true)}),
       {"target", "from-image", "photo.bmp", "--diameter", "84mm", "--out", "out"},
       "holds the output of 'demfit identify'"},
      {"identify --out a folder whose study is running",
       all({study_with([](json&) {}), made_by("out", kIdentifyMarker, true)}),
       {"identify", "study.json", "--out", "out", "--resume", "--no-plots"},
       "in use by another demfit process",
       /*lock_out=*/true},
  });
}

TEST_CASE("report never writes over another study's store or results") {
  const auto store_a = made_by("a", kIdentifyMarker, true);
  check_all({
      {"report A --out B holding study B",
       all({store_a, made_by("b", kIdentifyMarker, true)}),
       {"report", "a/study.db", "--out", "b", "--no-plots"},
       "holds another study's store"},
      {"report A --out B holding the report of study C",
       all({store_a,
            made_by("b", "report\nThis folder was created by 'demfit report'.\nstudy: /nowhere/c/study.db\n", false),
            file("b/report.md", "# the report of study C\n")}),
       {"report", "a/study.db", "--out", "b", "--no-plots"},
       "report of another study"},
      {"report A --out a simulate folder",
       all({store_a, made_by("b", kSimulateMarker, false)}),
       {"report", "a/study.db", "--out", "b", "--no-plots"},
       "holds the output of 'demfit simulate'"},
      {"report A --out an old-marker folder with study B",
       all({store_a, made_by("b", kLegacyMarker, true)}),
       {"report", "a/study.db", "--out", "b", "--no-plots"},
       "holds another study's store"},
  });
}

TEST_CASE("export writes only a new regular file, or standard output") {
  const auto store = file("x.db", "a study store\n");
  auto link_to_precious = [](const Sandbox& s) { fs::create_symlink(s.outside / "precious.txt", s.work / "out.k"); };
  check_all({
      {"export --lsdyna onto a measured curve",
       all({store, file("measured.csv", "x_1,y_1\n0,0\n1,1\n")}),
       {"export", "x.db", "--lsdyna", "measured.csv"},
       "already exists"},
      {"export --lsdyna onto a link to another file",
       all({store, link_to_precious}),
       {"export", "x.db", "--lsdyna", "out.k", "--force"},
       "symbolic link"},
      {"export --lsdyna onto a device, even with --force",
       store,
       {"export", "x.db", "--lsdyna", "/dev/null", "--force"},
       "not a regular file"},
      {"export --lsdyna onto a link to standard output",
       all({store, [](const Sandbox& s) { fs::create_symlink("/dev/stdout", s.work / "o.k"); }}),
       {"export", "x.db", "--lsdyna", "o.k", "--force"},
       "symbolic link"},
      {"export --lsdyna onto a folder",
       all({store, [](const Sandbox& s) { fs::create_directory(s.work / "k"); }}),
       {"export", "x.db", "--lsdyna", "k", "--force"},
       "not a regular file"},
      {"export --lsdyna ''", store, {"export", "x.db", "--lsdyna", ""}, "--lsdyna"},
  });
}

// A finished analytic study in work/out whose store claims a DEM case, so that export writes it.
void exportable_study(const Sandbox& s) {
  json study = analytic_study();
  study["stopping"]["max_iterations"] = 2;
  write_study(s, study);
  const auto r = s.run({"identify", "study.json", "--out", "out", "--no-plots"});
  INFO(r.err);
  REQUIRE(r.status == 0);
  sqlite3* db = nullptr;
  REQUIRE(sqlite3_open((s.work / "out" / "study.db").c_str(), &db) == SQLITE_OK);
  const char* claim =
      "UPDATE meta SET value = json_set(value, '$.model.case', 'pellet_compression') WHERE key = 'study_json'";
  REQUIRE(sqlite3_exec(db, claim, nullptr, nullptr, nullptr) == SQLITE_OK);
  sqlite3_close(db);
}

TEST_CASE("export --lsdyna - writes the cards to standard output and no file") {
  Sandbox s("battery2/export_stdout");
  exportable_study(s);
  const auto before = trust::snapshot(s.work);
  const auto r = s.run({"export", "out/study.db", "--lsdyna", "-"});
  INFO(r.err);
  CHECK(r.status == 0);
  CHECK(r.out.find("*CONTROL_DISCRETE_ELEMENT") != std::string::npos);
  CHECK(trust::snapshot(s.work) == before);
}

TEST_CASE("export --force replaces an existing regular keyword file, and only with --force") {
  Sandbox s("battery2/export_force");
  exportable_study(s);
  trust::write_text(s.work / "old.k", "an earlier export\n");
  auto r = s.run({"export", "out/study.db", "--lsdyna", "old.k"});
  CHECK(r.status == 1);
  CHECK(trust::read_text(s.work / "old.k") == "an earlier export\n");
  r = s.run({"export", "out/study.db", "--lsdyna", "old.k", "--force"});
  INFO(r.err);
  CHECK(r.status == 0);
  CHECK(trust::read_text(s.work / "old.k").find("*CONTROL_DISCRETE_ELEMENT") != std::string::npos);
  CHECK(fs::is_regular_file(fs::symlink_status(s.work / "old.k")));
}

TEST_CASE("an output path that leads through a symbolic link is refused") {
  auto link_dir = [](const Sandbox& s) { fs::create_directory_symlink(s.outside, s.work / "link"); };
  check_all({
      {"identify --out link/sub",
       all({study_with([](json&) {}), link_dir}),
       {"identify", "study.json", "--out", "link/sub", "--no-plots"},
       "'link' in 'link/sub' is a symbolic link"},
      {"simulate --out link/sub",
       all({file("case.json", kPellet), link_dir}),
       {"simulate", "case.json", "--out", "link/sub"},
       "is a symbolic link"},
      {"simulate --out link/a/b (deeper)",
       all({file("case.json", kPellet), link_dir}),
       {"simulate", "case.json", "--out", "link/a/b"},
       "is a symbolic link"},
      {"target from-image --out link/sub",
       all({file("photo.bmp", "BM"), link_dir}),
       {"target", "from-image", "photo.bmp", "--diameter", "84mm", "--out", "link/sub"},
       "is a symbolic link"},
  });
}

// A folder whose entries cannot be removed, for root too: the immutable attribute as root (chmod
// does not stop root), mode 0555 otherwise. Undone by the destructor. `made` is false when the
// file system has no immutable attribute.
struct Unchangeable {
  fs::path dir;
  bool made = false;
  bool immutable = false;
  explicit Unchangeable(fs::path folder) : dir(std::move(folder)) {
    if (::geteuid() != 0) {
      made = ::chmod(dir.c_str(), 0555) == 0;
      return;
    }
    immutable = made = set_immutable(true);
  }
  ~Unchangeable() {
    if (immutable) set_immutable(false);
    if (made && !immutable) ::chmod(dir.c_str(), 0755);
  }
  bool set_immutable(bool on) const {
    const int fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY);
    if (fd < 0) return false;
    int flags = 0;
    bool ok = ::ioctl(fd, FS_IOC_GETFLAGS, &flags) == 0;
    flags = on ? (flags | FS_IMMUTABLE_FL) : (flags & ~FS_IMMUTABLE_FL);
    ok = ok && ::ioctl(fd, FS_IOC_SETFLAGS, &flags) == 0;
    ::close(fd);
    return ok;
  }
};

TEST_CASE("simulate refuses an output folder it could not replace before the simulation starts") {
  Sandbox s("battery2/unchangeable_out");
  trust::write_text(s.work / "case.json", kPellet);
  trust::write_text(s.work / "out" / ".demfit-output", kSimulateMarker);
  trust::write_text(s.work / "out" / "summary.txt", "an earlier run\n");
  const auto before_work = trust::snapshot(s.work);
  const Unchangeable locked(s.work / "out");
  if (!locked.made) {
    WARN("this file system cannot make a folder unchangeable; case not run");
    return;
  }
  const trust::Result r = s.run({"simulate", "case.json", "--out", "out"});
  INFO(r.err);
  CHECK(r.status == 1);
  CHECK(r.err.rfind("demfit: error: --out: 'out' cannot be changed", 0) == 0);
  CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
  CHECK(trust::snapshot(s.work) == before_work);
  CHECK(trust::leftovers(s.root).empty());
}

TEST_CASE("simulate refuses an unwritable output place before the simulation starts") {
  check_all({
      {"simulate --out below a read-only file system",
       file("case.json", kPellet),
       {"simulate", "case.json", "--out", "/proc/demfit_trust_out"},
       "--out"},
  });
}

TEST_CASE("a simulation that fails leaves neither its staging folder nor the parents made for it") {
  check_all({
      {"pellets too large for the die, --out in new folders",
       file("case.json", R"({"case": "pellet_compression", "particle": {"radius": 0.05}})"),
       {"simulate", "case.json", "--out", "new/deeper/out"},
       "fewer or smaller particles"},
  });
}

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
