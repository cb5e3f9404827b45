// `demfit export --liggghts`: the LIGGGHTS 3.8 material fixes and contact models of a Hertz–Mindlin
// answer (cases/liggghts_export.hpp). The values are read back from the written lines and compared
// with the case and the answer; the snippet is run unchanged in LIGGGHTS itself on a small bed.
#include <catch2/catch.hpp>

#include <algorithm>
#include <map>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "../trust/trust_harness.hpp"
#include "demfit/cases/case_spec.hpp"
#include "demfit/cases/liggghts_export.hpp"
#include "demfit/identify/run_program.hpp"
#include "demfit/identify/study_spec.hpp"
#include "demfit/identify/study_store.hpp"

namespace {
namespace fs = std::filesystem;
namespace cases = demfit::cases;
namespace id = demfit::identify;
using json = nlohmann::json;

// A small Hertz drum: particle and wall materials differ, wall friction given separately, so that
// every entry of the snippet has its own value to find.
json hertz_drum_case() {
  return {{"case", "rotary_drum"},
          {"particle", {{"radius", 0.0015}, {"density", 1580.0}, {"youngs_modulus", 5.0e6}, {"poisson_ratio", 0.3}}},
          {"contact", {{"law", "hertz_mindlin"}, {"restitution", 0.45}, {"frics", 0.4}, {"fricr", 0.1}}},
          {"wall_contact",
           {{"youngs_modulus", 7.0e6}, {"poisson_ratio", 0.25}, {"frics", 0.35}, {"fricr", 0.05}}},
          {"time_step", {{"value", 1.0e-5}}},
          {"drum", {{"diameter", 0.05}, {"length", 0.01}, {"particle_count", 300}}}};
}

// The same drum with its wall friction tied to the particles' (ratio released), SJKR2 cohesion and
// the epsd2 rolling model.
json tied_cohesive_case() {
  json c = hertz_drum_case();
  c["contact"]["cohesion_energy_density"] = 2000.0;
  c["contact"]["cohesion_model"] = "sjkr2";
  c["contact"]["rolling_model"] = "epsd2";
  c["wall_contact"] = {{"youngs_modulus", 7.0e6}, {"poisson_ratio", 0.25}, {"friction_as_particles", true}};
  return c;
}

cases::IdentifiedVariables interval_of(const std::string& name, double value, double lower, double upper) {
  id::ReportedInterval interval;
  interval.available = true;
  interval.value = value;
  interval.lower = lower;
  interval.upper = upper;
  interval.method = "posterior";
  return {{name, interval}};
}

// The numbers after "property/global <name> <style> [n]" on the snippet's fix line for `name`.
std::vector<double> fix_values(const std::string& text, const std::string& name) {
  const std::regex line("fix \\S+ all property/global " + name + " (peratomtypepair 2|peratomtype)([^\\n]*)");
  std::smatch m;
  if (!std::regex_search(text, m, line)) return {};
  std::istringstream in(m[2].str());
  std::vector<double> values;
  for (double v; in >> v;) values.push_back(v);
  return values;
}

std::string line_starting(const std::string& text, const std::string& start) {
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);)
    if (line.rfind(start, 0) == 0) return line;
  return {};
}

}  // namespace

TEST_CASE("The LIGGGHTS export writes the answer's values and the case's materials into the property fixes") {
  const cases::CaseSpec base = cases::parse_case(hertz_drum_case());
  const std::string text =
      cases::liggghts_snippet(base, {{"frics", 0.523}, {"fricr", 0.137}}, interval_of("frics", 0.523, 0.47, 0.58), "t");
  INFO(text);
  // Atom type 1 = particles, 2 = walls; type pairs 1-1, 1-2, 2-1, 2-2.
  CHECK(fix_values(text, "youngsModulus") == std::vector<double>{5.0e6, 7.0e6});
  CHECK(fix_values(text, "poissonsRatio") == std::vector<double>{0.3, 0.25});
  CHECK(fix_values(text, "coefficientRestitution") == std::vector<double>{0.45, 0.45, 0.45, 0.45});
  CHECK(fix_values(text, "coefficientFriction") == std::vector<double>{0.523, 0.35, 0.35, 0.35});
  CHECK(fix_values(text, "coefficientRollingFriction") == std::vector<double>{0.137, 0.05, 0.05, 0.05});
  CHECK(fix_values(text, "cohesionEnergyDensity").empty());  // cohesion off: no fix, no cohesion model
  CHECK(line_starting(text, "pair_style") == "pair_style gran model hertz tangential history rolling_friction cdt");
  CHECK(line_starting(text, "pair_coeff") == "pair_coeff * *");
  CHECK(line_starting(text, "variable demfit_wall_model") ==
        "variable demfit_wall_model string \"model hertz tangential history rolling_friction cdt\"");
}

TEST_CASE("The LIGGGHTS export states each identified value with its 95 % interval and units as comments") {
  const cases::CaseSpec base = cases::parse_case(hertz_drum_case());
  const std::string text =
      cases::liggghts_snippet(base, {{"frics", 0.523}}, interval_of("frics", 0.523, 0.47, 0.58), "study 's', run 2/1");
  INFO(text);
  CHECK(text.rfind("# demfit export for LIGGGHTS 3.8: study 's', run 2/1\n", 0) == 0);
  CHECK(text.find("particle-particle frics = 0.523 [-] (identified, 95 % interval [0.47, 0.58] (posterior))") !=
        std::string::npos);
  CHECK(text.find("restitution = 0.45 [-] (case value)") != std::string::npos);
  CHECK(text.find("youngsModulus [Pa]") != std::string::npos);
  CHECK(text.find("SI units") != std::string::npos);
  // Every line is a comment or a LIGGGHTS command: no text of the title can start a command.
  const std::string hostile = cases::liggghts_snippet(base, {}, {}, "x\nrun 1000000");
  CHECK(line_starting(hostile, "run").empty());
}

TEST_CASE("The LIGGGHTS export writes cohesion, the case's rolling model and the tied wall friction ratio") {
  const cases::CaseSpec base = cases::parse_case(tied_cohesive_case());
  const std::string text = cases::liggghts_snippet(base, {{"frics", 0.5}, {"fricr", 0.2}, {"wall_friction_ratio", 0.6}},
                                                   interval_of("wall_friction_ratio", 0.6, 0.4, 0.9), "t");
  INFO(text);
  CHECK(fix_values(text, "coefficientFriction") == std::vector<double>{0.5, 0.3, 0.3, 0.3});  // 0.6 x 0.5
  CHECK(fix_values(text, "coefficientRollingFriction") == std::vector<double>{0.2, 0.2, 0.2, 0.2});
  CHECK(fix_values(text, "cohesionEnergyDensity") == std::vector<double>{2000.0, 2000.0, 2000.0, 2000.0});
  CHECK(line_starting(text, "pair_style") ==
        "pair_style gran model hertz tangential history cohesion sjkr2 rolling_friction epsd2");
  CHECK(text.find("wall_friction_ratio = 0.6 [-] (identified, 95 % interval [0.4, 0.9] (posterior)) x frics") !=
        std::string::npos);
  CHECK(text.find("cohesionEnergyDensity [J/m^3]") != std::string::npos);
}

TEST_CASE("The LIGGGHTS export refuses an lsdyna_linear case in one line saying why") {
  json linear = hertz_drum_case();
  linear["contact"] = {{"normk", 0.01}, {"frics", 0.4}};
  linear["wall_contact"] = {{"frics", 0.3}};
  const cases::CaseSpec base = cases::parse_case(linear);
  try {
    (void)cases::liggghts_snippet(base, {}, {}, "t");
    FAIL("an lsdyna_linear case was exported");
  } catch (const std::runtime_error& e) {
    const std::string message = e.what();
    CHECK(message.find('\n') == std::string::npos);
    CHECK(message.find("lsdyna_linear") != std::string::npos);
    CHECK(message.find("NORMK") != std::string::npos);
    CHECK(message.find("--lsdyna") != std::string::npos);
  }
}

TEST_CASE("The LIGGGHTS export of several experiments writes their one material, and refuses two materials") {
  json fast = hertz_drum_case();
  fast["drum"]["rpm"] = 45.0;  // another speed: the same material
  const std::vector<std::pair<std::string, cases::CaseSpec>> same = {
      {"rpm15", cases::parse_case(hertz_drum_case())}, {"rpm45", cases::parse_case(fast)}};
  const std::string text = cases::liggghts_snippet(same, {{"frics", 0.523}}, {}, "t");
  INFO(text);
  CHECK(fix_values(text, "coefficientFriction") == std::vector<double>{0.523, 0.35, 0.35, 0.35});
  CHECK(text.find("experiments rpm15, rpm45") != std::string::npos);

  json other = hertz_drum_case();
  other["contact"]["restitution"] = 0.6;
  const std::vector<std::pair<std::string, cases::CaseSpec>> differ = {
      {"rpm15", cases::parse_case(hertz_drum_case())}, {"wet", cases::parse_case(other)}};
  try {
    (void)cases::liggghts_snippet(differ, {{"frics", 0.523}}, {}, "t");
    FAIL("two materials were exported as one");
  } catch (const std::runtime_error& e) {
    const std::string message = e.what();
    CHECK(message.find('\n') == std::string::npos);
    CHECK(message.find("'rpm15' and 'wet'") != std::string::npos);
    CHECK(message.find("coefficientRestitution") != std::string::npos);
  }
}

namespace {

// A finished one-run study store of `case_json` (nullptr: the built-in pellet case, whose law is
// lsdyna_linear) whose answer sets frics = 0.523 with the interval [0.47, 0.58].
void one_run_store(const fs::path& db, const json& case_json) {
  const json study = {
      {"demfit_study_version", 1},
      {"name", "export"},
      {"model", {{"case", case_json.is_null() ? "pellet_compression" : "drum.json"}}},
      {"variables", {{{"name", "frics"}, {"lower", 0.1}, {"upper", 0.9}, {"initial", 0.3}}}},
      {"targets",
       {{{"curve", "pressure_volume"}, {"x_column", "v"}, {"y_column", "p"}, {"x", {1.0, 2.0}}, {"y", {1.0, 2.0}}}}},
      {"seed", 1}};
  const id::StudySpec spec = id::parse_study(study, db.parent_path());
  const json resolved = case_json.is_null() ? json() : cases::to_json(cases::parse_case(case_json));
  auto store = id::StudyStore::open_for_run(db, spec, false, resolved);
  id::EvaluationRecord r;
  r.kind = "initial";
  r.unit_x = {0.5};
  r.parameters = {{"frics", 0.523}};
  r.curves["pressure_volume"] = id::Curve{"v", "p", {1.0, 2.0}, {1.0, 2.0}};
  r.objective = 0.01;
  r.ok = true;
  store.add_evaluation(r);
  const json posterior = {{"variables", {{"frics", {{"lower_95", 0.47}, {"upper_95", 0.58}}}}}};
  store.put_result({{"best_iteration", 0}, {"best_point", 0}, {"best_objective", 0.01},
                    {"best_parameters", {{"frics", 0.523}}}, {"best_variables", {{"frics", 0.523}}},
                    {"runs", 1}, {"failed_runs", 0}, {"iterations", 1}, {"converged", true},
                    {"stop_reason", "converged"}, {"final_selection", nullptr}, {"wall_seconds", 1.0},
                    {"uncertainty", {{"posterior", posterior}}}});
}

// A finished one-run store of a study with two experiments (drum speeds 15 and 45 rpm) whose
// resolved cases are recorded; `restitution_45` sets the second experiment's material.
void two_experiment_store(const fs::path& db, double restitution_45) {
  const json target = {{"curve", "free_surface"}, {"x_column", "x_mm"}, {"y_column", "height_mm"},
                       {"x", {1.0, 2.0}}, {"y", {1.0, 2.0}}};
  json study = {{"demfit_study_version", 1},
                {"name", "speeds"},
                {"experiments",
                 {{{"name", "rpm15"}, {"model", {{"case", "drum.json"}}}, {"targets", {target}}},
                  {{"name", "rpm45"}, {"model", {{"case", "drum.json"}}}, {"targets", {target}}}}},
                {"variables", {{{"name", "frics"}, {"lower", 0.1}, {"upper", 0.9}, {"initial", 0.3}}}},
                {"seed", 1}};
  const id::StudySpec spec = id::parse_study(study, db.parent_path());
  json fast = hertz_drum_case();
  fast["drum"]["rpm"] = 45.0;
  fast["contact"]["restitution"] = restitution_45;
  const json resolved = {{"rpm15", cases::to_json(cases::parse_case(hertz_drum_case()))},
                         {"rpm45", cases::to_json(cases::parse_case(fast))}};
  auto store = id::StudyStore::open_for_run(db, spec, false, resolved);
  id::EvaluationRecord r;
  r.kind = "initial";
  r.unit_x = {0.5};
  r.parameters = {{"frics", 0.523}};
  r.curves["rpm15/free_surface"] = id::Curve{"x_mm", "height_mm", {1.0, 2.0}, {1.0, 2.0}};
  r.curves["rpm45/free_surface"] = id::Curve{"x_mm", "height_mm", {1.0, 2.0}, {1.0, 2.0}};
  r.objective = 0.01;
  r.ok = true;
  store.add_evaluation(r);
  store.put_result({{"best_iteration", 0}, {"best_point", 0}, {"best_objective", 0.01},
                    {"best_parameters", {{"frics", 0.523}}}, {"best_variables", {{"frics", 0.523}}},
                    {"runs", 1}, {"failed_runs", 0}, {"iterations", 1}, {"converged", true},
                    {"stop_reason", "converged"}, {"final_selection", nullptr}, {"wall_seconds", 1.0},
                    {"uncertainty", nullptr}});
}

}  // namespace

TEST_CASE("export --liggghts writes a new file, refuses an existing one without --force and writes - to stdout") {
  trust::Sandbox s("liggghts_export_files");
  fs::create_directories(s.work / "study");
  one_run_store(s.work / "study" / "study.db", hertz_drum_case());
  auto r = s.run({"export", "study/study.db", "--liggghts", "material.in"});
  INFO(r.err);
  REQUIRE(r.status == 0);
  const std::string written = trust::read_text(s.work / "material.in");
  CHECK(fix_values(written, "coefficientFriction") == std::vector<double>{0.523, 0.35, 0.35, 0.35});
  CHECK(written.find("95 % interval [0.47, 0.58] (posterior)") != std::string::npos);

  trust::write_text(s.work / "material.in", "the user's own input\n");
  r = s.run({"export", "study/study.db", "--liggghts", "material.in"});
  CHECK(r.status == 1);
  CHECK(r.err.find("--liggghts") != std::string::npos);
  CHECK(trust::read_text(s.work / "material.in") == "the user's own input\n");
  r = s.run({"export", "study/study.db", "--liggghts", "material.in", "--force"});
  CHECK(r.status == 0);
  CHECK(trust::read_text(s.work / "material.in") == written);

  r = s.run({"export", "study/study.db", "--liggghts", "-"});
  CHECK(r.status == 0);
  CHECK(r.out == written);
  r = s.run({"export", "study/study.db", "--liggghts", "a.in", "--lsdyna", "a.k"});
  CHECK(r.status != 0);
  CHECK(!fs::exists(s.work / "a.in"));
  CHECK(!fs::exists(s.work / "a.k"));
}

TEST_CASE("export --liggghts of an LS-DYNA-law study fails in one line and writes nothing") {
  trust::Sandbox s("liggghts_export_linear");
  fs::create_directories(s.work / "study");
  one_run_store(s.work / "study" / "study.db", nullptr);
  const auto before = trust::snapshot(s.work);
  const auto r = s.run({"export", "study/study.db", "--liggghts", "material.in"});
  INFO(r.err);
  CHECK(r.status == 1);
  CHECK(r.err.rfind("demfit: error: --liggghts: ", 0) == 0);
  CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
  CHECK(r.err.find("lsdyna_linear") != std::string::npos);
  CHECK(trust::snapshot(s.work) == before);
}

namespace {

// A LIGGGHTS driver around the snippet: a 2-type box, gravity, a floor of wall type 2 with the
// exported wall model, 200 particles of the case's density and radius poured and run 5000 steps
// (50 ms: they reach the floor, so particle-wall contacts are computed too).
constexpr const char* kDriver = R"(atom_style granular
atom_modify map array
boundary f f f
newton off
communicate single vel yes
units si
region box block -0.012 0.012 -0.012 0.012 0.0 0.04 units box
create_box 2 box
neighbor 0.0006 bin
neigh_modify delay 0
include material.in
timestep 1e-5
fix gravity all gravity 9.81 vector 0.0 0.0 -1.0
fix floor all wall/gran ${demfit_wall_model} primitive type 2 zplane 0.0
fix pts all particletemplate/sphere 15485863 atom_type 1 density constant 1580 radius constant 0.0015
fix pdd all particledistribution/discrete 32452843 1 pts 1.0
region fill block -0.01 0.01 -0.01 0.01 0.002 0.038 units box
fix ins all insert/pack seed 49979693 distributiontemplate pdd insert_every once overlapcheck yes all_in yes particles_in_region 200 region fill
fix integrate all nve/sphere
thermo_style custom step atoms ke
thermo 1000
run 5000
)";

// Runs the exported `snippet` in LIGGGHTS (a 60 s limit) and returns its log; status in `status`.
std::string run_in_liggghts(const std::string& name, const std::string& snippet, int& status) {
  trust::Sandbox s(name);
  trust::write_text(s.work / "material.in", snippet);
  trust::write_text(s.work / "driver.in", kDriver);
  status = id::run_program({"timeout", "60", "liggghts", "-in", "driver.in", "-log", "log.liggghts"}, s.work);
  return trust::read_text(s.work / "log.liggghts");
}

}  // namespace

TEST_CASE("LIGGGHTS 3.8 runs the exported snippet unchanged and echoes its values") {
  REQUIRE(id::program_available("liggghts"));  // installed by scripts/setup (Debian package liggghts)
  for (const json& case_json : {hertz_drum_case(), tied_cohesive_case()}) {
    const cases::CaseSpec base = cases::parse_case(case_json);
    const std::string snippet =
        cases::liggghts_snippet(base, {{"frics", 0.523}}, interval_of("frics", 0.523, 0.47, 0.58), "run check");
    int status = -1;
    const std::string log = run_in_liggghts("liggghts_run_" + case_json["contact"].value("rolling_model", "cdt"),
                                            snippet, status);
    INFO(snippet << "\n--- LIGGGHTS log ---\n" << log);
    CHECK(status == 0);
    CHECK(log.find("for 5000 steps with 200 atoms") != std::string::npos);
    // LIGGGHTS echoes each command it read: the fixes carry the snippet's values.
    for (const char* property : {"youngsModulus", "poissonsRatio", "coefficientRestitution", "coefficientFriction",
                                 "coefficientRollingFriction", "cohesionEnergyDensity"})
      CHECK(fix_values(log, property) == fix_values(snippet, property));
    CHECK(fix_values(log, "coefficientFriction").at(0) == Approx(0.523).epsilon(1e-12));
    CHECK(log.find(line_starting(snippet, "pair_style")) != std::string::npos);
  }
}

TEST_CASE("export --liggghts of a study with experiments writes their shared material, or refuses two materials") {
  trust::Sandbox s("liggghts_export_experiments");
  fs::create_directories(s.work / "same");
  two_experiment_store(s.work / "same" / "study.db", 0.45);
  auto r = s.run({"export", "same/study.db", "--liggghts", "material.in"});
  INFO(r.err);
  REQUIRE(r.status == 0);
  const std::string written = trust::read_text(s.work / "material.in");
  CHECK(fix_values(written, "coefficientFriction") == std::vector<double>{0.523, 0.35, 0.35, 0.35});
  CHECK(written.find("experiments rpm15, rpm45") != std::string::npos);
  r = s.run({"export", "same/study.db", "--lsdyna", "cards.k"});  // no full parameter set for LS-DYNA
  CHECK(r.status == 1);
  CHECK(!fs::exists(s.work / "cards.k"));

  fs::create_directories(s.work / "differ");
  two_experiment_store(s.work / "differ" / "study.db", 0.6);
  r = s.run({"export", "differ/study.db", "--liggghts", "other.in"});
  CHECK(r.status == 1);
  CHECK(r.err.find("'rpm15' and 'rpm45' simulate different contact values") != std::string::npos);
  CHECK(!fs::exists(s.work / "other.in"));
}
