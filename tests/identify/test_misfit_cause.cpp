// A misfit far above the noise names its likely cause in order (study_warnings.hpp): another
// stored run that fits clearly better means the search has not converged; no better run means
// the model, the units or the fill.
#include <catch2/catch.hpp>

#include <string>
#include <vector>

#include "demfit/identify/study_warnings.hpp"

namespace {
namespace id = demfit::identify;

// A line with alternating +-0.01 noise (sigma = 0.04/sqrt(6) = 0.0163 MPa).
std::vector<double> noisy_line() {
  std::vector<double> y;
  for (int i = 0; i < 21; ++i) y.push_back(0.5 * i + (i % 2 ? 0.01 : -0.01));
  return y;
}

std::vector<double> shifted_line(double offset) {
  std::vector<double> y;
  for (int i = 0; i < 21; ++i) y.push_back(0.5 * i + offset);
  return y;
}

id::StudySpec spec_with_target() {
  id::StudySpec spec;
  spec.variables.push_back({"k", 1.0, 2.0, 1.5, false, 1.0});
  spec.max_iterations = 4;
  id::TargetSpec t;
  t.name = "pv";
  t.curve = "pressure_volume";
  std::vector<double> x;
  for (int i = 0; i < 21; ++i) x.push_back(i);
  t.data = {"volume_cm3", "pressure_MPa", x, noisy_line()};
  spec.targets.push_back(t);
  return spec;
}

id::EvaluationRecord stored_run(int point, const std::vector<double>& y) {
  id::EvaluationRecord r;
  r.point = point;
  r.kind = "design";
  r.ok = true;
  r.objective = 1.0;
  r.parameters = {{"k", 1.5}};
  std::vector<double> x;
  for (int i = 0; i < 21; ++i) x.push_back(i);
  r.curves["pressure_volume"] = {"volume_cm3", "pressure_MPa", x, y};
  return r;
}

// The first warning containing `text`, or "" when none does.
std::string warning_with(const std::vector<std::string>& warnings, const std::string& text) {
  for (const auto& w : warnings)
    if (w.find(text) != std::string::npos) return w;
  return "";
}

std::string misfit_warning(const std::vector<std::string>& warnings) {
  return warning_with(warnings, "x the noise of the data");
}

}  // namespace

TEST_CASE("an answer missing the data while another stored run fits within the noise says the search has not converged") {
  const auto spec = spec_with_target();
  const std::vector<id::EvaluationRecord> runs{stored_run(0, shifted_line(0.5)), stored_run(1, shifted_line(0.0))};
  const auto d = id::study_diagnostics(spec, runs, {}, &runs[0], nlohmann::json{{"converged", false}});
  const std::string w = misfit_warning(d.warnings);
  INFO(w);
  CHECK(w.find("the search has not converged: run 0/1 fits it") != std::string::npos);
  CHECK(w.find("model, the units or the fill") == std::string::npos);
}

TEST_CASE("an answer missing the data when no stored run fits better blames the model, the units or the fill") {
  const auto spec = spec_with_target();
  const std::vector<id::EvaluationRecord> runs{stored_run(0, shifted_line(0.5)), stored_run(1, shifted_line(0.6)),
                                               stored_run(2, shifted_line(-0.45))};
  const auto d = id::study_diagnostics(spec, runs, {}, &runs[0], nlohmann::json{{"converged", true}});
  const std::string w = misfit_warning(d.warnings);
  INFO(w);
  CHECK(w.find("no stored run fits it clearly better: the model, the units or the fill") != std::string::npos);
  CHECK(w.find("has not converged") == std::string::npos);
}

namespace {

// A result whose posterior pins k and leaves w free (an interval over most of its bounds).
nlohmann::json result_with_posterior(bool w_unidentifiable) {
  nlohmann::json variables;
  variables["k"] = {{"lower_95", 1.45}, {"upper_95", 1.55}, {"unidentifiable", false}};
  variables["w"] = {{"lower_95", 0.1}, {"upper_95", w_unidentifiable ? 0.9 : 0.3}, {"unidentifiable", w_unidentifiable}};
  return {{"converged", true}, {"uncertainty", {{"posterior", {{"variables", variables}}}}}};
}

std::string identifiability_warning(const std::vector<std::string>& warnings) {
  return warning_with(warnings, "not identifiable");
}

}  // namespace

TEST_CASE("a variable the data cannot pin is named in a warning that says what would pin it") {
  auto spec = spec_with_target();
  spec.variables.push_back({"w", 0.0, 1.0, 0.5, false, 1.0});
  auto answer = stored_run(0, noisy_line());
  answer.parameters["w"] = 0.2;
  const std::vector<id::EvaluationRecord> runs{answer};
  const auto flagged = id::study_diagnostics(spec, runs, {}, &runs[0], result_with_posterior(true));
  const std::string w = identifiability_warning(flagged.warnings);
  INFO(w);
  CHECK(w.find("variable 'w' is not identifiable") != std::string::npos);
  CHECK(w.find("'k'") == std::string::npos);
  CHECK(w.find("another speed, fill or load path") != std::string::npos);
  const auto pinned = id::study_diagnostics(spec, runs, {}, &runs[0], result_with_posterior(false));
  CHECK(identifiability_warning(pinned.warnings).empty());
}
