#pragma once
// Shared by the external-model tests: a study of the fake solver (data/external/fake_solver.sh),
// whose response is force_N = amplitude (1 - exp(-rate time_s)) at 21 times in [0, 1] s.
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace demfit::identify::test {

inline std::filesystem::path external_data_dir() {
  return std::filesystem::path(DEMFIT_SOURCE_DIR) / "tests" / "identify" / "data" / "external";
}

// The fake solver's curve computed here, independently of the program: the target of a study.
inline nlohmann::json fake_solver_target(double amplitude, double rate) {
  std::vector<double> x, y;
  for (int i = 0; i <= 20; ++i) {
    x.push_back(i / 20.0);
    y.push_back(amplitude * (1.0 - std::exp(-rate * x.back())));
  }
  return {{"curve", "response"}, {"x_column", "time_s"}, {"y_column", "force_N"}, {"x", x}, {"y", y}};
}

// The "external" object running the fake solver in `mode` with a time limit [s].
inline nlohmann::json fake_external(const std::string& mode = "normal", double time_limit_s = 20.0) {
  return {{"command", {"./fake_solver.sh", mode}},
          {"template", "in.txt.template"},
          {"parameters", {{"amplitude", "N"}, {"rate", "1/s"}}},
          {"time_limit_s", time_limit_s},
          {"outputs", {{"response", {{"file", "response.csv"}, {"x", "time_s"}, {"y", "force_N"}}}}}};
}

// A study varying amplitude and rate of the fake solver against its curve at (1.3, 4.2).
inline nlohmann::json fake_solver_study(const nlohmann::json& external, int max_iterations = 12) {
  return {{"demfit_study_version", 1},
          {"name", "fake_solver"},
          {"model", {{"external", external}}},
          {"variables",
           {{{"name", "amplitude"}, {"lower", 0.5}, {"upper", 2.0}, {"initial", 1.0}},
            {{"name", "rate"}, {"lower", 1.0}, {"upper", 8.0}, {"initial", 3.0}, {"log_scale", true}}}},
          {"targets", {fake_solver_target(1.3, 4.2)}},
          {"stopping", {{"max_iterations", max_iterations}, {"design_tolerance", 0.0}, {"objective_tolerance", 0.0}}},
          {"seed", 11}};
}

}  // namespace demfit::identify::test
