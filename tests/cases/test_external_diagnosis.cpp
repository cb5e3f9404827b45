// demfit diagnose on an external program: the candidates are the template parameters the study
// declares with off values (model.external.candidates, docs/external-model.md). The program is an
// awk script (data/external_effect/hidden_effect_solver.awk, one process per run) whose curve
//   force_N = amplitude (1 - exp(-rate t)) + late_gain t^3 + offset
// carries two possible effects; the measurement is that curve computed here (independently of
// the script) with or without a late rise, plus seeded Gaussian noise. The diagnosis is run as
// the command line runs it (diagnosis_model_and_candidates, expensive-model options), without
// the replica runs that measure a model's scatter (the script is deterministic). ~70 runs, < 5 s.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "demfit/cases/diagnosis_model.hpp"
#include "demfit/diagnose/workflow.hpp"
#include "demfit/identify/external_model.hpp"
#include "demfit/identify/study_spec.hpp"

using namespace demfit;

namespace {
namespace fs = std::filesystem;

constexpr double kNoise = 0.004;  // [N] noise of the synthetic measurement

fs::path data_dir() { return fs::path(DEMFIT_SOURCE_DIR) / "tests" / "cases" / "data" / "external_effect"; }

nlohmann::json candidates() {
  return nlohmann::json::array(
      {{{"name", "late_rise"}, {"parameter", "late_gain"}, {"off", 0.0}, {"range", {0.0, 2.0}}, {"unit", "N"}},
       {{"name", "offset"}, {"parameter", "offset"}, {"off", 0.0}, {"range", {-0.5, 0.5}}}});
}

nlohmann::json external(const nlohmann::json& with_candidates = candidates()) {
  return {{"command", {"awk", "-f", "hidden_effect_solver.awk", "in.txt"}},
          {"template", "in.txt.template"},
          {"files", {"hidden_effect_solver.awk"}},
          {"parameters", {{"amplitude", "N"}, {"rate", "1/s"}, {"late_gain", "N"}, {"offset", "N"}}},
          {"time_limit_s", 20.0},
          {"outputs", {{"response", {{"file", "response.csv"}, {"x", "time_s"}, {"y", "force_N"}}}}},
          {"candidates", with_candidates}};
}

// The measured curve: amplitude 1.3 N, rate 4.2 1/s, late_gain as given, seeded noise.
nlohmann::json measurement(double late_gain) {
  std::mt19937_64 random(7);
  std::normal_distribution<double> noise(0.0, kNoise);
  std::vector<double> x, y;
  for (int i = 0; i <= 40; ++i) {
    const double t = i / 40.0;
    x.push_back(t);
    y.push_back(1.3 * (1.0 - std::exp(-4.2 * t)) + late_gain * t * t * t + noise(random));
  }
  return {{"curve", "response"}, {"x_column", "time_s"}, {"y_column", "force_N"}, {"x", x}, {"y", y}};
}

nlohmann::json study(const nlohmann::json& model_external, double late_gain) {
  return {{"demfit_study_version", 1},
          {"name", "hidden_effect"},
          {"model", {{"external", model_external}}},
          {"variables",
           {{{"name", "amplitude"}, {"lower", 0.5}, {"upper", 2.0}, {"initial", 1.2}},
            {{"name", "rate"}, {"lower", 1.0}, {"upper", 8.0}, {"initial", 4.0}}}},
          {"targets", {measurement(late_gain)}},
          {"stopping", {{"max_iterations", 4}}},
          {"seed", 3}};
}

std::size_t run_count(const fs::path& out) {
  std::size_t n = 0;
  for ([[maybe_unused]] const auto& entry : fs::directory_iterator(out / identify::kExternalRunsFolder)) ++n;
  return n;
}

diagnose::Diagnosis diagnose_study(double late_gain, const std::string& folder) {
  const identify::StudySpec spec = identify::parse_study(study(external(), late_gain), data_dir());
  const fs::path out = fs::path(DEMFIT_BINARY_DIR) / "tests" / "cases" / folder;
  fs::remove_all(out);
  std::vector<diagnose::EffectCandidate> found;
  const auto model = cases::diagnosis_model_and_candidates(spec, found, out);
  REQUIRE(cases::uses_dem(spec));
  diagnose::DiagnoseOptions options = diagnose::expensive_model_options();  // as demfit diagnose does
  options.noise_sigma = kNoise;
  // The script is deterministic: replica runs would measure a scatter of exactly 0.
  options.scatter_replicas = 0;
  const diagnose::Diagnosis d = diagnose::run_diagnosis(spec, *model, found, options);
  int evaluations = d.base.evaluations;
  for (const auto& r : d.refits) evaluations += r.fit.evaluations;
  std::printf("external diagnosis (late_gain %g): verdict %s, %d fit evaluations (%zu runs in all)\n", late_gain,
              diagnose::verdict_text(d.verdict), evaluations, run_count(out));
  fs::remove_all(out);
  return d;
}

std::string external_spec_error(const nlohmann::json& with_candidates) {
  try {
    identify::parse_external_spec(external(with_candidates), "model.external");
  } catch (const std::exception& e) {
    return e.what();
  }
  return "accepted";
}

}  // namespace

TEST_CASE("An external study's declared candidates become diagnose candidates in the parameter's unit",
          "[external][diagnose]") {
  const identify::StudySpec spec = identify::parse_study(study(external(), 0.0), data_dir());
  std::vector<diagnose::EffectCandidate> found;
  const fs::path out = fs::path(DEMFIT_BINARY_DIR) / "tests" / "cases" / "external_candidates";
  const auto model = cases::diagnosis_model_and_candidates(spec, found, out);
  REQUIRE(found.size() == 2);
  CHECK(found[0].name == "late_rise");
  REQUIRE(found[0].parameters.size() == 1);
  CHECK(found[0].parameters[0].name == "late_gain");
  CHECK(found[0].parameters[0].lower == 0.0);
  CHECK(found[0].parameters[0].upper == 2.0);
  CHECK(found[0].parameters[0].off_value == 0.0);
  CHECK(found[0].parameters[0].unit == "N");
  CHECK(found[1].parameters[0].unit == "N");  // taken from model.external.parameters
  // The base model runs with every candidate off.
  CHECK(model->default_parameters().at("late_gain") == 0.0);
  CHECK(model->default_parameters().at("offset") == 0.0);
}

TEST_CASE("diagnose names the late rise hidden in an external program's curve", "[external][diagnose]") {
  const diagnose::Diagnosis d = diagnose_study(0.4, "external_diagnosis_hidden");
  INFO(d.summary);
  REQUIRE(d.verdict == diagnose::Verdict::effect_identified);
  REQUIRE(d.chosen >= 0);
  CHECK(d.refits[d.chosen].effect == "late_rise");
}

TEST_CASE("diagnose names nothing when the external program's curve has no hidden effect", "[external][diagnose]") {
  const diagnose::Diagnosis d = diagnose_study(0.0, "external_diagnosis_none");
  INFO(d.summary);
  CHECK(d.verdict == diagnose::Verdict::no_missing_effect);
  CHECK(d.chosen == -1);
}

TEST_CASE("A candidate whose parameter is not in the template is refused naming the field", "[external][input]") {
  auto c = candidates();
  c[0]["parameter"] = "ced";
  const std::string error = external_spec_error(c);
  CHECK(error.find("model.external.candidates[0].parameter") != std::string::npos);
  CHECK(error.find("'ced' is not a parameter of the template") != std::string::npos);
  CHECK(error.find('\n') == std::string::npos);
}

TEST_CASE("A candidate whose off value lies outside its range is refused naming the field", "[external][input]") {
  auto c = candidates();
  c[1]["off"] = 0.7;
  const std::string error = external_spec_error(c);
  CHECK(error.find("model.external.candidates[1].off") != std::string::npos);
  CHECK(error.find("outside the range") != std::string::npos);
  CHECK(error.find('\n') == std::string::npos);
}

TEST_CASE("Two candidates with one name are refused naming the second", "[external][input]") {
  auto c = candidates();
  c[1]["name"] = "late_rise";
  const std::string error = external_spec_error(c);
  CHECK(error.find("model.external.candidates[1].name") != std::string::npos);
  CHECK(error.find("names two candidates") != std::string::npos);
}

TEST_CASE("A candidate's unit must be its parameter's declared unit", "[external][input]") {
  auto c = candidates();
  c[0]["unit"] = "J/m^3";
  const std::string error = external_spec_error(c);
  CHECK(error.find("model.external.candidates[0].unit") != std::string::npos);
  CHECK(error.find("('N')") != std::string::npos);
}
