#pragma once
// Shared helpers of the identify tests: temporary folders and a study on the analytic model.
#include <filesystem>
#include <random>
#include <string>

#include <nlohmann/json.hpp>

#include "demfit/identify/analytic_model.hpp"
#include "demfit/identify/study.hpp"
#include "demfit/identify/study_spec.hpp"

namespace demfit::identify::test {

// A fresh folder under the build tree, removed first if it exists.
inline std::filesystem::path fresh_dir(const std::string& name) {
  const auto dir = std::filesystem::path(DEMFIT_BINARY_DIR) / "test_output" / "identify" / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

// Run options of a test study: output in `dir`, no plots, no progress lines.
inline RunOptions quiet_options(const std::filesystem::path& dir, int jobs = 1) {
  RunOptions options;
  options.output_dir = dir;
  options.jobs = jobs;
  options.plots = false;
  options.progress = false;
  return options;
}

// Study JSON identifying amplitude and rate of AnalyticCurveModel from its "response" curve at
// the true values (1.3, 4.2), optional Gaussian noise of `noise` x max|y|.
inline nlohmann::json analytic_study(double noise = 0.0, int max_iterations = 12, unsigned seed = 7) {
  AnalyticCurveModel model;
  const auto curves = model.evaluate({{"amplitude", 1.3}, {"rate", 4.2}}, {});
  Curve target = curves.at("response");
  double ymax = 0;
  for (double y : target.y) ymax = std::max(ymax, std::abs(y));
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  for (double& y : target.y) y += noise * ymax * normal(rng);
  return {{"demfit_study_version", 1},
          {"name", "analytic"},
          {"model", {{"case", "analytic"}}},
          {"variables",
           {{{"name", "amplitude"}, {"lower", 0.5}, {"upper", 2.0}, {"initial", 1.0}},
            {{"name", "rate"}, {"lower", 1.0}, {"upper", 8.0}, {"initial", 3.0}, {"log_scale", true}}}},
          {"targets",
           {{{"curve", "response"}, {"x_column", "x_1"}, {"y_column", "y_1"}, {"x", target.x}, {"y", target.y}}}},
          {"stopping", {{"max_iterations", max_iterations}, {"design_tolerance", 0.0}, {"objective_tolerance", 0.0}}},
          {"seed", 11}};
}

// Thrown from a run's completion callback to stop a study where a kill would; not a
// std::exception, so nothing in the loop can swallow it.
struct SimulatedKill {};

}  // namespace demfit::identify::test
