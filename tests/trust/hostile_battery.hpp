#pragma once
// The second battery of hostile inputs (test_hostile_inputs_2.cpp, test_hostile_values.cpp): a
// case is a command line with its set-up; each must end with exit status != 0 and ONE line
// "demfit: error: ..." naming the field, leave every file of the working folder and of the rest of
// the disk as it was, and leave no partial output. No case runs a simulation.
#include <catch2/catch.hpp>

#include <functional>
#include <optional>

#include <nlohmann/json.hpp>

#include "demfit/identify/store_lock.hpp"
#include "trust_harness.hpp"

namespace hostile {
using nlohmann::json;
using trust::Sandbox;
namespace fs = std::filesystem;
namespace id = demfit::identify;

inline const fs::path kData = fs::path(DEMFIT_SOURCE_DIR) / "tests" / "identify" / "data";
inline const char* kPellet = R"({"case": "pellet_compression"})";
inline const char* kDrum = R"({"case": "rotary_drum"})";

struct Hostile {
  std::string name;                           // what is wrong
  std::function<void(const Sandbox&)> setup;  // writes the inputs into work/
  std::vector<std::string> args;              // demfit arguments (run in work/)
  std::string field;                          // the message must contain this
  bool lock_out = false;                      // this process holds work/out's study lock meanwhile
};

inline json analytic_study() { return json::parse(trust::read_text(kData / "analytic_study.json")); }

inline void write_study(const Sandbox& s, const json& study) {
  trust::write_text(s.work / "study.json", study.dump(2));
  fs::copy_file(kData / "analytic_target.csv", s.work / "analytic_target.csv", fs::copy_options::overwrite_existing);
}
inline std::function<void(const Sandbox&)> study_with(std::function<void(json&)> edit) {
  return [edit](const Sandbox& s) {
    json study = analytic_study();
    edit(study);
    write_study(s, study);
  };
}
inline std::function<void(const Sandbox&)> file(std::string name, std::string text) {
  return [name, text](const Sandbox& s) { trust::write_text(s.work / name, text); };
}
// Several set-ups in order.
inline std::function<void(const Sandbox&)> all(std::vector<std::function<void(const Sandbox&)>> steps) {
  return [steps](const Sandbox& s) {
    for (const auto& step : steps) step(s);
  };
}
// A folder as `demfit <kind>` leaves it (marker first line: the kind), with a study's files when
// it is a study folder. The study.db is a stand-in: every refusal here comes before it is read.
inline std::function<void(const Sandbox&)> made_by(std::string folder, std::string marker, bool study_files) {
  return [folder, marker, study_files](const Sandbox& s) {
    trust::write_text(s.work / folder / ".demfit-output", marker);
    if (!study_files) return;
    trust::write_text(s.work / folder / "study.db", "a finished study's store\n");
    trust::write_text(s.work / folder / "report.md", "# a finished study's report\n");
    trust::write_text(s.work / folder / "best_parameters.json", "{\"amplitude\": 1.2}\n");
  };
}
inline const std::string kIdentifyMarker = "identify\nThis folder was created by 'demfit identify'.\n";
inline const std::string kSimulateMarker = "simulate\nThis folder was created by 'demfit simulate'.\n";
inline const std::string kLegacyMarker = "This folder was created by demfit (--out). demfit may replace it.\n";

inline void check_refused(const Hostile& h) {
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

inline void check_all(const std::vector<Hostile>& inputs) {
  for (const auto& h : inputs) {
    DYNAMIC_SECTION(h.name) { check_refused(h); }
  }
}

}  // namespace hostile
