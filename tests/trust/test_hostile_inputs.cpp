// The first battery: bad or hostile inputs given to demfit on the command line. Each one
// must end with exit status != 0 and ONE line "demfit: error: ..." naming the field, leave every
// file of the working folder and of the rest of the disk as it was, and leave no partial output.
#include <catch2/catch.hpp>

#include <functional>

#include <nlohmann/json.hpp>

#include "trust_harness.hpp"

namespace {
using nlohmann::json;
using trust::Sandbox;
namespace fs = std::filesystem;

const fs::path kData = fs::path(DEMFIT_SOURCE_DIR) / "tests" / "identify" / "data";

json analytic_study() { return json::parse(trust::read_text(kData / "analytic_study.json")); }

struct Hostile {
  std::string name;                           // what is wrong
  std::function<void(const Sandbox&)> setup;  // writes the inputs into work/
  std::vector<std::string> args;              // demfit arguments (run in work/)
  std::string field;                          // the message must contain this
};

void write_study(const Sandbox& s, const json& study) {
  trust::write_text(s.work / "study.json", study.dump(2));
  fs::copy_file(kData / "analytic_target.csv", s.work / "analytic_target.csv", fs::copy_options::overwrite_existing);
}
void write_raw_study(const Sandbox& s, const std::string& text) {
  trust::write_text(s.work / "study.json", text);
  fs::copy_file(kData / "analytic_target.csv", s.work / "analytic_target.csv", fs::copy_options::overwrite_existing);
}
// A study with one edit applied to the valid analytic study.
std::function<void(const Sandbox&)> study_with(std::function<void(json&)> edit) {
  return [edit](const Sandbox& s) {
    json study = analytic_study();
    edit(study);
    write_study(s, study);
  };
}
std::function<void(const Sandbox&)> raw_study(std::string text) {
  return [text](const Sandbox& s) { write_raw_study(s, text); };
}
std::function<void(const Sandbox&)> study_and_csv(std::string csv) {
  return [csv](const Sandbox& s) {
    write_study(s, analytic_study());
    trust::write_text(s.work / "analytic_target.csv", csv);
  };
}
std::function<void(const Sandbox&)> case_file(std::string text) {
  return [text](const Sandbox& s) { trust::write_text(s.work / "case.json", text); };
}
const std::vector<std::string> kIdentify{"identify", "study.json", "--out", "out", "--no-plots"};
const std::vector<std::string> kSimulate{"simulate", "case.json", "--out", "out"};
const char* kCase = R"({"case": "pellet_compression"})";

std::string nested(int depth) { return std::string(depth, '[') + "1" + std::string(depth, ']'); }
std::string long_csv(int points) {
  std::string text = "x_1,y_1\n";
  for (int i = 0; i < points; ++i) text += std::to_string(i * 1e-6) + ",0.5\n";
  return text;
}

void check_refused(const Hostile& h) {
  Sandbox s("battery/" + trust::safe_name(h.name));
  h.setup(s);
  const auto before_work = trust::snapshot(s.work);
  const auto before_outside = trust::snapshot(s.outside);
  const trust::Result r = s.run(h.args);
  INFO("input: " << h.name << "\nstderr: " << r.err);
  CHECK(r.status != 0);
  CHECK(r.status < 128);  // an error, not a crash
  CHECK(r.err.rfind("demfit: error: ", 0) == 0);
  CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
  CHECK(r.err.size() < 600);  // short excerpts, never a whole value
  CHECK(r.err.find(h.field) != std::string::npos);
  CHECK(trust::snapshot(s.work) == before_work);  // nothing created, changed or removed
  CHECK(trust::snapshot(s.outside) == before_outside);
  CHECK(trust::leftovers(s.root).empty());
}

}  // namespace

TEST_CASE("a malformed or oversized study file is refused with one line naming the field") {
  const std::vector<Hostile> inputs = {
      {"malformed JSON", raw_study("{\"demfit_study_version\": 1, \"name\": }"), kIdentify, "not valid JSON"},
      {"value nested 100000 deep", raw_study("{\"demfit_study_version\": 1, \"name\": " + nested(100000) + "}"),
       kIdentify, "nested deeper"},
      {"value nested 65 deep in a typed field",
       study_with([](json& j) { j["variables"][0]["lower"] = json::parse(nested(60)); }), kIdentify,
       "variables[0].lower"},
      {"duplicate top-level key", raw_study(R"({"demfit_study_version": 1, "name": "a", "name": "b"})"), kIdentify,
       "'name' appears twice"},
      {"duplicate key inside a variable",
       [](const Sandbox& s) {
         std::string text = analytic_study().dump();
         const auto at = text.find("\"lower\":0.5");
         text.insert(at, "\"lower\":0.7,");
         write_raw_study(s, text);
       },
       kIdentify, "'lower' appears twice"},
      {"max_iterations above INT_MAX", study_with([](json& j) { j["stopping"]["max_iterations"] = 4294967297LL; }),
       kIdentify, "max_iterations"},
      {"max_iterations far above any study", study_with([](json& j) { j["stopping"]["max_iterations"] = 2000000000; }),
       kIdentify, "max_iterations"},
      {"points_per_iteration 10^9", study_with([](json& j) { j["sampling"]["points_per_iteration"] = 1000000000; }),
       kIdentify, "points_per_iteration"},
      {"points_per_iteration negative", study_with([](json& j) { j["sampling"]["points_per_iteration"] = -3; }),
       kIdentify, "points_per_iteration"},
      {"a 10000-character string where a number belongs",
       study_with([](json& j) { j["variables"][0]["lower"] = std::string(10000, 'A'); }), kIdentify,
       "variables[0].lower"},
      {"unsupported format version", study_with([](json& j) { j["demfit_study_version"] = 2; }), kIdentify,
       "demfit_study_version"},
      {"unknown top-level key", study_with([](json& j) { j["stoping"] = json::object(); }), kIdentify, "stoping"},
      {"empty variables", study_with([](json& j) { j["variables"] = json::array(); }), kIdentify, "variables"},
      {"upper below lower", study_with([](json& j) { j["variables"][0]["upper"] = 0.1; }), kIdentify,
       "variables[0].upper"},
      {"initial outside the bounds", study_with([](json& j) { j["variables"][0]["initial"] = 9.0; }), kIdentify,
       "variables[0].initial"},
      {"log scale from zero", study_with([](json& j) { j["variables"][1]["lower"] = 0.0; }), kIdentify,
       "variables[1].log_scale"},
      {"negative seed", study_with([](json& j) { j["seed"] = -1; }), kIdentify, "seed"},
      {"zero weight", study_with([](json& j) { j["targets"][0]["weight"] = 0; }), kIdentify, "targets[0].weight"},
      {"unknown metric", study_with([](json& j) { j["targets"][0]["metric"] = "rms"; }), kIdentify,
       "targets[0].metric"},
      {"gamma_pan above 1.5", study_with([](json& j) { j["domain_reduction"]["gamma_pan"] = 2.0; }), kIdentify,
       "gamma_pan"},
      {"unknown sampling strategy", study_with([](json& j) { j["sampling"]["strategy"] = "random"; }), kIdentify,
       "strategy"},
      {"inline x and y of different length", study_with([](json& j) {
         j["targets"][0].erase("csv");
         j["targets"][0]["x"] = {0.0, 0.5, 1.0};
         j["targets"][0]["y"] = {0.0, 0.5};
       }),
       kIdentify, "targets[0].y"},
      {"inline x holding a string", study_with([](json& j) {
         j["targets"][0].erase("csv");
         j["targets"][0]["x"] = {0.0, "one"};
         j["targets"][0]["y"] = {0.0, 0.5};
       }),
       kIdentify, "targets[0].x"},
      {"two targets alike as file names", study_with([](json& j) {
         j["targets"].push_back(j["targets"][0]);
         j["targets"][0]["name"] = "a/b";
         j["targets"][1]["name"] = "a_b";
       }),
       kIdentify, "targets"},
      {"variable that is not a model parameter", study_with([](json& j) { j["variables"][0]["name"] = "youngs"; }),
       kIdentify, "variables[0].name"},
      {"fixed parameter that is not a model parameter", study_with([](json& j) {
         j["model"]["fixed_parameters"] = {{"youngs", 1.0}};
       }),
       kIdentify, "model.fixed_parameters.youngs"},
  };
  for (const auto& h : inputs) {
    DYNAMIC_SECTION(h.name) { check_refused(h); }
  }
}

TEST_CASE("control characters in any name that reaches a file or a plot are refused") {
  const std::vector<Hostile> inputs = {
      {"newline and gnuplot command in a target name",
       study_with([](json& j) { j["targets"][0]["name"] = "t'\n!touch pwned\n'"; }), kIdentify, "targets[0].name"},
      {"escape character in a target name", study_with([](json& j) { j["targets"][0]["name"] = "t\x1b[2J"; }),
       kIdentify, "targets[0].name"},
      {"newline in the study name", study_with([](json& j) { j["name"] = "s\n*END"; }), kIdentify, "study: name"},
      {"tab in a variable name", study_with([](json& j) { j["variables"][0]["name"] = "amp\tlitude"; }), kIdentify,
       "variables[0].name"},
      {"DEL in a curve name", study_with([](json& j) { j["targets"][0]["curve"] = "resp\x7fonse"; }), kIdentify,
       "targets[0].curve"},
      {"newline in --out (identify)",
       study_with([](json&) {}),
       {"identify", "study.json", "--out", "o\n!touch pwned", "--no-plots"},
       "--out"},
      {"newline in --out (simulate)", case_file(kCase), {"simulate", "case.json", "--out", "o\nx"}, "--out"},
      {"newline in --lsdyna",
       [](const Sandbox& s) { trust::write_text(s.work / "x.db", "not a store"); },
       {"export", "x.db", "--lsdyna", "a\nb.k"},
       "--lsdyna"},
  };
  for (const auto& h : inputs) {
    DYNAMIC_SECTION(h.name) { check_refused(h); }
  }
}

TEST_CASE("a bad curve file is refused naming the file and the line") {
  const std::vector<Hostile> inputs = {
      {"missing curve file", study_with([](json& j) { j["targets"][0]["csv"] = "nothere.csv"; }), kIdentify,
       "nothere.csv"},
      {"curve file is a folder",
       [](const Sandbox& s) {
         json j = analytic_study();
         j["targets"][0]["csv"] = "folder.csv";
         write_study(s, j);
         fs::create_directories(s.work / "folder.csv");
       },
       kIdentify, "is a folder"},
      {"non-number in a row", study_and_csv("x_1,y_1\n0,0\n0.5,abc\n1,1\n"), kIdentify, "line 3"},
      {"row with too few fields", study_and_csv("x_1,y_1\n0,0\n0.5\n1,1\n"), kIdentify, "line 3"},
      {"decimal commas", study_and_csv("x_1,y_1\n0,0\n0,5,0,25\n1,1\n"), kIdentify, "decimal comma"},
      {"no header", study_and_csv("# only a comment\n"), kIdentify, "no header"},
      {"one point only", study_and_csv("x_1,y_1\n0,0\n"), kIdentify, "fewer than 2 points"},
      {"a column missing", study_and_csv("x_1,z_1\n0,0\n1,1\n"), kIdentify, "no column 'y_1'"},
      {"a semicolon-separated spreadsheet export", study_and_csv("x_1;y_1\n0;0\n0,5;0,25\n1;1\n"), kIdentify,
       "separated by ';' or tabs"},
      {"a 5000-byte line", study_and_csv("x_1,y_1\n0," + std::string(5000, '1') + "\n1,1\n"), kIdentify, "longer than"},
      {"more points than the documented limit", study_and_csv(long_csv(100001)), kIdentify, "more than 100000 points"},
      {"infinite value", study_and_csv("x_1,y_1\n0,0\n0.5,inf\n1,1\n"), kIdentify, "targets[0]"},
      {"control characters in a value", study_and_csv("x_1,y_1\n0,0\n0.5,\x1b[31m\n1,1\n"), kIdentify, "line 3"},
  };
  for (const auto& h : inputs) {
    DYNAMIC_SECTION(h.name) { check_refused(h); }
  }
}

TEST_CASE("a study that cannot match its model is refused before anything is created") {
  const std::vector<Hostile> inputs = {
      {"unknown curve name lists the model's curves", study_with([](json& j) { j["targets"][0]["curve"] = "respnse"; }),
       kIdentify, "it produces: loop, response"},
      {"target x-range outside the model's", study_and_csv("x_1,y_1\n5,1\n6,1\n7,1\n"), kIdentify, "does not overlap"},
      {"unknown model", study_with([](json& j) { j["model"]["case"] = "nosuchcase.json"; }), kIdentify, "nosuchcase"},
      {"unknown relative axis", study_with([](json& j) { j["targets"][0]["curve"] = "response@offset"; }), kIdentify,
       "unknown axis '@offset'"},
  };
  for (const auto& h : inputs) {
    DYNAMIC_SECTION(h.name) { check_refused(h); }
  }
}

TEST_CASE("an output folder that demfit did not create is never replaced or written into") {
  auto study = study_with([](json&) {});
  auto user_folder = [study](const Sandbox& s) {
    study(s);
    trust::write_text(s.work / "out" / "thesis.tex", "years of work\n");
  };
  auto plain_file = [study](const Sandbox& s) {
    study(s);
    trust::write_text(s.work / "out", "a file\n");
  };
  auto link_to_outside = [study](const Sandbox& s) {
    study(s);
    fs::create_directory_symlink(s.outside, s.work / "out");
  };
  auto case_in_marked = [](const Sandbox& s) {
    trust::write_text(s.work / "out" / ".demfit-output", "");
    trust::write_text(s.work / "out" / "case.json", kCase);
  };
  auto case_and_user_folder = [user_folder](const Sandbox& s) {
    user_folder(s);
    trust::write_text(s.work / "case.json", kCase);
  };
  auto photo = [](const Sandbox& s) {
    fs::copy_file(fs::path(DEMFIT_SOURCE_DIR) / "data" / "granudrum_mcc" / "granudrum_mcc_15rpm.bmp",
                  s.work / "photo.bmp");
  };
  const std::vector<Hostile> inputs = {
      {"identify --out .", study, {"identify", "study.json", "--out", ".", "--no-plots"}, "working folder"},
      {"identify --out ..",
       study,
       {"identify", "study.json", "--out", "..", "--no-plots"},
       "parent of the working folder"},
      {"identify --out /",
       study,
       {"identify", "study.json", "--out", "/", "--no-plots"},
       "parent of the working folder"},
      {"identify --out a user folder", user_folder, kIdentify, "not created by demfit"},
      {"identify --out a plain file", plain_file, kIdentify, "existing file"},
      {"identify --out a link", link_to_outside, kIdentify, "symbolic link"},
      {"identify --out the folder of its inputs via ./",
       study,
       {"identify", "study.json", "--out", "./", "--no-plots"},
       "working folder"},
      {"simulate --out .", case_file(kCase), {"simulate", "case.json", "--out", "."}, "working folder"},
      {"simulate --out ..", case_file(kCase), {"simulate", "case.json", "--out", ".."}, "parent of the working folder"},
      {"simulate --out a plain file",
       [](const Sandbox& s) {
         trust::write_text(s.work / "case.json", kCase);
         trust::write_text(s.work / "out", "a file\n");
       },
       kSimulate, "existing file"},
      {"simulate --out a user folder", case_and_user_folder, kSimulate, "not created by demfit"},
      {"simulate --out a demfit folder holding the case",
       case_in_marked,
       {"simulate", "out/case.json", "--out", "out"},
       "holds the input"},
      {"simulate --out a link",
       [](const Sandbox& s) {
         trust::write_text(s.work / "case.json", kCase);
         fs::create_directory_symlink(s.outside, s.work / "out");
       },
       kSimulate, "symbolic link"},
      {"diagnose --out .", study, {"diagnose", "study.json", "--out", "."}, "working folder"},
      {"target from-image --out .",
       photo,
       {"target", "from-image", "photo.bmp", "--diameter", "84mm", "--out", "."},
       "working folder"},
      {"target from-image --out ..",
       photo,
       {"target", "from-image", "photo.bmp", "--diameter", "84mm", "--out", ".."},
       "parent of the working folder"},
      {"diagnose --out a user folder",
       user_folder,
       {"diagnose", "study.json", "--out", "out"},
       "not created by demfit"},
      {"reproduce --out .", [](const Sandbox&) {}, {"reproduce", "table2", "--out", "."}, "working folder"},
      {"reproduce --out a user folder", user_folder, {"reproduce", "table2", "--out", "out"}, "not created by demfit"},
  };
  for (const auto& h : inputs) {
    DYNAMIC_SECTION(h.name) { check_refused(h); }
  }
}

TEST_CASE("bad case files and options of simulate are refused before any run") {
  const std::vector<Hostile> inputs = {
      {"duplicate key in a case", case_file(R"({"case": "pellet_compression", "case": "rotary_drum"})"), kSimulate,
       "'case' appears twice"},
      {"case nested 100000 deep", case_file("{\"case\": " + nested(100000) + "}"), kSimulate, "nested deeper"},
      {"NaN noise", case_file(kCase), {"simulate", "case.json", "--out", "out", "--noise", "nan"}, "--noise"},
      {"infinite noise", case_file(kCase), {"simulate", "case.json", "--out", "out", "--noise", "inf"}, "--noise"},
      {"100000 pellets in the die", case_file(R"({"case": "pellet_compression", "pellet": {"count": 100000}})"),
       kSimulate, "count"},
      {"pellet radius larger than the die",
       case_file(R"({"case": "pellet_compression", "particle": {"radius": 0.05}})"), kSimulate,
       "fewer or smaller particles"},
      {"case file is a folder", [](const Sandbox& s) { fs::create_directories(s.work / "case.json"); }, kSimulate,
       "case.json"},
  };
  for (const auto& h : inputs) {
    DYNAMIC_SECTION(h.name) { check_refused(h); }
  }
}

TEST_CASE("bad numeric options of diagnose and identify are refused") {
  auto study = study_with([](json&) {});
  const std::vector<Hostile> inputs = {
      {"diagnose --noise nan", study, {"diagnose", "study.json", "--noise", "nan", "--out", "out"}, "--noise"},
      {"diagnose with an unknown curve",
       study_with([](json& j) { j["targets"][0]["curve"] = "respnse"; }),
       {"diagnose", "study.json", "--out", "out"},
       "targets[0].curve"},
      {"diagnose with a disjoint x-range",
       [](const Sandbox& s) {
         write_study(s, analytic_study());
         trust::write_text(s.work / "analytic_target.csv", "x_1,y_1\n5,1\n6,1\n7,1\n");
       },
       {"diagnose", "study.json", "--out", "out"},
       "does not overlap"},
      {"diagnose --alpha inf", study, {"diagnose", "study.json", "--alpha", "inf", "--out", "out"}, "--alpha"},
      {"identify --run-timeout nan",
       study,
       {"identify", "study.json", "--out", "out", "--run-timeout", "nan"},
       "--run-timeout"},
      {"identify --jobs 0", study, {"identify", "study.json", "--out", "out", "--jobs", "0"}, "--jobs"},
  };
  for (const auto& h : inputs) {
    DYNAMIC_SECTION(h.name) { check_refused(h); }
  }
}
