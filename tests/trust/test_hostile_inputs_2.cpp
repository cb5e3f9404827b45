// The second battery of hostile inputs, folders and files: a command never destroys another
// command's study or results, never writes over what is not its own (devices, links, existing
// files, paths through links), and refuses an unwritable place before the work. The rules each
// case obeys are in hostile_battery.hpp.
#include <linux/fs.h>
#include <sqlite3.h>
#include <sys/ioctl.h>
#include <sys/stat.h>

#include <catch2/catch.hpp>

#include "demfit/identify/study_spec.hpp"
#include "demfit/identify/study_store.hpp"
#include "hostile_battery.hpp"

using namespace hostile;

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

namespace {

// A finished pellet study in work/out, written through the store's own API (every row carries
// its checksum, so an SQL edit would be refused): one successful run, stored as the answer.
void exportable_study(const Sandbox& s) {
  namespace id = demfit::identify;
  const json study = {{"demfit_study_version", 1},
                      {"name", "exportable"},
                      {"model", {{"case", "pellet_compression"}}},
                      {"variables", {{{"name", "frics"}, {"lower", 0.1}, {"upper", 0.9}, {"initial", 0.3}}}},
                      {"targets",
                       {{{"curve", "pressure_volume"},
                         {"x_column", "volume_cm3"},
                         {"y_column", "pressure_MPa"},
                         {"x", {60.0, 55.0, 50.0}},
                         {"y", {0.1, 0.5, 2.0}}}}}};
  fs::create_directories(s.work / "out");
  auto store = id::StudyStore::open_for_run(s.work / "out" / "study.db", id::parse_study(study, s.work), false,
                                            nullptr);
  id::EvaluationRecord r;
  r.kind = "initial";
  r.unit_x = {0.25};
  r.parameters = {{"frics", 0.3}, {"normk", 0.875046}, {"sheark", 0.299582}};
  r.curves["pressure_volume"] = id::Curve{"volume_cm3", "pressure_MPa", {60.0, 55.0, 50.0}, {0.1, 0.5, 2.0}};
  r.objective = 0.01;
  r.wall_seconds = 1.0;
  r.ok = true;
  store.add_evaluation(r);
  store.put_result({{"best_iteration", 0}, {"best_point", 0}, {"best_objective", 0.01},
                    {"best_parameters", r.parameters}, {"converged", false}, {"uncertainty", nullptr}});
}

}  // namespace

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

namespace {

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

}  // namespace

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
